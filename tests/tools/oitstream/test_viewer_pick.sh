#!/bin/sh
# The viewer's pick through real X events (xdotool under xvfb-run): a left
# click that does not drag, and the I key, list the layers of the pixel
# under the cursor on stdout, the same source triangles in the same order
# (and parts, for a part file) as `oitstream --pick` of the view the window
# reports, for a mesh (dfb) and a part file (stream); the panel and the
# marker change the image (G screenshots of the window before and after
# differ), and a drag (even one back to where it began) picks nothing and
# clears them (the window's screenshot after it equals the headless image of
# the window's view).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
. "$(dirname "$0")/viewer_x11.sh"
S="$OIT_BIN/oitstream"
EQUAL=0.002 # 0.5/255 plus float slack: the window quantises to 8 bits
scratch viewer_pick
cd "$T" || exit 1
W=200
H=150

lines_at_least() { [ "$(grep -c "$1" log.txt)" -ge "$2" ]; }
# the viewer's Nth pick (1-based) as "part:source" lines
viewer_layers() {
    awk -v want="$1" '/^viewer: pick [0-9]+,[0-9]+: /{k++; next}
        k == want && /^viewer:   layer /{print $13 ":" $15}' log.txt
}
# oitstream --pick of the window's view as "part:source" lines
cli_layers() {
    "$S" "$1" --size ${W}x$H --view "$(json_str view <st.json)" --pick "$2" >pick.json ||
        { fail "oitstream --pick $2 of $1"; return 1; }
    grep '"source_triangle"' pick.json |
        sed 's/.*"part": \([0-9a-z]*\), "source_triangle": \([0-9]*\).*/\1:\2/; s/^null:/-:/'
}
# check NAME MODEL N X Y: the viewer's Nth pick, at window point X,Y, against the CLI's
check() {
    v=$(viewer_layers "$3") c=$(cli_layers "$2" "$4,$5")
    n=$(printf '%s\n' "$v" | grep -c .)
    echo "$1: the viewer lists $n layers at $4,$5"
    [ "$n" -ge 2 ] || fail "$1: the pick at $4,$5 lists $n layers, want a deep pixel"
    [ "$v" = "$c" ] || fail "$1: the viewer's layers (part:source) $(echo $v) differ from oitstream --pick's $(echo $c)"
}

"$OIT_BIN/oitgen" quads --count 12 -o quads.ply >/dev/null || { fail "oitgen quads"; exit 1; }
"$OIT_BIN/oitprep" quads.ply -o quads.oitp >/dev/null 2>&1 || { fail "oitprep quads"; exit 1; }

for model in quads.ply quads.oitp; do
    rm -f oitstream_*.png
    start "$model" || continue
    xdotool key --window "$WIN" g
    wait_for 10 lines_at_least "^viewer: screenshot" 1 || fail "$model: G saved no screenshot"
    xdotool mousemove --window "$WIN" 100 75 click 1
    wait_for 20 lines_at_least "^viewer: pick 100,75: " 1 || { cat log.txt; fail "$model: a click at 100,75 picked nothing"; }
    check "$model click" "$model" 1 100 75
    xdotool key --window "$WIN" g
    wait_for 10 lines_at_least "^viewer: screenshot" 2 || fail "$model: G saved no screenshot"
    expect_differ "$model: the pick's panel vs none" oitstream_001.png oitstream_000.png 200
    xdotool mousemove --window "$WIN" 110 70 key --window "$WIN" i
    wait_for 20 lines_at_least "^viewer: pick 110,70: " 1 || fail "$model: I at 110,70 picked nothing"
    check "$model I" "$model" 2 110 70
    # a drag away and back: no pick, and the panel is gone
    e=$(stat_of exact_frames)
    xdotool mousemove --window "$WIN" 100 75 mousedown 1 mousemove --window "$WIN" 130 75 \
        mousemove --window "$WIN" 100 75 mouseup 1
    wait_for 30 stat_at_least exact_frames $((e + 1)) || fail "$model: no exact frame after the drag"
    [ "$(grep -c '^viewer: pick ' log.txt)" -eq 2 ] || fail "$model: a drag picked"
    xdotool key --window "$WIN" g
    wait_for 10 lines_at_least "^viewer: screenshot" 3 || fail "$model: G saved no screenshot"
    quit "$model"
    "$S" "$model" --size ${W}x$H --quiet --view "$(json_str view <st.json)" --out ref.png ||
        fail "$model: headless image of the window's view"
    expect_equal "$model: after a drag the panel is gone" oitstream_002.png ref.png
done
finish "viewer pick"
