#!/bin/sh
# Formats read through assimp, end to end (issue 47): each sample of
# tests/corpus/assimp (FBX, Collada, 3MF, 3DS, IFC) converts with oitprep
# (its "triangles in" the count pinned from `assimp info`, as test_assimp
# checks through the API), verifies (0 order violations, 0 source triangles
# lost) and streams equal to DFB on the source file, bit for bit. The IFC
# wall behind its glass (opacity 0.4) also equals the Embree reference
# outside its ambiguous pixels, and renders differently from the same file
# with the glass made opaque: the material's transparency reaches the image.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
S="$OIT_BIN/oitstream"
P="$OIT_BIN/oitprep"
need_tools "$S" "$P"
scratch assimp_stream
CORPUS=$(dirname "$0")/../corpus/assimp
SIZE=160x120

# sample FILE TRIANGLES: convert, verify, stream vs DFB.
sample() {
    f=$CORPUS/$1 n=$(echo "$1" | tr . _)
    "$P" "$f" -o "$T/$n.oitp" >"$T/$n.prep" 2>&1 || { fail "oitprep $1: $(tail -n 1 "$T/$n.prep")"; return; }
    got=$(sed -n 's/.*: \([0-9]*\) triangles in,.*/\1/p' "$T/$n.prep")
    [ "$got" = "$2" ] || fail "$1: oitprep read $got triangles, assimp counts $2"
    "$P" verify "$T/$n.oitp" >"$T/$n.verify" 2>&1 || fail "verify $1: $(tail -n 2 "$T/$n.verify" | tr '\n' ' ')"
    grep -q "order: 0 violations" "$T/$n.verify" || fail "$1: order violations: $(grep order: "$T/$n.verify")"
    grep -q ", 0 lost" "$T/$n.verify" || fail "$1: lost triangles: $(grep 'source triangles' "$T/$n.verify")"
    "$S" "$f" --method dfb --size $SIZE --out "$T/$n-dfb.png" --quiet 2>"$T/$n.err" || fail "dfb $1: $(cat "$T/$n.err")"
    "$S" "$T/$n.oitp" --method stream --size $SIZE --out "$T/$n-stream.png" --quiet 2>"$T/$n.err" ||
        fail "stream $1: $(cat "$T/$n.err")"
    expect_equal "$1 ($got triangles): stream vs dfb" "$T/$n-stream.png" "$T/$n-dfb.png"
}

sample box.fbx 12
sample kwxport_test_vcolors.dae 12
sample teapot_instancenodes.DAE 2048
sample box.3mf 12
sample cubes_with_alpha.3DS 60
sample wall_glass.ifc 24

"$S" "$T/wall_glass_ifc.oitp" --method reference --size $SIZE --out "$T/ifc-ref.png" \
    --ambiguity "$T/ifc-mask.png" --quiet || fail "reference wall_glass.ifc"
compare "wall_glass.ifc: stream vs reference" "$T/wall_glass_ifc-stream.png" "$T/ifc-ref.png" "$T/ifc-mask.png" 0
sed 's/IFCSURFACESTYLERENDERING(#100,0.6,/IFCSURFACESTYLERENDERING(#100,0.,/' "$CORPUS/wall_glass.ifc" >"$T/opaque_glass.ifc"
cmp -s "$CORPUS/wall_glass.ifc" "$T/opaque_glass.ifc" && fail "the glass's transparency was not found to change"
"$S" "$T/opaque_glass.ifc" --method dfb --size $SIZE --out "$T/opaque-dfb.png" --quiet || fail "dfb opaque glass"
expect_differ "wall_glass.ifc: glass at opacity 0.4 vs opaque" "$T/wall_glass_ifc-dfb.png" "$T/opaque-dfb.png" 100
finish assimp_stream
