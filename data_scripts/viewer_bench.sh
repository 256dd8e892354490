#!/bin/sh
# The viewer's responsiveness on one model, under a virtual X display:
# for each --preview mode, frames and CPU while idle, preview frames a second
# during a 4-second left drag driven by xdotool, and the time from the last
# motion to the exact frame; screenshots (status line on) of each mode's
# preview 2 s into the drag (preview.png for lowres, preview-MODE.png), and
# with lowres of the exact image after the drag (exact.png) and the help
# overlay (help.png).
#
# Usage: xvfb-run -a -s "-screen 0 1280x1100x24" data_scripts/viewer_bench.sh MODEL OUTDIR [WxH] [MODES]
#   OIT_BIN: the tools (default build/bin); WxH default 1024x1024 (oitstream's
#   default --size); MODES default "lowres wboit unsorted off".
# Prints a markdown table on stdout; screenshots land in OUTDIR.
set -u
MODEL=${1:?usage: viewer_bench.sh MODEL OUTDIR [WxH] [MODES]}
OUT=${2:?usage: viewer_bench.sh MODEL OUTDIR [WxH] [MODES]}
SIZE=${3:-1024x1024}
MODES=${4:-lowres wboit unsorted off}
BIN=${OIT_BIN:-build/bin}
S=$(cd "$BIN" && pwd)/oitstream
MODEL=$(cd "$(dirname "$MODEL")" && pwd)/$(basename "$MODEL")
[ -n "${DISPLAY:-}" ] || { echo "viewer_bench: no DISPLAY (run under xvfb-run)" >&2; exit 2; }
command -v xdotool >/dev/null || { echo "viewer_bench: xdotool missing (setup/install-deps.sh)" >&2; exit 2; }
mkdir -p "$OUT" && OUT=$(cd "$OUT" && pwd)
WORK=$(mktemp -d) && cd "$WORK" || exit 1
trap 'rm -rf "$WORK"' EXIT
TICKS=$(getconf CLK_TCK)
W=${SIZE%x*}
H=${SIZE#*x}

num() { sed -n "s/.*\"$1\": \([-0-9.e+]*\).*/\1/p" st.json | head -n 1; }
now_ms() { date +%s%3N; }
cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
until_stat() { # NAME MIN SECONDS
    n=$(($3 * 100))
    while [ "$n" -gt 0 ]; do
        [ -f st.json ] && [ "$(num "$1")" -ge "$2" ] 2>/dev/null && return 0
        sleep 0.01
        n=$((n - 1))
    done
    return 1
}
shots() { grep -c "^viewer: screenshot" log.txt; }
until_shots() { n=1000; while [ "$(shots)" -lt "$1" ] && [ $n -gt 0 ]; do sleep 0.01; n=$((n - 1)); done; }

echo "$(basename "$MODEL") at $SIZE, $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| preview | first exact frame ms | idle 5 s: frames, CPU s | drag: preview frames/s (scale) | exact ms when still | last motion -> exact shown ms |"
echo "|---|---|---|---|---|---|"
for mode in $MODES; do
    rm -f st.json log.txt oitstream_*.png
    "$S" "$MODEL" --window --size "$SIZE" --preview "$mode" --stats st.json >log.txt 2>&1 &
    PID=$!
    until_stat exact_frames 1 600 || { cat log.txt >&2; echo "viewer_bench: $mode: no first frame" >&2; kill "$PID"; continue; }
    WIN=$(timeout 30 xdotool search --sync --pid "$PID" | head -n 1)
    first=$(num last_exact_ms)
    sleep 1
    f0=$(num frames_rendered); c0=$(cpu_ticks "$PID")
    sleep 5
    f1=$(num frames_rendered); c1=$(cpu_ticks "$PID")
    idle_cpu=$(awk "BEGIN{printf \"%.2f\", ($c1 - $c0) / $TICKS}")
    # a 4 s drag: a step every 40 ms, around a circle so the view keeps changing
    p0=$(num preview_frames); e0=$(num exact_frames)
    xdotool mousemove --window "$WIN" $((W / 2)) $((H / 2)) mousedown 1
    t0=$(now_ms); i=0; shot=0
    while [ $(( $(now_ms) - t0 )) -lt 4000 ]; do
        i=$((i + 1))
        x=$(awk "BEGIN{printf \"%d\", $W / 2 + $W / 6 * cos($i / 8)}")
        y=$(awk "BEGIN{printf \"%d\", $H / 2 + $H / 10 * sin($i / 8)}")
        xdotool mousemove --window "$WIN" "$x" "$y"
        if [ "$mode" != off ] && [ $shot -eq 0 ] && [ $(( $(now_ms) - t0 )) -ge 2000 ]; then
            xdotool key --window "$WIN" g # the preview, as the window shows it
            shot=1
        fi
        sleep 0.04
    done
    t1=$(now_ms)
    xdotool mouseup 1
    p1=$(num preview_frames)
    scale=$(num preview_scale)
    until_stat exact_frames $((e0 + 1)) 60
    t2=$(now_ms)
    exact_ms=$(num last_exact_ms); exact_ms=${exact_ms%.*}
    fps=$(awk "BEGIN{printf \"%.1f\", ($p1 - $p0) * 1000 / ($t1 - $t0)}")
    [ "$mode" = lowres ] || scale=-
    [ "$mode" = off ] && fps="$(awk "BEGIN{printf \"%.1f\", ($(num exact_frames) - $e0 - 1) * 1000 / ($t1 - $t0)}") (exact)"
    [ "$mode" != off ] && until_shots 1
    if [ "$mode" != off ] && [ -f oitstream_000.png ]; then
        name=preview-$mode.png
        [ "$mode" = lowres ] && name=preview.png
        cp oitstream_000.png "$OUT/$name"
    fi
    if [ "$mode" = lowres ]; then
        sleep 0.5
        xdotool key --window "$WIN" g
        until_shots 2
        cp oitstream_001.png "$OUT/exact.png"
        xdotool key --window "$WIN" h g
        until_shots 3
        cp oitstream_002.png "$OUT/help.png"
    fi
    xdotool key --window "$WIN" q 2>/dev/null
    wait "$PID"
    grep "^viewer: .* frames rendered" log.txt >&2
    echo "| $mode | ${first%.*} | $((f1 - f0)), $idle_cpu | $fps ($scale) | $exact_ms | $((t2 - t1)) |"
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
