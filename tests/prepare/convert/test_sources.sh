#!/bin/sh
# Source indices through conversion (docs/part-file.md, PART_DATA): the
# demo scene converted by both schemes, with clipping (--scheme guaranteed;
# --scheme fast with small parts), with a --memory small enough to spill and
# 2 threads (byte-identical to the unspilled file), and the degenerate hard
# case (dropped triangles keep their neighbours' indices: an index is the
# position among the triangles the reader delivers, counted before the
# converter drops any). test_sources checks each file against its source:
# indices in range and every source triangle's area made up by the pieces
# that carry its index; the fast scheme's parts in ascending source order.
# `oitprep verify` reports no source triangle lost.
# usage: test_sources.sh TEST_SOURCES
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
C=${1:?usage: test_sources.sh TEST_SOURCES}
P="$OIT_BIN/oitprep"
G="$OIT_BIN/oitgen"
need_tools "$P" "$G" "$C"
scratch prep_sources

"$G" demo -o "$T/demo.ply" >/dev/null || die "oitgen demo"
gen_hard degenerate "$T/degenerate.ply"

# convert NAME SOURCE [--ascending] -- OITPREP_ARGS...: converts, checks the
# indices, and leaves the stats in $T/NAME.json.
convert() {
    name=$1 src=$2; shift 2
    asc=""
    [ "$1" = "--ascending" ] && { asc=--ascending; shift; }
    [ "$1" = "--" ] && shift
    "$P" "$src" -o "$T/$name.oitp" --stats "$T/$name.json" "$@" >"$T/$name.out" 2>&1 ||
        { fail "$name: oitprep $* exited $?: $(tail -n 2 "$T/$name.out")"; return; }
    "$C" "$src" "$T/$name.oitp" $asc || fail "$name: source indices wrong (oitprep $*)"
}

convert fast "$T/demo.ply" --ascending --
convert fast_clip "$T/demo.ply" --ascending -- --part-triangles 2048
convert fast_spill "$T/demo.ply" --ascending -- --part-triangles 2048 --memory 64K --threads 2
convert guaranteed "$T/demo.ply" -- --scheme guaranteed --threads 1
convert guaranteed_spill "$T/demo.ply" -- --scheme guaranteed --memory 64K --threads 2
convert degenerate "$T/degenerate.ply" -- --scheme guaranteed
convert degenerate_fast "$T/degenerate.ply" --ascending --

for f in fast_clip guaranteed; do
    split=$(json_num split_added <"$T/$f.json")
    [ -n "$split" ] && [ "$split" -gt 0 ] || fail "$f: nothing clipped (split_added $split)"
done
[ "$(json_num cut_slabs <"$T/guaranteed.json")" -gt 0 ] ||
    fail "guaranteed: no cutting planes (their clipped seams go untested)"
for f in fast_spill guaranteed_spill; do
    [ "$(json_num spilled_bytes <"$T/$f.json")" -gt 0 ] || fail "$f: --memory 64K did not spill"
done
cmp -s "$T/fast_clip.oitp" "$T/fast_spill.oitp" ||
    fail "fast: --memory 64K --threads 2 changes the file"
cmp -s "$T/guaranteed.oitp" "$T/guaranteed_spill.oitp" ||
    fail "guaranteed: --memory 64K --threads 2 changes the file"
dropped=$(json_num degenerate_dropped <"$T/degenerate.json")
[ -n "$dropped" ] && [ "$dropped" -gt 0 ] ||
    fail "degenerate: no triangle dropped ($dropped), so index shifts go untested"

for f in fast_clip guaranteed degenerate; do
    "$P" verify "$T/$f.oitp" --directions 4 --viewpoints 2 >"$T/$f.verify" 2>&1 ||
        fail "$f: oitprep verify failed: $(tail -n 3 "$T/$f.verify")"
    grep -q "source triangles: [0-9]* kept, [0-9]* in the parts, 0 lost" "$T/$f.verify" ||
        fail "$f: verify does not report 0 source triangles lost: $(cat "$T/$f.verify")"
done
grep "source triangles" "$T/guaranteed.verify"

finish --clean "source indices"
