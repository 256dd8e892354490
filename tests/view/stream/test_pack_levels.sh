#!/bin/sh
# The disjoint rule by level (--pack disjoint --schedule wave, view/stream/pack.h)
# end to end on a guaranteed-scheme file (oitgen plant, 10K triangles,
# oitprep --scheme guaranteed, K 8: about 520 small parts whose neighbours'
# rectangles overlap). On 3 orbit views at 128x128, in linear-light PFM:
#   - the image equals the tree's disjoint packs (the paper's rule, nearly
#     one part a pack: about 1.25 parts a pack here) byte for byte: a pack
#     that held two parts sharing a pixel, or drew an overlapping part
#     before one it must follow, changes some pixel's order or overflows
#     its slots. (Not the counted packs: there fragments of two parts at
#     one depth sort by source index, not by part, and 2 of the 3 views
#     differ in a few pixels, docs/ties.md);
#   - no pixel overflows;
#   - the levels take at most half the tree's packs (the file's layout: the
#     tree cuts about 420 packs a view, the levels about 170), and more than
#     one pack a view (the plant is several layers deep).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
need_tools "$S" "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
scratch pack_levels
gen_plant 10000 "$T/plant.ply"
prep_or_die "$T/plant.ply" "$T/g.oitp" --scheme guaranteed --max-layers 8
run() {
    n=$1
    shift
    "$S" "$T/g.oitp" --size 128x128 --orbit 3 "$@" --out "$T/$n.pfm" --stats "$T/$n.json" \
        --quiet || fail "$n: exited $?"
}
run tree --pack disjoint
run levels --pack disjoint --schedule wave
for i in 000 001 002; do
    cmp -s "$T/levels_$i.pfm" "$T/tree_$i.pfm" ||
        fail "view $i: the levels' image differs from the tree's disjoint packs"
done
for o in $(json_all overflow_pixels < "$T/levels.json"); do
    [ "$o" -eq 0 ] || fail "levels: $o pixels got more fragments than their pack's slots"
done
tree=$(json_sum packs < "$T/tree.json") levels=$(json_sum packs < "$T/levels.json")
drawn=$(json_sum parts_drawn < "$T/levels.json")
echo "over 3 views: $drawn parts drawn; tree $tree packs, levels $levels"
[ $((2 * levels)) -le "$tree" ] || fail "levels: $levels packs, more than half the tree's $tree"
[ "$levels" -gt 3 ] || fail "levels: $levels packs for 3 views of a deep plant"
finish --clean "pack levels"
