#!/bin/sh
# The tie rule across methods and conversion (issue 20): on every hard case
# and every fetched mesh, three views (azimuth 30 and 210 at elevation 35,
# azimuth 120 at -25), the share of pixels off by more than 1/255 between
#   the stream on the part file (oitprep, SCHEME) and DFB on the source mesh,
#   the stream and the Embree reference on the source mesh,
#   DFB and the reference, both on the source mesh,
# each outside the reference's ambiguity mask (pixel centres on triangle
# edges; with an older build the mask also covered depth ties) and, in
# brackets, on every pixel. Goal: <= 0.1% outside the mask.
#
#   data_scripts/ties.sh [BIN [OUT.md]]     BIN default build/bin
#   TIES_SIZE=384x384  TIES_SCHEME=fast|guaranteed  TIES_MODELS="coplanar fandisk.off"
#   TIES_GEN=DIR: oitgen from DIR (to run an older build on today's cases)
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/bin}
out=${2:-}
size=${TIES_SIZE:-384x384}
scheme=${TIES_SCHEME:-fast}
cache=${OIT_MESH_CACHE:-$here/cache}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
for t in oitgen oitprep oitstream; do
    [ -x "$bin/$t" ] || { echo "ties.sh: $bin/$t: missing (nice make build)" >&2; exit 1; }
done
models=${TIES_MODELS:-}
if [ -z "$models" ]; then
    models=$("${TIES_GEN:-$bin}/oitgen" --help | sed -n 's/^  *\(coplanar[a-z_]*\|rings\|sticks\|moebius\|degenerate\|nearflat\|far\|tiny\|thin\|nonmanifold\|stack\|dense\|decal\|touching\)  .*/\1/p' | tr '\n' ' ')
    for f in "$cache"/*; do
        case $f in *.off|*.stl|*.obj|*.ply|*.glb|*.gltf) models="$models $(basename "$f")" ;; esac
    done
fi
work=$(mktemp -d /tmp/ties.XXXXXX)
trap 'rm -rf "$work"' EXIT
pct() { # A B [MASK]
    if [ $# -eq 3 ]; then
        "$bin/oitstream" --compare "$1" "$2" --mask "$3" --json |
            sed -n 's/.*"pct_over_1_255_outside_mask": *\([-0-9.e+]*\).*/\1/p'
    else
        "$bin/oitstream" --compare "$1" "$2" --json | sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p'
    fi
}
rows="$work/rows"
: >"$rows"
worst=0
for m in $models; do
    src="$work/in.ply"
    case $m in
    *.*) src="$cache/$m"; [ -f "$src" ] || { echo "ties.sh: $src: missing (make fetch)" >&2; continue; } ;;
    *) "${TIES_GEN:-$bin}/oitgen" hard --case "$m" -o "$src" >/dev/null || { echo "ties.sh: oitgen $m failed" >&2; continue; } ;;
    esac
    "$bin/oitprep" "$src" -o "$work/in.oitp" --scheme "$scheme" >"$work/prep.txt" 2>&1 ||
        { echo "ties.sh: oitprep $m: $(tail -n 1 "$work/prep.txt")" >&2; continue; }
    for v in "30 35" "210 35" "120 -25"; do
        az=${v% *} el=${v#* }
        o="--size $size --azimuth $az --elevation $el --quiet"
        # One camera for all three: the stream's, framed on the part file.
        "$bin/oitstream" "$work/in.oitp" --method stream $o --out "$work/st.pfm" \
            --stats "$work/st.json" || { echo "ties.sh: $m view $v: stream failed" >&2; continue; }
        cam=$(sed -n 's/.*"view": *"\([^"]*\)".*/\1/p' "$work/st.json" | head -n 1)
        o="--size $size --view $cam --quiet"
        "$bin/oitstream" "$src" --method dfb $o --out "$work/dfb.pfm" &&
            "$bin/oitstream" "$src" --method reference $o --out "$work/ref.pfm" \
                --ambiguity "$work/mask.png" || { echo "ties.sh: $m view $v failed" >&2; continue; }
        a=$(pct "$work/st.pfm" "$work/dfb.pfm" "$work/mask.png") A=$(pct "$work/st.pfm" "$work/dfb.pfm")
        b=$(pct "$work/st.pfm" "$work/ref.pfm" "$work/mask.png") B=$(pct "$work/st.pfm" "$work/ref.pfm")
        c=$(pct "$work/dfb.pfm" "$work/ref.pfm" "$work/mask.png") C=$(pct "$work/dfb.pfm" "$work/ref.pfm")
        printf '| %s | %s/%s | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f) |\n' "$m" "$az" "$el" \
            "$a" "$A" "$b" "$B" "$c" "$C" | tee -a "$rows"
        worst=$(awk "BEGIN{print ($a > $worst ? $a : $worst)}")
        worst=$(awk "BEGIN{print ($b > $worst ? $b : $worst)}")
        worst=$(awk "BEGIN{print ($c > $worst ? $c : $worst)}")
    done
done
{
    echo "Tie rule, $scheme scheme, $size, tools from $bin"
    echo "($0 $bin; $(date -u +%Y-%m-%d); commit $(git -C "$here" rev-parse --short HEAD 2>/dev/null))"
    echo
    echo "% of pixels off by more than 1/255 outside the reference's ambiguity mask (on every pixel)"
    echo
    echo "| model | view az/el | stream (part file) vs DFB (mesh) | stream vs reference (mesh) | DFB (mesh) vs reference (mesh) |"
    echo "|---|---|---|---|---|"
    cat "$rows"
    echo
    echo "Worst outside the mask: $worst% (goal <= 0.1%)"
} >"$work/table.md"
if [ -n "$out" ]; then cp "$work/table.md" "$out"; echo "ties.sh: wrote $out"; else cat "$work/table.md"; fi
