#!/bin/sh
# partfile/share.h over real part files (test_share.c says what it asserts):
# the corpus file, `oitgen demo` in parts of 2K triangles, and a fetched mesh
# (bunny00.off) in parts of 512 triangles when the cache has it.
# Usage: test_share.sh TEST_SHARE
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
scratch share
"$OIT_BIN/oitgen" demo -o "$T/demo.ply" >/dev/null || die "oitgen demo"
prep_or_die "$T/demo.ply" "$T/demo.oitp" --part-triangles 2048
files="multi:$(dirname "$0")/../corpus/partfile/small.oitp $T/demo.oitp"
if have_mesh bunny00.off; then
    prep_or_die "$MESH" "$T/bunny.oitp" --part-triangles 512
    files="$files $T/bunny.oitp"
fi
# shellcheck disable=SC2086
"$1" $files || fail "test_share"
finish share
