#!/bin/sh
# The budget rule end to end (view/stream/pack.h): oitstream --pack budget with
# small K (--max-layers 2, 3 and 4), in the tree and the wave schedule,
# against DFB on the small grid file (test_streamer: closed boxes of 2
# layers, boxes with an octahedron inside of 4, so at K 2 and 3 those are
# wide parts, at K 4 full first parts). The file's layer bounds are exact,
# so a pack whose first part goes uncounted, or a part that joins a wide
# pack, gets pixels of more than its slots: overflow, and an image off
# DFB's. Asserted on 3 orbit views each: the images agree to 1/255 on
# 99.9% of pixels, no pixel overflows, and the packs joined parts (fewer
# packs than parts drawn), so the rule had something to decide.
# Usage: test_pack_budget.sh WRITER   (WRITER: test_streamer)
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
need_tools "$S"
scratch pack_budget
P="$T/grid.oitp"
"$1" "$P" || die "cannot write the part file"
"$S" "$P" --method dfb --size 128x128 --orbit 3 --out "$T/dfb.png" --quiet ||
    die "dfb exited $?"
for K in 2 3 4; do
    for sched in tree wave; do
        n="k${K}_$sched"
        "$S" "$P" --size 128x128 --orbit 3 --pack budget --max-layers $K --schedule $sched \
            --out "$T/$n.png" --stats "$T/$n.json" --quiet || { fail "$n: exited $?"; continue; }
        for i in 000 001 002; do
            compare "$n view $i: stream vs dfb" "$T/${n}_$i.png" "$T/dfb_$i.png" 0.1
        done
        for o in $(json_all overflow_pixels < "$T/$n.json"); do
            [ "$o" -eq 0 ] || fail "$n: $o pixels got more fragments than their pack's slots"
        done
        packs=$(json_sum packs < "$T/$n.json") drawn=$(json_sum parts_drawn < "$T/$n.json")
        echo "$n: $packs packs for $drawn parts drawn over 3 views"
        [ "$packs" -lt "$drawn" ] || fail "$n: $packs packs for $drawn parts: nothing joined"
    done
done
finish --clean "pack budget"
