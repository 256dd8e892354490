#!/bin/sh
# oitstream --pack first-k (view/render/capture/capture_firstk.h) where its slots cannot
# hold a pack: exact, nothing lost, and the second pass reported.
# Usage: test_firstk.sh WRITER   (WRITER: test_streamer, writes the grid file)
#  - 600 stacked squares (oitgen hard --case stack, --scheme fast: 16 parts of
#    about 38 layers, one pack) seen head on: every covered pixel gets 600
#    fragments in one pack, far over K = 8 and 16. The image must equal DFB's
#    on the same file and on the source mesh (1/255 on >= 99.9% of pixels,
#    as the stream-vs-DFB tests), the fragments of every frame DFB's (a pixel
#    composited twice or skipped would change them), overflow 0 and
#    second_pass_pixels > 0; counted packs report 0 for both figures.
#  - 4 stacked quads: nothing over K, so no pack takes the second pass.
#  - the automatic mode (the default): on the stack, head on, the first frame
#    takes first-K (choice "seed"), finds far more than 1 pixel in 50 over K,
#    outgrows the pass-2 store its slots give a first frame, and is drawn
#    again counted (redraws 1, capture counted); the next one probes counted
#    (which holds after it is the measured costs' call: test_choice.sh); on
#    the 4 quads every frame stays first-K; every frame's image is bit for
#    bit the first's, whichever capture took it.
#  - the grid in many packs (64K upload ring), K = 2 so pixels overflow,
#    exact and with early termination: bit for bit the counted capture's
#    image, which composites the same fragments of the same packs.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
# Under the sanitizer build, LeakSanitizer's exit scan crashed ("Tracer
# caught signal 11") on the 4-quad first-k run, every time, after the run had
# passed: its log showed a main-thread DTLS range of 0xd9b-0x1800001e9d, the
# runtime's known misreading of glibc's dynamic TLS (google/sanitizers#1322,
# allocation-layout dependent). Its workaround leaves dynamic TLS out of the
# scan; leaks everywhere else are still reported. No effect without ASan.
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}intercept_tls_get_addr=0"
export ASAN_OPTIONS
S="$OIT_BIN/oitstream"
scratch firstk

need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
gen_hard stack "$T/stack.ply"
prep_or_die "$T/stack.ply" "$T/stack.oitp" --scheme fast
# head on, and from the side of the stack's corner
printf '0,0,5,0,0,0,0,1,0,18\n1.5,1.2,4,0,0,0,0,1,0,30\n' > "$T/views.txt"
W="--size 64x64 --walk $T/views.txt --quiet"
"$S" "$T/stack.oitp" --method dfb $W --out "$T/dfb" --stats "$T/dfb.json" ||
    fail "stack: dfb exited $?"
"$S" "$T/stack.ply" --method dfb $W --out "$T/mesh" || fail "stack: dfb on the mesh exited $?"
for K in 8 16; do
    n="firstk_$K"
    "$S" "$T/stack.oitp" --pack first-k --max-layers $K $W --out "$T/$n" --stats "$T/$n.json" ||
        { fail "stack K=$K: first-k exited $?"; continue; }
    for i in 000 001; do
        compare "stack K=$K view $i vs dfb" "$T/$n/frame_$i.png" "$T/dfb/frame_$i.png" 0.1
        compare "stack K=$K view $i vs dfb on the mesh" "$T/$n/frame_$i.png" "$T/mesh/frame_$i.png" 0.1
    done
    f=$(json_all fragments < "$T/$n.json" | tr '\n' ' ')
    fd=$(json_all fragments < "$T/dfb.json" | tr '\n' ' ')
    echo "stack K=$K: fragments $f(dfb $fd), max layers $(json_all max_layers < "$T/$n.json" | tr '\n' ' ')," \
         "second pass: pixels $(json_all second_pass_pixels < "$T/$n.json" | tr '\n' ' ')" \
         "packs $(json_all second_pass_packs < "$T/$n.json" | tr '\n' ' ')" \
         "of $(json_all packs < "$T/$n.json" | tr '\n' ' ')"
    [ "$f" = "$fd" ] || fail "stack K=$K: fragments $f, dfb's $fd"
    [ "$(json_sum overflow_pixels < "$T/$n.json")" -eq 0 ] || fail "stack K=$K: overflow"
    [ "$(json_min second_pass_pixels < "$T/$n.json")" -gt 0 ] &&
        [ "$(json_min second_pass_packs < "$T/$n.json")" -gt 0 ] ||
        fail "stack K=$K: a frame without second-pass pixels or packs"
    [ "$(json_num max_layers < "$T/$n.json")" -ge 600 ] ||
        fail "stack K=$K: the head-on view has at most $(json_num max_layers < "$T/$n.json") layers"
done
"$S" "$T/stack.oitp" --pack counted $W --stats "$T/counted.json" || fail "stack: counted exited $?"
[ "$(json_sum second_pass_pixels < "$T/counted.json")" -eq 0 ] &&
    [ "$(json_sum second_pass_packs < "$T/counted.json")" -eq 0 ] ||
    fail "stack: counted packs report a second pass"

"$OIT_BIN/oitgen" quads --count 4 -o "$T/quads.ply" >/dev/null &&
    "$OIT_BIN/oitprep" "$T/quads.ply" -o "$T/quads.oitp" --scheme fast >/dev/null ||
    fail "cannot make the 4-quad part file"
"$S" "$T/quads.oitp" --pack first-k --max-layers 8 --size 96x96 --orbit 3 --quiet \
    --out "$T/quads" --stats "$T/quads.json" || fail "4 quads: first-k exited $?"
"$S" "$T/quads.oitp" --method dfb --size 96x96 --orbit 3 --quiet --out "$T/quads_dfb" ||
    fail "4 quads: dfb exited $?"
compare "4 quads view 000" "$T/quads/frame_000.png" "$T/quads_dfb/frame_000.png" 0.1
echo "4 quads: max layers $(json_all max_layers < "$T/quads.json" | tr '\n' ' ')," \
     "second-pass packs $(json_all second_pass_packs < "$T/quads.json" | tr '\n' ' ')"
[ "$(json_sum second_pass_packs < "$T/quads.json")" -eq 0 ] &&
    [ "$(json_sum second_pass_pixels < "$T/quads.json")" -eq 0 ] ||
    fail "4 quads: a second pass where no pixel gets more than 4"

# The automatic mode: 10 frames of one view (the probe comes at frame 9).
for i in 1 2 3 4 5 6 7 8 9 10; do echo "0,0,5,0,0,0,0,1,0,18"; done > "$T/still.txt"
"$S" "$T/stack.oitp" --size 64x64 --walk "$T/still.txt" --quiet --out "$T/auto/" \
    --stats "$T/auto.json" || fail "stack: auto exited $?"
seq_auto=$(grep -o '"choice": "[^"]*", "choice_why": "[^"]*"' "$T/auto.json" |
    sed 's/.*"choice": "\([^"]*\)", "choice_why": "\([^"]*\)"/\1:\2/' | head -n 2 | tr '\n' ' ')
echo "stack, automatic mode, 10 frames of one view: first-K per frame" \
     "$(json_all auto_first_k < "$T/auto.json" | tr -d '\n'), choices $seq_auto..., redraws" \
     "$(json_all redraws < "$T/auto.json" | tr '\n' ' '), deep pixels" \
     "$(json_all deep_pixels < "$T/auto.json" | tr '\n' ' ')"
# Which path holds after the probe is the measured costs' call
# (view/stream/choice.h, test_choice.sh): here only the seed and the probe.
[ "$seq_auto" = "first-k:seed counted:probe " ] ||
    fail "stack: automatic mode chose $seq_auto, want first-K, then the counted probe"
[ "$(json_all deep_pixels < "$T/auto.json" | head -n 1)" -gt $((64 * 64 / 50)) ] ||
    fail "stack: the first frame found at most 1 pixel in 50 over K"
[ "$(json_all redraws < "$T/auto.json" | tr -d '\n')" = 1000000000 ] &&
    [ "$(json_str capture < "$T/auto.json")" = counted ] ||
    fail "stack: the first frame was not drawn again counted (redraws" \
         "$(json_all redraws < "$T/auto.json" | tr -d '\n'), capture $(json_str capture < "$T/auto.json"))"
for i in 001 002 008 009; do
    cmp -s "$T/auto/frame_000.png" "$T/auto/frame_$i.png" ||
        fail "stack: automatic mode frame $i differs from frame 0"
done
"$S" "$T/quads.oitp" --size 96x96 --walk "$T/still.txt" --quiet --stats "$T/quads_auto.json" \
    --out "$T/quads_auto/" || fail "4 quads: auto exited $?"
[ "$(json_all auto_first_k < "$T/quads_auto.json" | tr -d '\n')" = 1111111111 ] ||
    fail "4 quads: the automatic mode left first-K"

P="$T/grid.oitp"
"$1" "$P" || die "cannot write the grid part file"
G="--size 96x96 --orbit 3 --max-layers 2 --upload-budget 64K --cache-budget off --quiet"
for e in 0 0.05; do
    for pk in counted first-k; do
        "$S" "$P" $G --pack $pk --epsilon $e --out "$T/grid_${pk}_$e.pfm" \
            --stats "$T/grid_${pk}_$e.json" || fail "grid $pk E=$e: exited $?"
    done
    for i in 000 001 002; do
        cmp -s "$T/grid_counted_${e}_$i.pfm" "$T/grid_first-k_${e}_$i.pfm" ||
            fail "grid E=$e view $i: first-k differs from counted"
    done
    j="$T/grid_first-k_$e.json"
    echo "grid E=$e: packs $(json_all packs < "$j" | tr '\n' ' ')," \
         "second-pass packs $(json_all second_pass_packs < "$j" | tr '\n' ' ')," \
         "pixels $(json_all second_pass_pixels < "$j" | tr '\n' ' ')," \
         "fragments $(json_sum fragments < "$j") (counted $(json_sum fragments < "$T/grid_counted_$e.json"))"
    [ "$(json_min packs < "$j")" -gt 1 ] || fail "grid E=$e: a frame in one pack"
    [ "$(json_sum second_pass_pixels < "$j")" -gt 0 ] || fail "grid E=$e: no second pass at K=2"
    [ "$(json_sum fragments < "$j")" = "$(json_sum fragments < "$T/grid_counted_$e.json")" ] ||
        fail "grid E=$e: fragments differ from counted"
done
[ "$(json_sum fragments < "$T/grid_first-k_0.05.json")" -lt \
  "$(json_sum fragments < "$T/grid_first-k_0.json")" ] ||
    fail "grid: E=0.05 dropped no fragment"

finish first-k
