#!/bin/sh
# oitprep verify's slab check, on test_streamer's grid file (one slab, normal
# +z, with a box below, a thin box inside and a box above): the file passes
# with 0 vertices on the wrong side; with the slab's planes moved 0.05 up
# (the inside box then reaches below d0) verify exits 1 and names the slab.
# usage: test_verify_slab.sh TEST_STREAMER
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
W=$1
scratch verify_slab
"$W" "$T/good.oitp" && "$W" "$T/bad.oitp" --bad-slab || die "test_streamer"

"$OIT_BIN/oitprep" verify "$T/good.oitp" >"$T/good.txt" 2>&1 ||
    fail "verify rejects the good file: $(cat "$T/good.txt")"
grep -q "slabs: 1, 0 vertices on the wrong side" "$T/good.txt" ||
    fail "good file: $(grep slabs "$T/good.txt")"
grep slabs "$T/good.txt"

"$OIT_BIN/oitprep" verify "$T/bad.oitp" >"$T/bad.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "verify exits $rc on the bad slab, want 1"
grep -q "slabs: 1, [1-9][0-9]* vertices on the wrong side" "$T/bad.txt" ||
    fail "bad file: $(grep slabs "$T/bad.txt")"
grep -q "first violation: .*(slab 0, part" "$T/bad.txt" ||
    fail "bad file: the first violation does not name the slab: $(cat "$T/bad.txt")"
grep "slabs\|first violation" "$T/bad.txt"

# A part whose recorded layer bound is one less than the hits a ray gets
# (a closed box recorded with bound 1: 2 hits) fails the bound check.
"$W" "$T/bound.oitp" --understated-bound || die "test_streamer --understated-bound"
"$OIT_BIN/oitprep" verify "$T/bound.oitp" >"$T/bound.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "verify exits $rc on a bound one too low, want 1"
grep -q "gives 2 hits, more than its bound" "$T/bound.txt" ||
    fail "understated bound: no part named with 2 hits over its bound: $(cat "$T/bound.txt")"
grep "hits\|violation" "$T/bound.txt" | head -n 3

# The same bound in a file of measured bounds (oitprep --scheme fast's flag):
# an estimate, so verify passes and reports the excess; with the slab's two
# parts swapped as well, its order and slab violations still fail it.
"$W" "$T/measured.oitp" --measured && "$W" "$T/swapped.oitp" --measured-swapped ||
    die "test_streamer --measured"
"$OIT_BIN/oitprep" verify "$T/measured.oitp" >"$T/measured.txt" 2>&1
rc=$?
[ "$rc" -eq 0 ] || fail "verify exits $rc on a measured bound one too low, want 0: $(cat "$T/measured.txt")"
grep -q "measured bounds, not guaranteed.*; [1-9][0-9]* part-rays over it, by at most 1 " "$T/measured.txt" &&
    grep -q "order: 0 violations" "$T/measured.txt" ||
    fail "measured bound: excess not reported: $(cat "$T/measured.txt")"
grep "layers" "$T/measured.txt"
"$OIT_BIN/oitprep" verify "$T/swapped.oitp" >"$T/swapped.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "verify exits $rc on swapped slab parts with measured bounds, want 1"
grep -q "order: [1-9][0-9]* violations" "$T/swapped.txt" &&
    grep -q "slabs: 1, [1-9][0-9]* vertices on the wrong side" "$T/swapped.txt" ||
    fail "swapped slab parts: $(cat "$T/swapped.txt")"
grep "order\|slabs" "$T/swapped.txt"

finish "verify slab check"
