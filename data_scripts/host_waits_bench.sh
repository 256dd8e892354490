#!/bin/sh
# The stream's default path before and after a change, on part files made
# from the same meshes: one view (azimuth 0, elevation 20: oitstream's
# default framing) drawn FRAMES times a process, the builds interleaved
# over ROUNDS rounds (the order flipped each round); per round the median
# of the warm frames' wall ms (frames 2..FRAMES of --stats), then the
# median over rounds; and each build's host_waits, redraws and path
# (auto_first_k) per frame from its first round ("-": not reported by that
# build). Markdown on stdout, progress on stderr.
# usage: host_waits_bench.sh BEFORE_BIN AFTER_BIN SIZE FILE.oitp... 
#   (env ROUNDS, default 3; FRAMES, default 4)
set -eu
[ $# -ge 4 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN SIZE FILE.oitp..." >&2; exit 2; }
before=$1 after=$2 size=$3
shift 3
rounds=${ROUNDS:-3} frames=${FRAMES:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
all() { grep -o "\"$1\": *[-0-9.e+]*" "$2" | sed 's/.*: *//' | paste -sd' ' -; }
med() { sort -g | awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
warm_ms() { all ms "$1" | tr ' ' '\n' | sed 1d | med; }
run() { # BIN FILE OUT.json
    "$1/oitstream" "$2" --size "$size" --walk "$work/walk.txt" --quiet --out "$work/img/" \
        --stats "$3" >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
}
echo "| file | size | build | warm ms, each round | median | host_waits per frame | redraws | first-k |"
echo "|---|---|---|---|---|---|---|---|"
for f in "$@"; do
    "$after/oitstream" "$f" --method unsorted --size 16x16 --out "$work/v/" --stats "$work/v.json" \
        --quiet >/dev/null
    v=$(sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | head -n 1)
    i=0
    : >"$work/walk.txt"
    while [ $i -lt "$frames" ]; do echo "$v" >>"$work/walk.txt"; i=$((i + 1)); done
    : >"$work/b.ms"; : >"$work/a.ms"
    r=1
    while [ $r -le "$rounds" ]; do
        echo "== $(basename "$f") round $r" >&2
        if [ $((r % 2)) = 1 ]; then order="b a"; else order="a b"; fi
        for w in $order; do
            bin=$before; [ $w = a ] && bin=$after
            run "$bin" "$f" "$work/$w$r.json"
            warm_ms "$work/$w$r.json" >>"$work/$w.ms"
        done
        r=$((r + 1))
    done
    for w in b a; do
        name=before; [ $w = a ] && name=after
        waits=$(all host_waits "$work/${w}1.json"); redraws=$(all redraws "$work/${w}1.json")
        echo "| $(basename "$f") | $size | $name | $(paste -sd' ' "$work/$w.ms") |" \
             "$(med <"$work/$w.ms") | ${waits:--} | ${redraws:--} |" \
             "$(all auto_first_k "$work/${w}1.json") |"
    done
done
