#!/bin/sh
# The fast scheme (oitprep --scheme fast, issue 17) against Wang & Xie's
# guaranteed scheme and DFB on the source mesh, per model: the demo, a 1M
# plant and every fetched mesh in the cache. Per model, in one run with the
# same views (an orbit of 4, elevation 20, each view rendered twice: the
# second, warm frame is timed, as a viewer sees a still view):
#   triangles in / out and parts of each scheme, conversion seconds,
#   stream ms (median of the 4 warm frames) of the fast scheme at each part
#   size of FAST_T (default 8192 32768 131072) and of the guaranteed scheme,
#   DFB on the source mesh (the user's alternative), and the worst share of
#   pixels off by > 1/255 between the fast stream (default part size) and DFB
#   on the source mesh.
# Usage: data_scripts/fast_scheme.sh [BINDIR] [OUT.md] [WxH]
# FAST_T: part sizes; FAST_PLANT: the plant's triangles (0: none);
# FAST_MODELS: cache files to take instead of all.
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin} out=${2:-bench/fast-scheme-$(hostname).md} size=${3:-512x512}
cache=${OIT_MESH_CACHE:-data_scripts/cache}
fast_t=${FAST_T:-8192 32768 131072}
# The T of the ratio, off % and DFB columns: oitprep's default (convert.h).
fast_d=${FAST_DEFAULT:-131072}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}

"$bin/oitgen" demo -o "$work/demo.ply" >/dev/null
models="$work/demo.ply"
plant=${FAST_PLANT:-1000000}
if [ "$plant" != 0 ]; then
    "$bin/oitgen" plant --triangles "$plant" -o "$work/plant$plant.ply" >/dev/null
    models="$models $work/plant$plant.ply"
fi
for m in ${FAST_MODELS:-$OIT_FETCHED_MODELS $OIT_FETCHED_DRACO}; do
    [ -f "$cache/$m" ] && models="$models $cache/$m"
done

num() { sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" "$2" | head -n 1; }
# Median of the warm (even-numbered, 2nd, 4th, ...) frames' ms of a stats file.
warm_ms() {
    grep -o '"ms": [0-9.]*' "$1" | sed 's/.*: //' | awk 'NR % 2 == 0' | sort -g |
        awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2];
                                   else printf "%.1f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
# Renders $1 along the walk with extra options; stats to $2, frames to $3/.
render() {
    f=$1 stats=$2 dir=$3; shift 3
    mkdir -p "$dir"
    nice -n 10 "$bin/oitstream" "$f" --walk "$work/walk.txt" --size "$size" "$@" \
        --out "$dir/" --stats "$stats" --quiet
}

mkdir -p "$(dirname "$out")"
{
    echo "# Fast scheme vs guaranteed scheme vs DFB on the source mesh"
    echo
    echo "Machine: $(uname -m), $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1);"
    echo "GL: the renderer line at the end. Size $size; 4 orbit views (elevation 20),"
    echo "each rendered twice, the second (warm: residency cache full) timed; ms = median of the 4 warm frames."
    echo "Command: \`data_scripts/fast_scheme.sh $bin $out $size\` (FAST_T=\"$fast_t\")"
    echo
    echo "fast T = --scheme fast --part-triangles T; \"fast\" columns at T = $fast_d. \"off %\" = worst"
    echo "view's share of pixels off by more than 1/255 between that stream and DFB on the source mesh."
    echo "conv s = oitprep wall seconds (2 threads); ratio T = triangles out / in at part size T."
    echo "Load average at the start: $(cut -d' ' -f1-3 /proc/loadavg) (the machine is shared)."
    echo
    h="| model | tris in | fast: tris out | ratio | parts | conv s | guaranteed: tris out | parts | conv s |"
    sep="|---|---|---|---|---|---|---|---|---|"
    for t in $fast_t; do h="$h stream fast $t ms |"; sep="$sep---|"; done
    for t in $fast_t; do h="$h ratio $t |"; sep="$sep---|"; done
    echo "$h stream guaranteed ms | DFB mesh ms | fast / DFB | off % |"
    echo "$sep---|---|---|---|"
} >"$out"

for m in $models; do
    name=$(basename "$m")
    echo "== $name" >&2
    # The views: an orbit as oitstream frames the source mesh, each twice.
    nice -n 10 "$bin/oitstream" "$m" --method dfb --orbit 4 --size 16x16 --out "$work/v/" \
        --stats "$work/v.json" --quiet
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | awk '{ print; print }' >"$work/walk.txt"
    "$bin/oitprep" "$m" -o "$work/g.oitp" --stats "$work/g.json" 2>/dev/null
    render "$work/g.oitp" "$work/gs.json" "$work/gi"
    render "$m" "$work/d.json" "$work/di" --method dfb
    row_t="" row_r=""
    for t in $fast_t; do
        "$bin/oitprep" "$m" -o "$work/f$t.oitp" --scheme fast --part-triangles "$t" \
            --stats "$work/f$t.json" 2>/dev/null
        render "$work/f$t.oitp" "$work/fs$t.json" "$work/fi$t"
        row_t="$row_t $(warm_ms "$work/fs$t.json") |"
        row_r="$row_r $(awk -v a="$(num triangles_out "$work/f$t.json")" \
            -v b="$(num triangles_in "$work/f$t.json")" 'BEGIN { printf "%.3f", a / b }') |"
    done
    off=0
    for i in 001 003 005 007; do
        p=$("$bin/oitstream" --compare "$work/fi$fast_d/frame_$i.png" "$work/di/frame_$i.png" --json |
            sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
        off=$(awk -v a="$off" -v b="$p" 'BEGIN { print (b > a ? b : a) }')
    done
    f=$work/f$fast_d.json g=$work/g.json
    tin=$(num triangles_in "$f")
    ratio=$(awk -v a="$(num triangles_out "$f")" -v b="$tin" 'BEGIN { printf "%.3f", a / b }')
    dms=$(warm_ms "$work/d.json")
    fms=$(warm_ms "$work/fs$fast_d.json")
    speed=$(awk -v a="$fms" -v b="$dms" 'BEGIN { printf "%.2f", a / b }')
    echo "| $name | $tin | $(num triangles_out "$f") | $ratio | $(num parts "$f") | $(num total "$f") |" \
        "$(num triangles_out "$g") | $(num parts "$g") | $(num total "$g") |$row_t$row_r" \
        "$(warm_ms "$work/gs.json") | $dms | $speed | $off |" >>"$out"
    tail -n 1 "$out" >&2
done
echo >>"$out"
echo "Renderer: $(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/d.json" | head -n 1)" >>"$out"
