#!/bin/sh
# oitstream --window under a virtual X display (run by xvfb-run): the window
# shows exactly what the headless renderer writes, and each scripted key
# changes the frame the way the matching command-line option does:
#   - the window's screenshot (no overlay) equals `--out` of the same view
#   - the status line changes the top rows only, and some of them
#   - L equals `--show layers` (on the stream too), T equals `--shading translucent`, the key
#     of "array" equals `--method array`, W moves the view and R restores it
#   - Q stops the loop early with exit status 0; E reports no early termination
#   - one key map for meshes and part files: key 1 is dfb and key 5 stream for
#     both; on a mesh, 5 puts a message on the image saying why it cannot run
#   - --up z equals `--up z --out` and changes the default view
#   - V toggles orthographic (equal to --ortho fit) and back
#   - P writes the first free oitstream_NNN.png and never replaces a file,
#     rendered offscreen from the current view at --shot-size
#   - the status line of named fields wraps to the window's width
# Equal means within half an 8-bit step (the window quantises to 8 bits).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
[ -n "${DISPLAY:-}" ] || skip "no DISPLAY (run under xvfb-run)"
S="$OIT_BIN/oitstream"
scratch viewer
cd "$T" || exit 1
SIZE=160x120
EQUAL=0.002 # 0.5/255 plus float slack

# 0. Usage errors (exit 2) before any window opens.
for bad in "--window-frames 3" "--window --orbit 4" "--window --out x.png"; do
    # shellcheck disable=SC2086 # the options are meant to split
    "$S" quads.ply $bad >/dev/null 2>&1; rc=$?
    [ "$rc" -eq 2 ] || fail "oitstream quads.ply $bad: exit $rc, want 2"
done
for opt in --window-script --preview --still --up; do
    "$S" --help | grep -q -- "$opt" || fail "--help does not document $opt"
done
"$S" quads.ply --preview lowres >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || fail "--preview without --window: exit $rc, want 2"
"$S" quads.ply --window --up w >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || fail "--up w: exit $rc, want 2"

# 16 overlapping translucent squares: every pixel of the centre has many
# layers, and few triangles keep llvmpipe frames fast. No more than the
# array method's 16 slots: which fragments of an overflowing pixel keep
# them is up to the order of atomics, so two array frames of a deeper scene
# need not be equal (section 3).
"$OIT_BIN/oitgen" quads --count 16 -o quads.ply >/dev/null || { fail "oitgen quads"; exit 1; }

# 1. The overlay run: 3 frames, screenshot of the last.
"$S" quads.ply --window --size $SIZE --window-frames 3 --window-screenshot overlay.png >overlay.txt 2>&1 ||
    { cat overlay.txt; fail "--window exited with $?"; exit 1; }
cat overlay.txt
grep -q "^viewer: 3 frames" overlay.txt || fail "the overlay run did not show 3 frames"
[ -f overlay.png ] || fail "no overlay.png"
ARRAY_KEY=$(sed -n 's/^viewer: key \([1-9]\): array$/\1/p' overlay.txt)
[ -n "$ARRAY_KEY" ] || fail "no key lists the array method"

# 2. The scripted run, no overlay: P saves oitstream_NNN.png after the next frame.
#    000 home, 001 heat map, 002 translucent, 003 after W, 004 array after R.
SCRIPT="PLPLTPTWPR${ARRAY_KEY}PEEQ"
"$S" quads.ply --window --no-overlay --size $SIZE --window-frames 100 --window-script "$SCRIPT" \
    >script.txt 2>&1 || { cat script.txt; fail "the scripted run exited with $?"; }
cat script.txt
FRAMES=$(sed -n 's/^viewer: \([0-9]*\) frames.*/\1/p' script.txt)
[ "$FRAMES" = "$(( ${#SCRIPT} - 1 ))" ] || fail "Q should stop after $(( ${#SCRIPT} - 1 )) frames, not '$FRAMES'"
grep -q "early termination on, epsilon 0.00392157 (used by the stream method only)" script.txt &&
    grep -q "early termination off (exact)" script.txt || fail "E E did not turn early termination on, then off"
for i in 000 001 002 003 004; do [ -f oitstream_$i.png ] || fail "P did not save oitstream_$i.png"; done
grep -q "last: $ARRAY_KEY array .* overflow 0 " script.txt ||
    fail "the array frame overflowed its slots: its image is not defined, so section 3 cannot compare it"

# 3. The same views headless.
"$S" quads.ply --size $SIZE --quiet --out ref.png || fail "headless dfb"
"$S" quads.ply --size $SIZE --quiet --show layers --out heat.png || fail "headless heat map"
"$S" quads.ply --size $SIZE --quiet --shading translucent --out translucent.png || fail "headless translucent"
"$S" quads.ply --size $SIZE --quiet --method array --out array.png || fail "headless array"

expect_equal "window vs headless" oitstream_000.png ref.png
expect_equal "L vs --show layers" oitstream_001.png heat.png
expect_differ "L vs colour" oitstream_001.png ref.png 1000
expect_equal "T vs --shading translucent" oitstream_002.png translucent.png
expect_differ "T vs transparent" oitstream_002.png ref.png 100
expect_differ "W vs home" oitstream_003.png ref.png 100
expect_equal "R then array key vs --method array" oitstream_004.png array.png

# 4. The status line: some pixels change, all within its band, whose rows
#    the viewer reports: whole lines of 11 rows (the named fields wrap at
#    160 pixels: more than one line, fewer than would fill the window).
BAND=$(sed -n 's/^viewer: .* status band \([0-9]*\) rows.*/\1/p' overlay.txt)
echo "status band: $BAND rows"
[ -n "$BAND" ] && [ $((BAND % 11)) -eq 0 ] && [ "$BAND" -ge 22 ] && [ "$BAND" -le 66 ] ||
    fail "the status band is '$BAND' rows, want 2 to 6 lines of 11"
grep -q "last: 1 dfb  exact  frame [0-9.]* ms  \(gpu [0-9.]* ms  \)\?fragments [0-9.]*K  layers 16  overflow 0" overlay.txt ||
    fail "the status line does not name its fields"
# GPU time (timer queries, read frames later): in by the third frame
grep -q "last: 1 dfb  exact  frame [0-9.]* ms  gpu [0-9.]* ms  " overlay.txt ||
    fail "the status line has no GPU time"
image_diff "overlay vs none" overlay.png oitstream_000.png
[ "$OVER" -ge 50 ] && [ "$OVER" -le $((160 * ${BAND:-11})) ] ||
    fail "the status line changed $OVER pixels, want 50..$((160 * ${BAND:-11})) (the top $BAND rows)"

# 5. One key map: 1 is dfb and 5 stream on a part file as on a mesh; on the
#    mesh 5 leaves dfb on and says why on the image (000 before, 001 after).
"$OIT_BIN/oitprep" quads.ply -o quads.oitp >/dev/null 2>&1 || fail "oitprep quads"
"$S" quads.oitp --window --no-overlay --size $SIZE --window-script "1" >keys_part.txt 2>&1 ||
    { cat keys_part.txt; fail "the part-file run exited with $?"; }
rm -f oitstream_00[0-9].png
"$S" quads.ply --window --no-overlay --size $SIZE --window-script "P5P4" >keys_mesh.txt 2>&1 ||
    { cat keys_mesh.txt; fail "the mesh key run exited with $?"; }
cat keys_part.txt keys_mesh.txt
for f in keys_part.txt keys_mesh.txt; do
    grep -q "^viewer: key 1: dfb$" $f || fail "$f: key 1 is not dfb"
    grep -q "^viewer: key 5: stream" $f || fail "$f: key 5 is not stream"
done
grep -q "^viewer: method 5: stream" keys_part.txt || fail "a part file does not start with 5, stream"
grep -q "^viewer: method 1: dfb" keys_part.txt || fail "key 1 on a part file does not switch to dfb"
grep -q "^viewer: 5 stream cannot run on this input: needs a part file" keys_mesh.txt ||
    fail "key 5 on a mesh does not say why stream cannot run"
grep -q "^viewer: method 5" keys_mesh.txt && fail "key 5 on a mesh switched method"
#    4, stencil, runs or says why it cannot run here (llvmpipe: too few samples)
grep -q "^viewer: method 4: stencil\|^viewer: 4 stencil cannot run here: ." keys_mesh.txt ||
    fail "key 4 neither switched to stencil nor said why it cannot"
expect_equal "before 5 vs headless" oitstream_000.png ref.png
#    the message is on the window's image (P renders the view alone)
"$S" quads.ply --window --no-overlay --size $SIZE --window-script "5" --window-screenshot msg5.png \
    >msg5.txt 2>&1 || { cat msg5.txt; fail "the message run exited with $?"; }
expect_differ "the message of 5 on the image" msg5.png ref.png 100

# 5b. P never overwrites: a later run numbers on from the first free name
#     (000 and 001 are section 5's), skips a file someone else made, and
#     says which it wrote.
printf 'not ours\n' > oitstream_003.png
before=$(cksum oitstream_000.png oitstream_001.png)
"$S" quads.ply --window --no-overlay --size $SIZE --window-script "PWPR" >shots.txt 2>&1 ||
    { cat shots.txt; fail "the screenshot run exited with $?"; }
cat shots.txt
grep -q "^viewer: screenshot oitstream_002.png " shots.txt &&
    grep -q "^viewer: screenshot oitstream_004.png " shots.txt ||
    fail "P did not write oitstream_002.png then oitstream_004.png (the first free names)"
[ "$(cksum oitstream_000.png oitstream_001.png)" = "$before" ] ||
    fail "P replaced an earlier run's screenshot"
[ "$(cat oitstream_003.png)" = "not ours" ] || fail "P replaced oitstream_003.png, not its own"
expect_equal "a later run's first screenshot vs headless" oitstream_002.png ref.png
expect_differ "its second, after W" oitstream_004.png ref.png 100

# 6. --up z: the window's default view is the headless --up z view, and not
#    the y-up one.
"$S" quads.ply --window --no-overlay --size $SIZE --up z --window-screenshot upz.png >upz.txt 2>&1 ||
    { cat upz.txt; fail "the --up z window exited with $?"; }
"$S" quads.ply --size $SIZE --quiet --up z --out upz_ref.png || fail "headless --up z"
expect_equal "--up z window vs headless" upz.png upz_ref.png
expect_differ "--up z vs y" upz.png ref.png 1000
#    U cycles y -> z: the same view
"$S" quads.ply --window --no-overlay --size $SIZE --window-script "U" --window-screenshot upkey.png >upkey.txt 2>&1 ||
    { cat upkey.txt; fail "the U run exited with $?"; }
expect_equal "U vs --up z" upkey.png upz_ref.png

# 7. A window past one storage binding: 2048x2048 translucent, the stream's
#    state 48 bytes a pixel (192 MiB; GL promises 128 MiB a binding), is
#    drawn in bands and equals the headless frame (which was not drawable
#    either: 2^22 pixels were more work groups than one dispatch takes).
"$OIT_BIN/oitgen" quads --count 4 -o big.ply >/dev/null || fail "oitgen quads --count 4"
"$OIT_BIN/oitprep" big.ply -o big.oitp >/dev/null 2>&1 || fail "oitprep big.ply"
"$S" big.oitp --window --no-overlay --size 2048x2048 --shading translucent --window-frames 1 \
    --window-screenshot big.png >big.txt 2>&1 || { cat big.txt; fail "the 2048x2048 window exited with $?"; }
"$S" big.oitp --size 2048x2048 --quiet --shading translucent --out big_ref.png || fail "headless 2048x2048"
expect_equal "2048x2048 window vs headless" big.png big_ref.png

# 8. L on a part file: the stream counts fragments per pixel, so its heat
#    map is DFB's of the same triangles (000 stream, 001 its heat map); a
#    method that counts none (wboit, key 7) says so on the window's image
#    (before L and after).
mkdir -p heat && cd heat || exit 1
"$S" ../quads.oitp --window --no-overlay --size $SIZE --window-script "PLP" >heat.txt 2>&1 ||
    { cat heat.txt; fail "the heat-map run exited with $?"; }
"$S" ../quads.ply --window --no-overlay --size $SIZE --window-script "7" \
    --window-screenshot wboit.png >/dev/null 2>&1 || fail "the wboit run exited with $?"
"$S" ../quads.ply --window --no-overlay --size $SIZE --window-script "7L" \
    --window-screenshot wboit_l.png >heat_wboit.txt 2>&1 ||
    { cat heat_wboit.txt; fail "the wboit heat-map run exited with $?"; }
cat heat.txt heat_wboit.txt
expect_equal "L on the stream vs DFB's --show layers" oitstream_001.png ../heat.png
expect_differ "L on the stream vs its colours" oitstream_001.png oitstream_000.png 1000
grep -q "^viewer: layer heat map: wboit counts no fragments per pixel" heat_wboit.txt ||
    fail "L on wboit does not say it counts none"
expect_differ "the message of L on wboit on the image" wboit_l.png wboit.png 100
cd .. || exit 1

# 9. V toggles the projection: orthographic as high as the perspective
#    frustum at the target (the model keeps its size there), the headless
#    --ortho fit view; V again gives the perspective image back (000
#    perspective, 001 orthographic, 002 perspective); the status line says
#    ortho (a third V, the last frame).
mkdir -p ortho && cd ortho || exit 1
"$S" ../quads.ply --window --no-overlay --size $SIZE --window-script "PVPVPV" >ortho.txt 2>&1 ||
    { cat ortho.txt; fail "the V run exited with $?"; }
cat ortho.txt
"$S" ../quads.ply --size $SIZE --quiet --ortho fit --out ortho_ref.png || fail "headless --ortho fit"
grep -q "^viewer: projection orthographic, [0-9.e+-]* high$" ortho.txt &&
    grep -q "^viewer: projection perspective$" ortho.txt || fail "V does not say the projection"
grep -q "last: .*  ortho  " ortho.txt || fail "the status line does not say ortho"
expect_equal "V vs --ortho fit" oitstream_001.png ortho_ref.png
expect_differ "V vs perspective" oitstream_001.png ../ref.png 100
expect_equal "V twice vs perspective" oitstream_002.png ../ref.png
cd .. || exit 1

# 10. P renders the current view offscreen, without the overlay, at
#     --shot-size (default the window's size), with the current method
#     (stream here, after a fly, V and a fly back), and prints the file,
#     its size and the view as --view takes it: the image equals oitstream
#     --size --view of that view.
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{ print $3 * 256 + $4 "x" $7 * 256 + $8 }'; }
mkdir -p shot && cd shot || exit 1
"$S" ../quads.oitp --window --size $SIZE --shot-size 200x90 --window-script "DVAP" >shot.txt 2>&1 ||
    { cat shot.txt; fail "the --shot-size run exited with $?"; }
cat shot.txt
VIEW=$(sed -n 's/^viewer: screenshot oitstream_000.png 200x90 --view \(.*\)$/\1/p' shot.txt)
[ -n "$VIEW" ] || fail "P does not print the screenshot's name, size and view"
[ "$(png_size oitstream_000.png)" = 200x90 ] ||
    fail "the screenshot is $(png_size oitstream_000.png), not --shot-size 200x90"
"$S" ../quads.oitp --size 200x90 --view "$VIEW" --quiet --out shot_ref.png ||
    fail "headless --view $VIEW"
expect_equal "P at --shot-size vs --size --view" oitstream_000.png shot_ref.png
"$S" ../quads.oitp --size 200x90 --quiet --out home.png || fail "headless home view"
expect_differ "that view vs the home view" shot_ref.png home.png 100
"$S" ../quads.ply --window --size $SIZE --window-script "P" >shot_default.txt 2>&1 ||
    { cat shot_default.txt; fail "the default-size run exited with $?"; }
[ "$(png_size oitstream_001.png)" = "$(echo $SIZE)" ] ||
    fail "without --shot-size the screenshot is $(png_size oitstream_001.png), not the window's $SIZE"
expect_equal "P at the window's size vs headless (no overlay)" oitstream_001.png ../ref.png
#     the window's own image is --window-screenshot's: H's help shows there
"$S" ../quads.ply --window --no-overlay --size $SIZE --window-script "H" --window-screenshot help.png \
    >help.txt 2>&1 || { cat help.txt; fail "the help run exited with $?"; }
expect_differ "the help overlay on the window's image" help.png ../ref.png 1000
"$S" ../quads.ply --shot-size 200x90 >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || fail "--shot-size without --window: exit $rc, want 2"
cd .. || exit 1

finish viewer
