#!/bin/sh
# Early termination against exact (issue 23): per case, in one run and with
# the same views, DFB on the source mesh (the user's alternative), the exact
# stream (--epsilon 0) and the stream at E = 1/510, 1/255 and 0.01, all with
# oitstream's default options (the part file of oitprep's default scheme).
#
# Cases: the 600-square stack seen head on (oitgen hard --case stack), a
# plant seen end on from outside and from inside a hall (oitgen plant), then
# every fetched mesh, the demo and the 1M plant from an orbit of views
# (elevation 20, as oitstream frames the mesh). Each view is in the walk
# file EPS_REPEAT times in a row; its first frame is cold, the others warm;
# ms = median of the warm frames. With --epsilon the streamer tries
# front-first packs on the first frame and every 8th (streamer.h), so the
# warm median is mostly plain packs; all_ms, the mean of every frame, counts
# those tries too.
#
# Columns per case and E:
#   ms, x exact (stream at E over the exact stream, warm medians), all
#     frames x exact (the same of every frame's mean, cold and front-first
#     tries included), x DFB;
#   saved %: 1 - ms / exact ms; behind %: the share of the exact frame's
#     fragments that reach a pixel already below E in every channel, counted
#     by the Embree reference (oitstream --method reference --epsilon E,
#     stats fragments_saturated) on the first view: what a per-fragment
#     early termination would drop; the issue asks saved >= behind / 2;
#   kept %: the stream's fragments against the exact stream's;
#   skipped: parts neither uploaded nor drawn (sum over the warm frames),
#     uploaded MB (cold frames included);
#   max_abs: the first view's float image (PFM, before 8-bit rounding)
#     against the exact stream's; steps: the most 8-bit steps any pixel of
#     any view moved (PNG). E = 1/510 must keep max_abs <= 1/510 and steps
#     <= 1.
#
# Usage: data_scripts/epsilon.sh [BINDIR] [OUT.md] [WxH]
#   defaults: build/bin, bench/epsilon-$(hostname).md, 1024x1024
# Knobs (environment):
#   EPS_PLANT=12000000   triangles of the end-on and hall plant
#   EPS_VIEWS=3          orbit views of the other cases
#   EPS_REPEAT=2         frames of each view (>= 2)
#   EPS_CASES="stack hall end demo bunny00.off"  these cases only (a mesh
#                        of data_scripts/cache by name, or demo, plant1M)
# Exits non-zero, naming the case and step, when a render or comparison
# fails.
set -eu
bin=${1:-build/bin} size=${3:-1024x1024}
out=${2:-bench/epsilon-$(hostname).md}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/models.sh"
cache=${OIT_MESH_CACHE:-$here/cache}
plant=${EPS_PLANT:-12000000} views=${EPS_VIEWS:-3} repeat=${EPS_REPEAT:-2}
[ "$repeat" -ge 2 ] 2>/dev/null || { echo "epsilon.sh: EPS_REPEAT must be >= 2" >&2; exit 2; }
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
cmdline="$0 $*"
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
EPS="0.00196078 0.00392157 0.01"

die() { echo "epsilon.sh: $*" >&2; exit 1; }
for t in oitstream oitprep oitgen oit_meshinfo; do
    [ -x "$bin/$t" ] || die "$bin/$t is missing: build first (make build)"
done
S="$bin/oitstream"

# Per-frame values of a stats key, one a line.
frames() { grep -o "\"$1\": [-0-9.e+]*" "$2" | sed 's/.*: //'; }
# Median of the warm (even-numbered) frames' ms.
warm_ms() { frames ms "$1" | awk -v r="$repeat" '(NR - 1) % r' | sort -g | awk '{v[NR] = $1} END {
    if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2];
    else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
sum_warm() { frames "$1" "$2" | awk -v r="$repeat" '(NR - 1) % r {s += $1} END {print s + 0}'; }
mean_all() { frames ms "$1" | awk '{s += $1} END {print NR ? s / NR : "nan"}'; }
sum_all() { frames "$1" "$2" | awk '{s += $1} END {print s + 0}'; }
num() { sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" | head -n 1; }

bounds() { "$bin/oit_meshinfo" "$1" | awk '/^bounds/ {print $2, $3, $4, $5, $6, $7}'; }

# A walk file with every view of $1 (a --view per line) EPS_REPEAT times.
repeated() { awk -v r="$repeat" '{for (i = 0; i < r; i++) print}' "$1" > "$2"; }

# The views of an orbit as oitstream frames the mesh, from a cheap run.
orbit_views() {
    "$S" "$1" --method unsorted --size 64x64 --orbit "$views" --out "$work/o" \
        --stats "$work/o.json" --quiet || die "$1: cannot frame the orbit"
    grep -o '"view": "[^"]*"' "$work/o.json" | sed 's/"view": "//; s/"$//' > "$2"
}

# Stack head on; the plant end on (from beyond its -x end, looking along x,
# the whole yz section in view) and from inside (a hall a third along x, at
# a fifth of its height, looking along x).
special_view() {
    set -- "$1" $(bounds "$2")
    case $1 in
    stack) echo "0,0,5,0,0,0,0,1,0,18" ;;
    end) awk -v a="$2" -v b="$3" -v c="$4" -v d="$5" -v e="$6" -v f="$7" 'BEGIN {
        cy = (b + e) / 2; cz = (c + f) / 2; h = (e - b > f - c) ? e - b : f - c
        x = a - 1.5 * h; printf "%g,%g,%g,%g,%g,%g,0,1,0,40\n", x, cy, cz, d, cy, cz }' ;;
    hall) awk -v a="$2" -v b="$3" -v c="$4" -v d="$5" -v e="$6" -v f="$7" 'BEGIN {
        x = a + (d - a) / 3; y = b + (e - b) / 5; cz = (c + f) / 2
        printf "%g,%g,%g,%g,%g,%g,0,1,0,70\n", x, y, cz, d, y, cz }' ;;
    esac
}

source_of() {
    case $1 in
    stack) "$bin/oitgen" hard --case stack -o "$work/stack.ply" >/dev/null && echo "$work/stack.ply" ;;
    end | hall)
        [ -f "$work/plant.ply" ] ||
            "$bin/oitgen" plant --triangles "$plant" -o "$work/plant.ply" >/dev/null
        echo "$work/plant.ply" ;;
    demo) "$bin/oitgen" demo -o "$work/demo.ply" >/dev/null && echo "$work/demo.ply" ;;
    plant*) "$bin/oitgen" plant --triangles "${1#plant}" -o "$work/$1.ply" >/dev/null &&
        echo "$work/$1.ply" ;;
    *) [ -f "$cache/$1" ] && echo "$cache/$1" ;;
    esac
}

cases=${EPS_CASES:-"stack end hall plant1000000 demo $OIT_FETCHED_MODELS"}

rows="$work/rows.md" renderer="?"
: > "$rows"

for c in $cases; do
    src=$(source_of "$c") || { echo "$c: not fetched, skipped" >&2; continue; }
    echo "$c ..." >&2
    part="$work/$(basename "$src").oitp"
    [ -f "$part" ] || "$bin/oitprep" "$src" -o "$part" >/dev/null 2>"$work/prep.err" ||
        die "$c: oitprep failed: $(cat "$work/prep.err")"
    case $c in
    stack | end | hall) special_view "$c" "$src" > "$work/views.txt"; nv=1 ;;
    *) orbit_views "$src" "$work/views.txt"; nv=$views ;;
    esac
    repeated "$work/views.txt" "$work/walk.txt"
    first=$(head -n 1 "$work/views.txt")
    "$S" "$src" --method dfb --size "$size" --walk "$work/walk.txt" --out "$work/dfb" \
        --stats "$work/dfb.json" --quiet || die "$c: dfb failed"
    dfb=$(warm_ms "$work/dfb.json")
    renderer=$(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/dfb.json" | head -n 1)
    for e in 0 $EPS; do
        "$S" "$part" --epsilon "$e" --size "$size" --walk "$work/walk.txt" --out "$work/s$e" \
            --stats "$work/s$e.json" --quiet || die "$c: stream E=$e failed"
        "$S" "$part" --epsilon "$e" --size "$size" --view "$first" --out "$work/s$e.pfm" \
            --quiet || die "$c: stream E=$e (float image) failed"
    done
    exact=$(warm_ms "$work/s0.json") exact_all=$(mean_all "$work/s0.json")
    f0=$(sum_warm fragments "$work/s0.json")
    for e in $EPS; do
        "$S" "$src" --method reference --epsilon "$e" --size "$size" --view "$first" \
            --out "$work/r.png" --stats "$work/r.json" --quiet || die "$c: reference E=$e failed"
        behind=$(awk -v s="$(frames fragments_saturated "$work/r.json")" \
            -v f="$(frames fragments "$work/r.json")" 'BEGIN {printf "%.1f", f ? 100 * s / f : 0}')
        ms=$(warm_ms "$work/s$e.json") all=$(mean_all "$work/s$e.json")
        kept=$(awk -v a="$(sum_warm fragments "$work/s$e.json")" -v b="$f0" \
            'BEGIN {printf "%.1f", b ? 100 * a / b : 0}')
        skipped=$(sum_warm parts_skipped "$work/s$e.json")
        up=$(awk -v b="$(sum_all bytes_uploaded "$work/s$e.json")" 'BEGIN {printf "%.1f", b / 1e6}')
        mabs=$("$S" --compare "$work/s$e.pfm" "$work/s0.pfm" --json | num max_abs) ||
            die "$c: E=$e compare failed"
        steps=0
        for f in "$work/s$e"/frame_*.png; do
            m=$("$S" --compare "$f" "$work/s0/$(basename "$f")" --json | num max_abs) ||
                die "$c: E=$e frame compare failed"
            steps=$(awk -v m="$m" -v s="$steps" 'BEGIN {v = int(m * 255 + 0.5); print (v > s) ? v : s}')
        done
        awk -v c="$c" -v nv="$nv" -v d="$dfb" -v x="$exact" -v e="$e" -v ms="$ms" \
            -v bh="$behind" -v kp="$kept" -v sk="$skipped" -v up="$up" -v ma="$mabs" \
            -v st="$steps" -v a="$all" -v xa="$exact_all" 'BEGIN {
            printf "| %s | %s | %.0f | %.0f | %s | %.0f | %.2f | %.2f | %.2f | %.1f | %s | %s | %s | %s | %.5f | %d |\n",
                c, nv, d, x, e, ms, ms / x, a / xa, ms / d, 100 * (1 - ms / x), bh, kp, sk, up, ma, st }' >> "$rows"
    done
done
mkdir -p "$(dirname "$out")"
{
    echo "# Early termination against exact, $size"
    echo
    echo "Machine: $(uname -m) ($(sed -n 's/^model name[^:]*: *//p' /proc/cpuinfo | head -n 1)), $(nproc) cores; GL: $renderer; $(date -u +%Y-%m-%d)."
    printf 'Command: `%s`\n\n' "$cmdline"
    echo "Columns: see the header of data_scripts/epsilon.sh. E = 1/510 (0.00196) is the"
    echo "point that may move no 8-bit value by more than one step."
    echo
    echo "| case | views | DFB ms | exact ms | E | ms | x exact | all frames x exact | x DFB | saved % | behind % | kept % | skipped | uploaded MB | max_abs | steps |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$rows"
} > "$out"
echo "wrote $out" >&2
