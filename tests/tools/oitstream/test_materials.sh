#!/bin/sh
# Materials (issue 37; view/render/image/shade.h, "Opaque triangles") from the command
# line: the OBJ assembly of tests/corpus/obj (three groups, MTL Kd and d,
# a texture map) and the glTF engine when it is fetched.
#   assembly.obj: its groups show their MTL colours (blue and red pixels
#     where the default colour has none), the map_Kd is reported once on
#     stderr, --stats says the opaque pre-pass ran, DFB == the stream ==
#     the Embree reference (outside the reference's ambiguous edge
#     pixels), fewer fragments are stored than with --see-through, which
#     stores every one (stream and DFB alike, within 1% of the reference's
#     hits: its rays and rasterization disagree on edges);
#   2CylinderEngine.glb (all 34 materials OPAQUE): the stream stores one
#     fragment a covered pixel where --see-through stores several, and
#     equals the reference outside its ambiguous pixels.
# PNG_FIGURES (first argument): tests/lib/png_figures.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
FIG=${1:?usage: test_materials.sh PNG_FIGURES}
S="$OIT_BIN/oitstream"
P="$OIT_BIN/oitprep"
need_tools "$S" "$P" "$FIG"
scratch materials
CORPUS=$(dirname "$0")/../../corpus
VIEW="0,0,6,0,0,0,0,1,0,45,0.5,20"

# fragments NAME: the fragments of the first frame of $T/NAME.json
fragments() { json_num fragments "$T/$1.json"; }

"$S" "$CORPUS/obj/assembly.obj" --method dfb --size 160x120 --view "$VIEW" --out "$T/a-dfb.png" \
    --stats "$T/a-dfb.json" --quiet 2>"$T/a.err" || fail "dfb: $(cat "$T/a.err")"
n=$(grep -c "assembly.mtl: map_Kd textures are not supported; using Kd" "$T/a.err")
[ "$n" = 1 ] || fail "the map_Kd note said $n times, want once: $(cat "$T/a.err")"
grep -q "map_d" "$T/a.err" && fail "a second texture note: $(cat "$T/a.err")"
[ "$(json_num opaque "$T/a-dfb.json")" = 1 ] || fail "--stats: opaque is not 1"
set -- $("$FIG" --red-blue "$T/a-dfb.png") 0 0
echo "assembly: red $1 pixels, blue $2 pixels"
[ "${1:-0}" -gt 100 ] && [ "${2:-0}" -gt 100 ] || fail "assembly: the MTL colours are not shown (red $1, blue $2)"
"$P" "$CORPUS/obj/assembly.obj" -o "$T/a.oitp" >"$T/prep.txt" 2>&1 || fail "oitprep: $(tail -n 1 "$T/prep.txt")"
"$S" "$T/a.oitp" --method stream --size 160x120 --view "$VIEW" --out "$T/a-stream.png" \
    --stats "$T/a-stream.json" --quiet || fail "stream"
"$S" "$T/a.oitp" --method reference --size 160x120 --view "$VIEW" --out "$T/a-ref.png" \
    --ambiguity "$T/a-mask.png" --stats "$T/a-ref.json" --quiet || fail "reference"
"$S" "$T/a.oitp" --method stream --see-through --size 160x120 --view "$VIEW" \
    --out "$T/a-see.png" --stats "$T/a-see.json" --quiet || fail "stream --see-through"
"$S" "$T/a.oitp" --method dfb --see-through --size 160x120 --view "$VIEW" \
    --stats "$T/a-dfbsee.json" --quiet || fail "dfb --see-through"
expect_equal "assembly: stream vs dfb" "$T/a-stream.png" "$T/a-dfb.png"
compare "assembly: stream vs reference" "$T/a-stream.png" "$T/a-ref.png" "$T/a-mask.png" 0
echo "assembly: fragments stream $(fragments a-stream), dfb $(fragments a-dfb)," \
    "--see-through $(fragments a-see) (dfb $(fragments a-dfbsee)), reference hits $(fragments a-ref)"
[ "$(fragments a-stream)" = "$(fragments a-dfb)" ] || fail "stream and DFB store different fragments"
[ "$(fragments a-see)" = "$(fragments a-dfbsee)" ] || fail "stream and DFB --see-through store different fragments"
at_most "$(fragments a-ref)" "$(( $(fragments a-see) * 101 / 100 ))" || fail "--see-through stores fewer than the reference hits"
[ "$(fragments a-stream)" -lt "$(fragments a-see)" ] || fail "nothing behind the opaque boxes was culled"
[ "$(json_num opaque "$T/a-see.json")" = 0 ] || fail "--see-through: opaque is not 0"
expect_differ "assembly: --see-through changes the image" "$T/a-see.png" "$T/a-stream.png" 100

if have_mesh 2CylinderEngine.glb; then
    "$P" "$MESH" -o "$T/e.oitp" >"$T/prep.txt" 2>&1 || fail "oitprep engine: $(tail -n 1 "$T/prep.txt")"
    "$S" "$T/e.oitp" --method stream --size 200x200 --out "$T/e-stream.png" --stats "$T/e-stream.json" --quiet || fail "engine stream"
    "$S" "$T/e.oitp" --method stream --see-through --size 200x200 --out "$T/e-see.png" --stats "$T/e-see.json" --quiet || fail "engine stream --see-through"
    "$S" "$T/e.oitp" --method reference --size 200x200 --out "$T/e-ref.png" --ambiguity "$T/e-mask.png" --quiet || fail "engine reference"
    compare "engine: stream vs reference" "$T/e-stream.png" "$T/e-ref.png" "$T/e-mask.png" 0
    covered=$("$FIG" "$T/e-stream.png" | awk '{print $3}')
    echo "engine: fragments $(fragments e-stream) over $covered non-white pixels, --see-through $(fragments e-see)"
    at_most "$(fragments e-stream)" "$((covered * 11 / 10))" || fail "engine: more than about one fragment a covered pixel"
    [ "$(fragments e-see)" -gt "$(( $(fragments e-stream) * 2 ))" ] || fail "engine: --see-through stores too few"
fi
finish materials
