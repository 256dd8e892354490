#!/bin/sh
# Issue 44 item 2: does --pack auto's measured choice (view/stream/choice.h) end
# where the faster path is? Per scene and size, one view seen from 20 degrees
# above (oitstream's default framing of the source mesh), FRAMES frames of it
# in one process, for: the stream's default (auto), --pack first-k, --pack
# counted, and DFB in core on the source mesh. The methods run interleaved,
# ROUNDS rounds; a run's figure is the median wall ms of its frames after the
# first (auto's probes included: a user pays them), the table the median
# over rounds. auto's column also gives the paths its frames took (f:
# first-k, c: counted) in the last round. Every run's last frame is checked
# against DFB's (1/255 on >= 99.99% of pixels), else the script fails.
#
# Usage: data_scripts/choice_bench.sh [BINDIR] [OUT.md]
#   defaults: build/bin, bench/choice-$(hostname).md
# Knobs: CHOICE_SCENES="issue_stack hard_stack plant1M", CHOICE_SIZES="512x512
# 1024x1024", CHOICE_FRAMES=5, CHOICE_ROUNDS=3, CHOICE_OFF_PCT=0.01 (the
# most pixels off by more than 1/255, %), CHOICE_KEEP=DIR (keep the
# work folder).
set -eu
bin=${1:-build/bin}
out=${2:-bench/choice-$(hostname).md}
here=$(cd "$(dirname "$0")" && pwd)
scenes=${CHOICE_SCENES:-issue_stack hard_stack plant1M}
sizes=${CHOICE_SIZES:-512x512 1024x1024}
frames=${CHOICE_FRAMES:-5} rounds=${CHOICE_ROUNDS:-3} off=${CHOICE_OFF_PCT:-0.01}
work=${CHOICE_KEEP:-$(mktemp -d /tmp/choice_bench.XXXXXX)}
mkdir -p "$work"
die() { echo "choice_bench: $*" >&2; exit 1; }
median() { sort -n | awk '{v[NR] = $1} END {if (NR == 0) print -1; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

make_scene() { # NAME -> $work/NAME.ply and .oitp
    case $1 in
    issue_stack) python3 "$here/stack_slivers.py" "$work/$1.ply" >/dev/null ;;
    hard_stack) "$bin/oitgen" hard --case stack -o "$work/$1.ply" >/dev/null ;;
    plant1M) "$bin/oitgen" plant -o "$work/$1.ply" >/dev/null ;;
    *) die "unknown scene $1" ;;
    esac || die "$1: cannot generate"
    "$bin/oitprep" "$work/$1.ply" -o "$work/$1.oitp" >"$work/$1.prep.txt" 2>&1 ||
        die "$1: oitprep: $(tail -n 1 "$work/$1.prep.txt")"
    "$bin/oitstream" "$work/$1.ply" --method unsorted --orbit 1 --size 16x16 --quiet \
        --stats "$work/$1.view.json" || die "$1: cannot frame the view"
    v=$(sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/$1.view.json")
    : >"$work/$1.walk"
    i=0
    while [ $i -lt "$frames" ]; do echo "$v" >>"$work/$1.walk"; i=$((i + 1)); done
}

run() { # SCENE SIZE METHOD ROUND -> the run's median ms on stdout
    d="$work/$1.$2.$3.$4"
    case $3 in
    auto) set -- "$1" "$2" "$3" "$4" "$work/$1.oitp" ;;
    first-k | counted) set -- "$1" "$2" "$3" "$4" "$work/$1.oitp" --pack "$3" ;;
    dfb) set -- "$1" "$2" "$3" "$4" "$work/$1.ply" --method dfb ;;
    esac
    s=$1 z=$2 m=$3
    shift 4
    nice -n 10 "$bin/oitstream" "$@" --walk "$work/$s.walk" --size "$z" --quiet --out "$d/" \
        --stats "$d.json" >"$d.log" 2>&1 || die "$s $z $m: oitstream $*: $(tail -n 1 "$d.log")"
    grep -o '"ms": *[-0-9.]*' "$d.json" | sed 's/.*: *//' | tail -n +2 | median
}

last=$(printf 'frame_%03d.png' $((frames - 1)))
for s in $scenes; do make_scene "$s"; done
{
    echo "# --pack auto's measured choice against fixed packs and DFB (llvmpipe)"
    echo
    echo "\`data_scripts/choice_bench.sh\` ($(date -u +%Y-%m-%d), $(nproc) cores, $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?')):"
    echo "one view per scene from 20 degrees above (oitstream's default framing of the"
    echo "source mesh), $frames frames of it in one process; a run's figure is the median"
    echo "wall ms (--stats \"ms\") of its frames after the first, auto's probes included;"
    echo "methods interleaved, median over $rounds rounds. auto's paths: its frames in"
    echo "the last round (f first-k, c counted). DFB runs on the source mesh."
    echo
    echo "auto's costs: choice_first_k_ms / choice_counted_ms at its last frame in the"
    echo "last round, the least wall ms of each path's frames as auto measured them."
    echo
    echo "| scene | size | auto ms | first-k ms | counted ms | DFB ms | auto / best fixed | auto / DFB | auto's paths | auto's costs f / c |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
} >"$work/table.md"
for s in $scenes; do
    for z in $sizes; do
        : >"$work/$s.$z.auto" >"$work/$s.$z.first-k" >"$work/$s.$z.counted" >"$work/$s.$z.dfb"
        r=1
        while [ $r -le "$rounds" ]; do
            for m in auto first-k counted dfb; do
                ms=$(run "$s" "$z" "$m" "$r")
                echo "$ms" >>"$work/$s.$z.$m"
                echo "$s $z round $r $m: $ms ms" >&2
            done
            for m in auto first-k counted; do
                c=$("$bin/oitstream" --compare "$work/$s.$z.$m.$r/$last" \
                    "$work/$s.$z.dfb.$r/$last" --json 2>/dev/null || true)
                pct=$(echo "$c" | sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
                [ -n "$pct" ] && awk -v p="$pct" -v o="$off" 'BEGIN {exit !(p <= o)}' ||
                    die "$s $z $m round $r: last frame differs from DFB's ($pct% over 1/255)"
            done
            r=$((r + 1))
        done
        a=$(median <"$work/$s.$z.auto") f=$(median <"$work/$s.$z.first-k")
        c=$(median <"$work/$s.$z.counted") d=$(median <"$work/$s.$z.dfb")
        j="$work/$s.$z.auto.$rounds.json"
        paths=$(grep -o '"choice": "[a-z-]*"' "$j" | sed 's/.*"first-k"/f/; s/.*"counted"/c/' |
            tr -d '\n')
        # the costs auto weighed at its last frame (its own measurements)
        cf=$(grep -o '"choice_first_k_ms": *[-0-9.]*' "$j" | tail -n 1 | sed 's/.*: *//')
        cc=$(grep -o '"choice_counted_ms": *[-0-9.]*' "$j" | tail -n 1 | sed 's/.*: *//')
        awk -v s="$s" -v z="$z" -v a="$a" -v f="$f" -v c="$c" -v d="$d" -v p="$paths" \
            -v cf="$cf" -v cc="$cc" 'BEGIN {
            b = f < c ? f : c
            printf "| %s | %s | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %s | %.0f / %.0f |\n", s, z, a, f, c, d, a / b, a / d, p, cf, cc
        }' >>"$work/table.md"
    done
done
mkdir -p "$(dirname "$out")"
cp "$work/table.md" "$out"
cat "$out"
[ -n "${CHOICE_KEEP:-}" ] || rm -rf "$work"
