#!/bin/sh
# Issue 44's measure ("Never slower than in core"): the stream against DFB
# on the source mesh, as a user sees it (wall clock, llvmpipe's own
# threads), with the methods interleaved and medians over rounds.
#
# Per scene and size: two oblique views (oitstream's --orbit 2, elevation
# 20 deg, framing the source mesh), each drawn twice in one process; a run's
# figure is the median of its warm (second) frames. Each round runs the
# stream (`oitstream M.oitp --epsilon 0`, default options on oitprep's
# default part file) and DFB (`oitstream MESH --method dfb`), alternating
# which goes first; the table gives the median over the rounds of each and
# stream / DFB of the medians, each round's ratio beside it, the stream's
# host_waits on warm frames (the most of any; "-" where this oitstream does
# not report it), the paths its warm frames took, and the worst warm
# frame's share of pixels off by more than 1/255 against DFB (the issue's
# bar: <= 0.01%).
#
# Then the one-image runs (whole process wall time of `oitstream M.oitp
# --out F.png` against `oitstream MESH --method dfb --out F.png`, as a user
# runs them once; NS_ONE_ROUNDS rounds interleaved, medians) and oitbench's
# stream / DFB / unsorted on the 1M plant at 512x512.
#
# Scenes (NS_SCENES picks some):
#   stack80     300 unit squares 0.01 apart (alpha 0.12) crossed by 50 long
#               slivers (700 triangles, ~80 layers from 20 deg): the
#               issue's stack (data_scripts/stack_slivers.py)
#   hardstack   oitgen hard --case stack (600 squares)
#   plant1M     oitgen plant --triangles 1000000
#   cad332K     18 copies of turbine.off (332,280 triangles; oitgen instances)
#   2CylinderEngine.glb, head.stl   fetched meshes (data_scripts/cache)
#
# Usage: data_scripts/never_slower.sh [BINDIR] [OUT.md]
#   defaults: build/bin, bench/never-slower-$(hostname).md
# Knobs: NS_ROUNDS (3), NS_SIZES ("1024x1024 128x128"), NS_SCENES,
#   NS_ONE_ROUNDS (5), NS_ONE ("demo fandisk.off turbine.off"; "" skips),
#   NS_BENCH=0 skips oitbench, NS_STREAM_ARGS (extra stream options).
# Exits non-zero naming the scene and step when a tool fails.
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin}
out=${2:-bench/never-slower-$(hostname).md}
here=$(cd "$(dirname "$0")" && pwd)
cache=${OIT_MESH_CACHE:-$here/cache}
rounds=${NS_ROUNDS:-3} one_rounds=${NS_ONE_ROUNDS:-5}
sizes=${NS_SIZES:-1024x1024 128x128}
scenes=${NS_SCENES:-stack80 hardstack plant1M cad332K 2CylinderEngine.glb head.stl}
one=${NS_ONE-demo fandisk.off turbine.off}
sargs=${NS_STREAM_ARGS:-}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
cmdline="$0 $*"

die() { echo "never_slower: $*" >&2; exit 1; }
for t in oitgen oitprep oitstream oitbench; do
    [ -x "$bin/$t" ] || die "$bin/$t: missing (make build)"
done
work=$(mktemp -d /tmp/never_slower.XXXXXX)
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

med() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) { print "-"; exit }
    if (NR % 2) printf "%.1f\n", v[(NR + 1) / 2]; else printf "%.1f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
warm_ms() { grep -o '"ms": [-0-9.]*' "$1" | sed 's/.*: //' | awk 'NR % 2 == 0' | med; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "-" }'; }
now_ms() { date +%s%N | awk '{ printf "%.1f\n", $1 / 1e6 }'; }
# The warm frames' values of an integer key, the most; "-" when absent.
warm_max() { grep -o "\"$1\": [0-9]*" "$2" | sed 's/.*: //' | awk 'NR % 2 == 0' |
    awk '{ if ($1 > m) m = $1; n++ } END { if (n) print m + 0; else print "-" }'; }
# The warm frames' paths: capture (pack) names, distinct, in order.
warm_paths() { grep -o '"capture": "[^"]*"' "$1" | sed 's/.*: "//; s/"//' | awk 'NR % 2 == 0' |
    awk '!s[$0]++' | paste -sd/ -; }

mesh_of() { # scene -> path of its source mesh in $work
    case $1 in
    stack80) python3 "$here/stack_slivers.py" "$work/stack80.ply" >/dev/null &&
        echo "$work/stack80.ply" ;;
    hardstack) "$bin/oitgen" hard --case stack -o "$work/hardstack.ply" >/dev/null &&
        echo "$work/hardstack.ply" ;;
    plant1M) nice -n 5 "$bin/oitgen" plant --triangles 1000000 -o "$work/plant1M.ply" >/dev/null &&
        echo "$work/plant1M.ply" ;;
    cad332K) [ -f "$cache/turbine.off" ] || return 1
        "$bin/oitgen" instances --input "$cache/turbine.off" --count 18 -o "$work/cad332K.ply" \
            >/dev/null && echo "$work/cad332K.ply" ;;
    demo) "$bin/oitgen" demo -o "$work/demo.ply" >/dev/null && echo "$work/demo.ply" ;;
    *) [ -f "$cache/$1" ] && echo "$cache/$1" ;;
    esac
}

# run NAME FILE SIZE OUTDIR [options]: oitstream along the walk.
run() {
    rn=$1 rf=$2 rs=$3 rd=$4; shift 4
    rm -rf "$rd" && mkdir -p "$rd"
    # shellcheck disable=SC2086
    "$bin/oitstream" "$rf" --walk "$work/walk.txt" --size "$rs" --out "$rd/" \
        --stats "$rd.json" --quiet "$@" || die "$rn: oitstream $rf $* failed"
    [ "$(grep -c '"ms":' "$rd.json")" = 4 ] || die "$rn: not 4 frames in $rd.json"
}

worst_off() { # dirA dirB -> worst warm pct over 1/255
    w=0
    for fr in frame_001.png frame_003.png; do
        j=$("$bin/oitstream" --compare "$1/$fr" "$2/$fr" --json) || die "compare $1/$fr failed"
        p=$(echo "$j" | sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
        w=$(awk -v a="$w" -v b="$p" 'BEGIN { print (b > a ? b : a) }')
    done
    printf '%.4f' "$w"
}

rows=$work/rows
: >"$rows"
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
for sc in $scenes; do
    m=$(mesh_of "$sc") || { echo "never_slower: $sc: no mesh (fetch_meshes.sh?), skipped" >&2; continue; }
    echo "== $sc" >&2
    "$bin/oitstream" "$m" --method unsorted --orbit 2 --size 16x16 --out "$work/v/" \
        --stats "$work/v.json" --quiet || die "$sc: framing the views failed"
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | awk '{ print; print }' >"$work/walk.txt"
    tris=$(sed -n 's/.*"triangles": \([0-9]*\).*/\1/p' "$work/v.json" | head -n 1)
    nice -n 5 "$bin/oitprep" "$m" -o "$work/m.oitp" >"$work/prep.log" 2>&1 ||
        { cat "$work/prep.log" >&2; die "$sc: oitprep failed"; }
    for size in $sizes; do
        : >"$work/s.ms"; : >"$work/d.ms"; : >"$work/ratios"
        r=1
        while [ "$r" -le "$rounds" ]; do
            if [ $((r % 2)) = 1 ]; then
                # shellcheck disable=SC2086
                run "$sc stream" "$work/m.oitp" "$size" "$work/s$r" --epsilon 0 $sargs
                run "$sc dfb" "$m" "$size" "$work/d$r" --method dfb
            else
                run "$sc dfb" "$m" "$size" "$work/d$r" --method dfb
                # shellcheck disable=SC2086
                run "$sc stream" "$work/m.oitp" "$size" "$work/s$r" --epsilon 0 $sargs
            fi
            sm=$(warm_ms "$work/s$r.json") dm=$(warm_ms "$work/d$r.json")
            echo "$sm" >>"$work/s.ms"; echo "$dm" >>"$work/d.ms"
            ratio "$sm" "$dm" >>"$work/ratios"; echo >>"$work/ratios"
            r=$((r + 1))
        done
        sm=$(med <"$work/s.ms") dm=$(med <"$work/d.ms")
        off=$(worst_off "$work/s1" "$work/d1")
        waits=$(warm_max host_waits "$work/s1.json")
        paths=$(warm_paths "$work/s1.json")
        row="| $sc | $tris | $size | $sm | $dm | $(ratio "$sm" "$dm") | $(paste -sd' ' "$work/ratios") | $waits | $paths | $off |"
        echo "$row" >>"$rows"
        echo "$row" >&2
        r=1
        while [ "$r" -le "$rounds" ]; do rm -rf "$work/s$r" "$work/d$r"; r=$((r + 1)); done
    done
    rm -f "$work/m.oitp"
    case $m in "$work"/*) rm -f "$m" ;; esac
done

# One image a process, as a user runs it once.
onerows=$work/onerows
: >"$onerows"
for sc in $one; do
    m=$(mesh_of "$sc") || { echo "never_slower: $sc: no mesh, skipped" >&2; continue; }
    "$bin/oitprep" "$m" -o "$work/one.oitp" >/dev/null 2>&1 || die "$sc: oitprep failed"
    : >"$work/os"; : >"$work/od"
    r=1
    while [ "$r" -le "$one_rounds" ]; do
        for w in s d; do
            [ $((r % 2)) = 1 ] || w=$(echo "$w" | tr sd ds)
            t0=$(now_ms)
            if [ "$w" = s ]; then
                "$bin/oitstream" "$work/one.oitp" --epsilon 0 --size 1024x1024 \
                    --out "$work/one_s.png" --quiet || die "$sc: one-image stream failed"
            else
                "$bin/oitstream" "$m" --method dfb --size 1024x1024 \
                    --out "$work/one_d.png" --quiet || die "$sc: one-image dfb failed"
            fi
            t1=$(now_ms)
            awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f\n", b - a }' >>"$work/o$w"
        done
        r=$((r + 1))
    done
    os=$(med <"$work/os") od=$(med <"$work/od")
    echo "| $sc | $os | $od | $(ratio "$os" "$od") |" >>"$onerows"
    tail -n 1 "$onerows" >&2
    case $m in "$work"/*) rm -f "$m" ;; esac
done

# oitbench on the 1M plant at 512x512.
bench=""
if [ "${NS_BENCH:-1}" != 0 ]; then
    m=$(mesh_of plant1M) || die "plant1M failed"
    nice -n 0 "$bin/oitbench" "$m" --methods stream,dfb,unsorted --orbit 2 --size 512x512 \
        --out "$work/bench" >"$work/bench.log" 2>&1 || { cat "$work/bench.log" >&2; die "oitbench failed"; }
    # results.csv: a "summary" row a method (the median over its views),
    # the method in column "method"
    col() { awk -F, -v k="$1" 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == k) c = i
            if ($i == "method") m = i }; next }
        $1 == "summary" { print $m "," $c }' "$work/bench/results.csv"; }
    bs=$(col ms_median | awk -F, '$1 == "stream" { print $2; exit }')
    bd=$(col ms_median | awk -F, '$1 == "dfb" { print $2; exit }')
    bu=$(col ms_median | awk -F, '$1 == "unsorted" { print $2; exit }')
    [ -n "$bs" ] && [ -n "$bd" ] && [ -n "$bu" ] ||
        die "oitbench: no summary rows for stream, dfb and unsorted in results.csv"
    bench="| $bs | $bd | $bu | $(ratio "$bs" "$bd") | $(ratio "$bs" "$bu") |"
fi

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?')
git -C "$here" diff --quiet HEAD -- 2>/dev/null || commit="$commit (+ uncommitted changes)"
{
    echo "# Never slower than in core (issue 44): the stream against DFB on the source mesh"
    echo
    echo "Machine: $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1);"
    echo "load average at the start $load_start, at the end $(cut -d' ' -f1-3 /proc/loadavg)."
    echo "GL: $(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/v.json" 2>/dev/null | head -n 1)."
    echo "Commit: $commit; tools from $bin. Command: \`$cmdline\`"
    env | grep '^NS_' | sed 's/^/  env: /' || true
    echo
    echo "Two views at elevation 20 deg, each drawn twice a process; a run's ms = median of its warm"
    echo "frames; $rounds rounds, stream and DFB alternating which runs first; ms = median over rounds."
    echo "host_waits: the most of the stream's warm frames (\"-\": not reported by this build)."
    echo "paths: the captures of the stream's warm frames. off %: worst warm frame, pixels off by > 1/255 against DFB."
    echo
    echo "| scene | triangles | size | stream ms | DFB ms | stream / DFB | each round | host_waits | paths | off % |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    cat "$rows"
    if [ -s "$onerows" ]; then
        echo
        echo "## One image a process (1024x1024, wall ms of the whole process, median of $one_rounds interleaved rounds)"
        echo
        echo "| scene | stream ms | DFB ms | stream / DFB |"
        echo "|---|---|---|---|"
        cat "$onerows"
    fi
    if [ -n "$bench" ]; then
        echo
        echo "## oitbench plant1M --methods stream,dfb,unsorted --orbit 2 --size 512x512 (ms_median)"
        echo
        echo "| stream ms | DFB ms | unsorted ms | stream / DFB | stream / unsorted |"
        echo "|---|---|---|---|---|"
        echo "$bench"
    fi
} >"$out"
cat "$out"
