#!/bin/sh
# VTK files end to end: a .vtp (appended, base64, zlib: VTK's default
# writer settings), the same gzipped, and a legacy unstructured .vtk that
# VTK 9.1 wrote (tests/corpus) convert with oitprep, their triangles_in
# equal to the count VTK's own reader gives (NAME.expected, first line), the
# part file's colour attributes (colour, alpha, opaque) those of the file, and
# `oitprep verify` exits 0 with no order violation and no triangle lost.
# usage: test_vtk_convert.sh CORPUS
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
C=${1:?usage: test_vtk_convert.sh CORPUS}
P="$OIT_BIN/oitprep"
need_tools "$P"
command -v gzip >/dev/null || skip "gzip not installed"
scratch vtk_convert

gzip -9nc "$C/vtp/poly_appended.vtp" >"$T/poly_appended.vtp.gz"
# check SOURCE EXPECTED
check() {
    src=$1 name=$(basename "$1")
    want=$(sed -n 's/^triangles \([0-9]*\) .*/\1/p' "$2")
    expect_rc 0 "$P" "$src" -o "$T/$name.oitp" --stats "$T/$name.json"
    got=$(json_num triangles_in "$T/$name.json")
    [ "$got" = "$want" ] || fail "$name: oitprep read $got triangles, VTK's reader $want"
    # the colour bits reach the part file: 1 colour, 2 alpha, 4 opaque
    bits=$(sed -n 's/^triangles [0-9]* attributes \([0-9]*\) .*/\1/p' "$2")
    want_attr=$( [ $((bits & 1)) -ne 0 ] && printf '"color"'
                 [ $((bits & 2)) -ne 0 ] && printf ', "alpha"'
                 [ $((bits & 4)) -ne 0 ] && printf ', "opaque"')
    expect_rc 0 "$P" info "$T/$name.oitp" --json
    attr=$(grep -o '"attributes": \[[^]]*\]' "$T/out.txt")
    [ "$attr" = "\"attributes\": [$want_attr]" ] ||
        fail "$name: part file $attr, expected [$want_attr]"
    expect_rc 0 "$P" verify "$T/$name.oitp"
    grep -q "order: 0 violations" "$T/out.txt" && grep -q " in the parts, 0 lost" "$T/out.txt" ||
        fail "$name: verify: $(cat "$T/out.txt")"
}
check "$C/vtp/poly_appended.vtp" "$C/vtp/poly_appended.vtp.expected"
check "$T/poly_appended.vtp.gz" "$C/vtp/poly_appended.vtp.expected"
check "$C/vtk/ugrid_ascii_51.vtk" "$C/vtk/ugrid_ascii_51.vtk.expected"
finish --clean "vtk convert"
