#!/bin/sh
# The default views' up axis (--up auto, formats/up_axis.h): a STEP file
# and its part file render as with --up z (Z-up, as CAD writes them) and
# not as with --up y, saying so on stderr; a glTF stays y; a hand-written
# OBJ flat in z (a 4 x 3 x 0.4 slab of boxes) renders as with --up z and
# the same OBJ stood up (flat in y) as with --up y; --up y still
# overrides a STEP file; --view needs no note.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
need_tools "$OIT_BIN/oitprep" "$OIT_BIN/oitstream"
S="$OIT_BIN/oitstream"
C="$(cd "$(dirname "$0")/../../corpus" && pwd)"
scratch up_axis
cd "$T" || exit 1

# draw NAME MODEL ARGS...: NAME.png at 96x72, stderr in NAME.err
draw() {
    name=$1 model=$2
    shift 2
    "$S" "$model" --size 96x72 --out "$name.png" "$@" 2>"$name.err" || fail "oitstream $model $*"
}
# box X0 Y0 Z0 X1 Y1 Z1 BASE: an OBJ box's 8 vertices and 12 faces
box() {
    printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $1 $2 $3 $4 $2 $3 $4 $5 $3 $1 $5 $3
    printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $1 $2 $6 $4 $2 $6 $4 $5 $6 $1 $5 $6
    b=$7
    for f in "1 3 2" "1 4 3" "5 6 7" "5 7 8" "1 2 6" "1 6 5" "2 3 7" "2 7 6" "3 4 8" "3 8 7" \
        "4 1 5" "4 5 8"; do
        set -- $f
        echo "f $(($1 + b)) $(($2 + b)) $(($3 + b))"
    done
}

draw step "$C/step/parts.step"
draw step_z "$C/step/parts.step" --up z
draw step_y "$C/step/parts.step" --up y
grep -q "up axis z (STEP and IGES are Z-up; --up overrides)" step.err ||
    fail "no note of the STEP file's up axis: $(cat step.err)"
expect_equal "STEP default vs --up z" step.png step_z.png
expect_differ "STEP default vs --up y" step.png step_y.png 100
grep -q "up axis" step_y.err && fail "--up y still printed a note"
"$OIT_BIN/oitprep" "$C/step/parts.step" -o parts.oitp >/dev/null 2>&1 || fail "oitprep parts.step"
draw part parts.oitp
draw part_z parts.oitp --up z
expect_equal "the STEP's part file: default vs --up z" part.png part_z.png

draw gltf "$C/gltf/scene.gltf"
draw gltf_y "$C/gltf/scene.gltf" --up y
expect_equal "glTF default vs --up y" gltf.png gltf_y.png
grep -q "up axis" gltf.err && fail "a glTF got an up axis note: $(cat gltf.err)"

{ box 0 0 0 1.8 1.4 0.4 0; box 2 0 0 4 1.3 0.3 8; box 0.5 1.6 0 3.5 3 0.35 16; } >flat.obj
{ box 0 0 0 1.8 0.4 1.4 0; box 2 0 0 4 0.3 1.3 8; box 0.5 0 1.6 3.5 0.35 3 16; } >stood.obj
draw flat flat.obj
draw flat_z flat.obj --up z
draw flat_y flat.obj --up y
expect_equal "flat in z: default vs --up z" flat.png flat_z.png
expect_differ "flat in z: default vs --up y" flat.png flat_y.png 50
grep -q "up axis z (flat in z" flat.err || fail "no note for the flat OBJ: $(cat flat.err)"
draw stood stood.obj
draw stood_y stood.obj --up y
expect_equal "flat in y: default vs --up y" stood.png stood_y.png

draw view "$C/step/parts.step" --view 0,0,5,0,0,0,0,1,0,45
grep -q "up axis" view.err && fail "--view printed an up axis note"
finish "up axis"
