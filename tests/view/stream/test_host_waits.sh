#!/bin/sh
# The host's waits on the GPU within a frame (view/render/gl/host_wait.h) on the
# default stream path (--pack auto: first-K packs, their second pass driven
# by the GPU from the first frame on), resident part files:
#  - 300 stacked squares (oitgen hard --case stack) seen from far off, so
#    that fewer than 1 pixel in 50 overflows K, --pack first-k: no frame
#    reads anything back within it; the first may outgrow the pass-2
#    store its slots give it, end short and be drawn again (its one wait:
#    the short frame's final read-back), no later frame waits or redraws,
#    second-pass pixels > 0 on every frame and DFB's image and fragments;
#  - the same under auto: its first frame is first-K's (no wait but for a
#    redraw), and its pixels over K have the still view's second frame
#    probe counted, drawn predicted from the first frame's counts (one
#    geometry pass, predicted_batches > 0); no warm frame waits;
#  - 4 stacked quads (nothing over K): 0 waits and redraws, no second pass;
#  - the stack head on, every pixel over K, --pack counted (the path auto
#    takes there; pinned, because which path auto holds is its measured
#    times' call, which a loaded machine can change): counted batches wait
#    for their counts only until a frame has measured what they need, so
#    every frame after the first waits 0 times and none is drawn again
#    (--store-budget 64M: one store holds a batch; the runs below cut
#    batches in bands);
#  - --pack first-k on the stack, the corner view (1.6 M fragments) then the
#    head-on one (2.5 M): the first frame may outgrow its slots' store (as
#    above); the head-on frame outgrows the store sized from
#    the corner's need, ends short and is drawn again (redraws 1, one wait:
#    the short frame's final read-back); the frames after it wait 0 times
#    and never redraw; every frame's image and fragments DFB's;
#  - the same walk with --pack counted: the first frame reads its batches'
#    counts, the second is sized ahead from them, the head-on frame outgrows
#    that store and is drawn again (redraws 0 0 1 0 0, waits after the first
#    0 1 0 0), every frame's image and fragments DFB's;
#  - both counted runs again with --store-budget 2M (131,072 fragments a
#    store against 2.5 M head on): each batch is drawn in bands of rows,
#    cut on the GPU and, ahead, the bands the frame before cut; warm
#    frames still wait 0 times (head on) and the walk redraws only where
#    its view changes (0 0 1 0 0, waits 0 1 0 0), at least 19 bands a
#    head-on frame, every image and fragment count DFB's.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
scratch host_waits
need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
gen_hard stack "$T/stack.ply"
prep_or_die "$T/stack.ply" "$T/stack.oitp" --scheme fast
"$OIT_BIN/oitgen" quads --count 4 -o "$T/quads.ply" >/dev/null ||
    die "cannot make the 4-quad mesh"
prep_or_die "$T/quads.ply" "$T/quads.oitp" --scheme fast

# every frame of run NAME: its images (in $T/NAME/) equal DFB's (in
# $T/NAME_dfb/), and its fragments
same_as_dfb() {
    _n=$1
    for _f in "$T/$_n"/frame_*.png; do
        _i=$(basename "$_f")
        compare "$_n $_i vs dfb" "$_f" "$T/${_n}_dfb/$_i" 0.01
    done
    [ "$(json_all fragments < "$T/$_n.json" | tr '\n' ' ')" = \
      "$(json_all fragments < "$T/${_n}_dfb.json" | tr '\n' ' ')" ] ||
        fail "$_n: fragments $(json_all fragments < "$T/$_n.json" | tr '\n' ' '), dfb's" \
             "$(json_all fragments < "$T/${_n}_dfb.json" | tr '\n' ' ')"
}

# run NAME FILE SIZE VIEWS [OPTION...]: the stream and DFB, stats kept
run() {
    _n=$1 _p=$2 _s=$3 _v=$4
    shift 4
    "$S" "$_p" --size "$_s" --walk "$_v" --quiet --out "$T/$_n/" --stats "$T/$_n.json" "$@" ||
        fail "$_n: oitstream exited $?"
    "$S" "$_p" --method dfb --size "$_s" --walk "$_v" --quiet --out "$T/${_n}_dfb/" \
        --stats "$T/${_n}_dfb.json" || fail "$_n: dfb exited $?"
    echo "$_n: host waits $(json_all host_waits < "$T/$_n.json" | tr '\n' ' ')," \
         "redraws $(json_all redraws < "$T/$_n.json" | tr '\n' ' ')," \
         "second-pass pixels $(json_all second_pass_pixels < "$T/$_n.json" | tr '\n' ' ')," \
         "first-K $(json_all auto_first_k < "$T/$_n.json" | tr -d '\n')"
    same_as_dfb "$_n"
}

# frames 1.. of NAME: 0 waits, 0 redraws
warm_zero() {
    [ "$(json_all host_waits < "$T/$1.json" | sed 1d | awk '{s += $1} END {print s + 0}')" -eq 0 ] ||
        fail "$1: a warm frame waited: $(json_all host_waits < "$T/$1.json" | tr '\n' ' ')"
    [ "$(json_all redraws < "$T/$1.json" | sed 1d | awk '{s += $1} END {print s + 0}')" -eq 0 ] ||
        fail "$1: a warm frame was drawn again: $(json_all redraws < "$T/$1.json" | tr '\n' ' ')"
}

# frame 0 of NAME (first-K): no wait but for its redraw, at most one
first_frame() {
    _w=$(json_all host_waits < "$T/$1.json" | head -n 1)
    _r=$(json_all redraws < "$T/$1.json" | head -n 1)
    [ "$_r" -le 1 ] && [ "$_w" -eq "$_r" ] ||
        fail "$1: the first frame waited $_w times and was drawn again $_r times; want one" \
             "wait a redraw, at most one"
}

for i in 1 2 3 4; do echo "0,0,60,0,0,0,0,1,0,18"; done > "$T/far.txt"
run far "$T/stack.oitp" 128x128 "$T/far.txt" --pack first-k
warm_zero far
first_frame far
[ "$(json_min second_pass_pixels < "$T/far.json")" -gt 0 ] ||
    fail "far: a frame without second-pass pixels: nothing overflowed K"
run farauto "$T/stack.oitp" 128x128 "$T/far.txt"
warm_zero farauto
first_frame farauto
[ "$(json_all auto_first_k < "$T/farauto.json" | head -n 2 | tr -d '\n')" = 10 ] &&
    [ "$(json_all predicted_batches < "$T/farauto.json" | sed -n 2p)" -gt 0 ] ||
    fail "farauto: first-K $(json_all auto_first_k < "$T/farauto.json" | tr -d '\n')," \
         "predicted batches $(json_all predicted_batches < "$T/farauto.json" | tr '\n' ' '):" \
         "want the second frame counted, predicted"

run quads "$T/quads.oitp" 96x96 "$T/far.txt"
warm_zero quads
first_frame quads
[ "$(json_sum second_pass_pixels < "$T/quads.json")" -eq 0 ] ||
    fail "quads: a second pass where no pixel gets more than 4"

for i in 1 2 3 4; do echo "0,0,5,0,0,0,0,1,0,18"; done > "$T/deep.txt"
run deep "$T/stack.oitp" 64x64 "$T/deep.txt" --store-budget 64M --pack counted
warm_zero deep

printf '%s\n' 1.5,1.2,4,0,0,0,0,1,0,30 1.5,1.2,4,0,0,0,0,1,0,30 0,0,5,0,0,0,0,1,0,18 \
    0,0,5,0,0,0,0,1,0,18 0,0,5,0,0,0,0,1,0,18 > "$T/grow.txt"
run grow "$T/stack.oitp" 64x64 "$T/grow.txt" --pack first-k
[ "$(json_all redraws < "$T/grow.json" | sed 1d | tr '\n' ' ')" = "0 1 0 0 " ] &&
    [ "$(json_all redraws < "$T/grow.json" | head -n 1)" -le 1 ] ||
    fail "grow: redraws $(json_all redraws < "$T/grow.json" | tr '\n' ' '), want 0 or 1, 0 1 0 0"
[ "$(json_all host_waits < "$T/grow.json" | sed 1d | tr '\n' ' ')" = "0 1 0 0 " ] ||
    fail "grow: host waits after the first frame" \
         "$(json_all host_waits < "$T/grow.json" | sed 1d | tr '\n' ' '), want 0 1 0 0"
run growc "$T/stack.oitp" 64x64 "$T/grow.txt" --pack counted
[ "$(json_all redraws < "$T/growc.json" | tr '\n' ' ')" = "0 0 1 0 0 " ] ||
    fail "growc: redraws $(json_all redraws < "$T/growc.json" | tr '\n' ' '), want 0 0 1 0 0"
[ "$(json_all host_waits < "$T/growc.json" | sed 1d | tr '\n' ' ')" = "0 1 0 0 " ] ||
    fail "growc: host waits after the first frame" \
         "$(json_all host_waits < "$T/growc.json" | sed 1d | tr '\n' ' '), want 0 1 0 0"
run banded "$T/stack.oitp" 64x64 "$T/deep.txt" --store-budget 2M --pack counted
warm_zero banded
[ "$(json_min batches < "$T/banded.json")" -ge 19 ] ||
    fail "banded: batches $(json_all batches < "$T/banded.json" | tr '\n' ' '), want >= 19 bands"
run growb "$T/stack.oitp" 64x64 "$T/grow.txt" --store-budget 2M --pack counted
[ "$(json_all redraws < "$T/growb.json" | tr '\n' ' ')" = "0 0 1 0 0 " ] ||
    fail "growb: redraws $(json_all redraws < "$T/growb.json" | tr '\n' ' '), want 0 0 1 0 0"
[ "$(json_all host_waits < "$T/growb.json" | sed 1d | tr '\n' ' ')" = "0 1 0 0 " ] ||
    fail "growb: host waits after the first frame" \
         "$(json_all host_waits < "$T/growb.json" | sed 1d | tr '\n' ' '), want 0 1 0 0"
finish "host waits"
