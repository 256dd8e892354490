#!/bin/sh
# oitstream --window driven through real X events (xdotool under xvfb-run):
#   - idle: no frame is rendered and almost no CPU is used in 5 s, for a
#     mesh (dfb) and a part file (stream, with its reader thread);
#   - a left drag shows the preview (status "preview", a reduced-resolution
#     image), and after --still ms of stillness the exact image (status
#     "exact"), which equals `oitstream --out` of the view the window reports;
#   - H shows the help overlay (pixels change), H again hides it;
#   - G saves the window's image as shown (the preview, the help), P the
#     view rendered offscreen: the exact image even while the preview
#     shows, and no overlay;
#   - O, a typed path and Enter open another file (a part file: stream),
#     which idles too, and after a drag shows the headless stream's image;
#   - Q quits with exit status 0 and the counters on stdout.
# Equal means within half an 8-bit step (the window quantises to 8 bits).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
. "$(dirname "$0")/viewer_x11.sh"
S="$OIT_BIN/oitstream"
scratch viewer_interactive
cd "$T" || exit 1
W=200
H=150
EQUAL=0.002 # 0.5/255 plus float slack
STILL=4000  # ms: long enough to look at the preview under ASan, short enough to wait for
TICKS=$(getconf CLK_TCK)

cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
shots() { grep -c "^viewer: screenshot" log.txt; }
# idle NAME: nothing rendered, nothing presented, < 0.3 s of CPU in 5 s
idle() {
    f0=$(stat_of frames_rendered) p0=$(stat_of presented) c0=$(cpu_ticks "$PID")
    sleep 5
    f1=$(stat_of frames_rendered) p1=$(stat_of presented) c1=$(cpu_ticks "$PID")
    cpu=$(awk "BEGIN{printf \"%.2f\", ($c1 - $c0) / $TICKS}")
    echo "$1 idle 5 s: $((f1 - f0)) frames rendered, $((p1 - p0)) presented, ${cpu} s CPU"
    [ "$f1" -eq "$f0" ] || fail "$1: $((f1 - f0)) frames rendered while idle, want 0"
    awk "BEGIN{exit !($cpu < 0.3)}" || fail "$1: ${cpu} s of CPU while idle for 5 s, want < 0.3"
}

"$OIT_BIN/oitgen" quads --count 24 -o quads.ply >/dev/null || { fail "oitgen quads"; exit 1; }
"$OIT_BIN/oitprep" quads.ply -o quads.oitp >/dev/null 2>&1 || { fail "oitprep quads"; exit 1; }

# 1. A mesh: idle, drag, preview, exact, help.
if start quads.ply --preview lowres --still $STILL; then
    idle mesh
    e0=$(stat_of exact_frames)
    xdotool mousemove --window "$WIN" 100 75 mousedown 1 mousemove --window "$WIN" 120 80 \
        mousemove --window "$WIN" 140 85 mousemove --window "$WIN" 160 90 mouseup 1
    wait_for 30 stat_at_least preview_frames 1 || fail "the drag rendered no preview"
    [ "$(json_str shown <st.json)" = preview ] || fail "after the drag the window shows '$(json_str shown <st.json)', want preview"
    TITLE=$(xdotool getwindowname "$WIN")
    echo "title while moving: $TITLE"
    echo "$TITLE" | grep -q "  preview 1/[2-8] res  " || fail "the status line does not say preview: $TITLE"
    xdotool key --window "$WIN" g
    wait_for 10 sh -c '[ "$(grep -c "^viewer: screenshot" log.txt)" -ge 1 ]' || fail "G saved no screenshot of the preview"
    xdotool key --window "$WIN" p
    wait_for 10 sh -c '[ "$(grep -c "^viewer: screenshot" log.txt)" -ge 2 ]' || fail "P saved no screenshot while the preview shows"
    [ "$(stat_of exact_frames)" -eq "$e0" ] || fail "the exact frame came before the screenshot of the preview (--still $STILL)"
    # the exact frame, within --still of the last motion (and some slack for ASan)
    wait_for 30 stat_at_least exact_frames $((e0 + 1)) || fail "no exact frame after the drag"
    [ "$(json_str shown <st.json)" = exact ] || fail "still, the window shows '$(json_str shown <st.json)', want exact"
    TITLE=$(xdotool getwindowname "$WIN")
    echo "title when still: $TITLE"
    echo "$TITLE" | grep -q "  exact  " || fail "the status line does not say exact: $TITLE"
    VIEW=$(json_str view <st.json)
    xdotool key --window "$WIN" p
    wait_for 10 sh -c '[ "$(grep -c "^viewer: screenshot" log.txt)" -ge 3 ]' || fail "P saved no exact screenshot"
    xdotool key --window "$WIN" h g
    wait_for 10 sh -c '[ "$(grep -c "^viewer: screenshot" log.txt)" -ge 4 ]' || fail "G saved no help screenshot"
    xdotool key --window "$WIN" p
    wait_for 10 sh -c '[ "$(grep -c "^viewer: screenshot" log.txt)" -ge 5 ]' || fail "P saved no screenshot under the help"
    xdotool key --window "$WIN" h
    idle "mesh after the drag"
    quit mesh
    "$S" quads.ply --size ${W}x$H --quiet --view "$VIEW" --out ref.png || fail "headless dfb of $VIEW"
    # 000 G of the preview, 001 P then, 002 P of the exact frame, 003 G of
    # the help, 004 P under the help
    expect_equal "exact after the drag vs headless of its view" oitstream_002.png ref.png
    expect_differ "preview vs exact" oitstream_000.png oitstream_002.png 100
    awk "BEGIN{exit !($RMSE < 0.05)}" || fail "the preview is not the exact image at a lower resolution (rmse $RMSE)"
    expect_equal "P while the preview shows: the exact image" oitstream_001.png ref.png
    expect_differ "help overlay vs none" oitstream_003.png oitstream_002.png 1000
    expect_equal "P leaves the help overlay out" oitstream_004.png ref.png
    grep -q "^viewer: [0-9]* frames rendered (2 exact, [1-9][0-9]* preview)" log.txt ||
        fail "want 2 exact frames (the first, and after the drag) and some previews"
fi

# 2. O on the mesh: type the part file's path, Enter: it opens with its
#    default method (5, stream), which then idles too (a reader thread of
#    its own).
if start quads.ply --preview lowres --still 1000; then
    xdotool key --window "$WIN" o
    xdotool type --window "$WIN" --delay 20 "quads.oitp"
    xdotool key --window "$WIN" Return
    wait_for 60 grep -q "^viewer: opened quads.oitp: [0-9]* triangles (part file), method stream" log.txt ||
        fail "O did not open quads.oitp with the stream method"
    wait_for 60 stat_at_least exact_frames 2 || fail "no exact frame of the opened part file"
    [ "$(json_str method <st.json)" = stream ] || fail "the opened part file shows method '$(json_str method <st.json)'"
    idle "part file opened with O"
    # a drag: streamed previews at a lower resolution, then the exact frame,
    # which is the headless stream of the same view
    e0=$(stat_of exact_frames) p0=$(stat_of preview_frames)
    xdotool mousemove --window "$WIN" 100 75 mousedown 1 mousemove --window "$WIN" 80 60 \
        mousemove --window "$WIN" 60 50 mouseup 1
    wait_for 30 stat_at_least preview_frames $((p0 + 1)) || fail "the drag on the part file rendered no preview"
    wait_for 30 stat_at_least exact_frames $((e0 + 1)) || fail "no exact frame after the drag on the part file"
    VIEW=$(json_str view <st.json)
    before=$(shots) # (wait_for's countdown is n)
    xdotool key --window "$WIN" p
    wait_for 10 sh -c "[ \$(grep -c '^viewer: screenshot' log.txt) -gt $before ]" || fail "P saved no screenshot of the part file"
    quit "O"
    grep -q "^viewer: method 5: stream" log.txt || fail "the part file did not switch to key 5, stream"
    "$S" quads.oitp --size ${W}x$H --quiet --view "$VIEW" --out ref_stream.png || fail "headless stream of $VIEW"
    # P never replaces a screenshot (section 1's are there): the name is
    # the one the viewer says it wrote.
    shot=$(sed -n 's/^viewer: screenshot \([^ ]*\) .*/\1/p' log.txt | tail -n 1)
    [ "$shot" = oitstream_005.png ] || fail "P wrote '$shot', want oitstream_005.png (000-004 are section 1's)"
    expect_equal "stream exact after the drag vs headless" "$shot" ref_stream.png
fi

finish viewer_interactive
