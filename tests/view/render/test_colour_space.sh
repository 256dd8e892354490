#!/bin/sh
# Linear-light compositing (oitstream --colour-space linear, view/render/image/shade.h
# "Colour space") through the GL methods against the Embree reference, on
# one input: a numerical hard case (hard CASE, oitgen hard --case CASE,
# vertex colours) or a fetched mesh (mesh FILE in $OIT_MESH_CACHE, no
# colour: the default colour; exit 77 when it is not there). On three views:
#   DFB (part file) == the reference (part file) and the stream (part file)
#   == the reference, in linear light, outside the reference's ambiguity
#   mask: DESIGN.md's tolerance, at most 0.1% of pixels off by > 1/255
#   (8-bit encoded steps: the images are sRGB-encoded in both spaces);
#   linear DFB differs from sRGB-space DFB on >= 5% of pixels (the option
#   is live), and DFB in the default space still equals the reference.
#   On the hard case array, pll, ppll4, b3d, dp (and ddp without depth
#   ties) == DFB in linear light on the source mesh.
#   Three views in transparent shading, one in translucent (the decoded
#   medium colour, Beer-Lambert in linear light).
#   A PFM written and read back holds linear light that encodes to the
#   PNG's bytes (PFM linear-light output, view/render/image/image.h): --compare of the
#   PNG and the PFM of one frame finds no pixel more than 1/255 apart, and
#   the PFM's raw floats are the decoded PNG values (png_figures --pfm-linear).
# usage: test_colour_space.sh hard CASE PNG_FIGURES | mesh FILE PNG_FIGURES
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
KIND=${1:?usage: test_colour_space.sh hard CASE | mesh FILE}
NAME=${2:?usage: test_colour_space.sh hard CASE | mesh FILE}
FIGURES=${3:?usage: test_colour_space.sh hard CASE PNG_FIGURES | mesh FILE PNG_FIGURES}
S="$OIT_BIN/oitstream"
scratch "colour_space_${KIND}_$NAME"
SIZE=128x128
FAIL_PREFIX="$NAME: "
INDENT="    "

case "$KIND" in
hard)
    gen_hard "$NAME" "$T/in.ply"
    IN="$T/in.ply" ;;
mesh)
    need_mesh "$NAME"
    IN=$MESH ;;
*) echo "usage: test_colour_space.sh hard CASE | mesh FILE" >&2; exit 2 ;;
esac
prep_or_die "$IN" "$T/in.oitp"

# The option's spelling: srgb and linear only, a usage error (2) otherwise,
# for oitstream and oitbench alike, and both list it in --help.
for tool in oitstream oitbench; do
    "$OIT_BIN/$tool" "$T/in.oitp" --colour-space gamma >"$T/bad.txt" 2>&1
    rc=$?
    [ $rc -eq 2 ] && grep -q "colour-space 'gamma'.*srgb or linear" "$T/bad.txt" ||
        fail "$tool --colour-space gamma: exit $rc, $(head -n 1 "$T/bad.txt")"
    "$OIT_BIN/$tool" --help 2>&1 | grep -q -- "--colour-space" || fail "$tool --help lacks --colour-space"
done

# view NAME SHADING OPTS...: the checks above from one camera.
view() {
    name=$1 sh=$2; shift 2
    v="$T/$name"
    L="--colour-space linear --shading $sh"
    "$S" "$T/in.oitp" --method stream $L --size "$SIZE" "$@" --out "$v-stream.pfm" \
        --stats "$v-stream.json" --quiet || { fail "$name: stream"; return; }
    cam=$(json_str view "$v-stream.json")
    "$S" "$T/in.oitp" --method dfb $L --size "$SIZE" --view "$cam" --out "$v-dfb.pfm" --quiet ||
        fail "$name: dfb"
    "$S" "$T/in.oitp" --method dfb $L --size "$SIZE" --view "$cam" --out "$v-dfb.png" --quiet ||
        fail "$name: dfb (png)"
    "$S" "$T/in.oitp" --method reference $L --size "$SIZE" --view "$cam" --out "$v-ref.pfm" \
        --ambiguity "$v-mask.png" --quiet || fail "$name: reference"
    "$S" "$T/in.oitp" --method dfb --shading $sh --size "$SIZE" --view "$cam" --out "$v-dfb-srgb.pfm" --quiet ||
        fail "$name: dfb (srgb)"
    "$S" "$T/in.oitp" --method reference --colour-space srgb --shading $sh --size "$SIZE" --view "$cam" \
        --out "$v-ref-srgb.pfm" --ambiguity "$v-mask-srgb.png" --quiet || fail "$name: reference (srgb)"
    echo "  view $name ($sh)"
    compare "linear: dfb vs reference" "$v-dfb.pfm" "$v-ref.pfm" "$v-mask.png" 0.1
    compare "linear: stream vs reference" "$v-stream.pfm" "$v-ref.pfm" "$v-mask.png" 0.1
    compare "srgb: dfb vs reference" "$v-dfb-srgb.pfm" "$v-ref-srgb.pfm" "$v-mask-srgb.png" 0.1
    "$S" --compare "$v-dfb.pfm" "$v-dfb-srgb.pfm" --json >"$T/cmp.json" || fail "$name: compare"
    d=$(json_num pct_over_1_255 "$T/cmp.json")
    echo "    linear vs srgb (dfb): over 1/255 $d% (at least 5%)"
    at_most 5 "$d" || fail "$name: linear and sRGB compositing differ on only $d% of pixels"
    compare "png vs pfm of one frame" "$v-dfb.png" "$v-dfb.pfm" 0
    if [ -n "$FIGURES" ]; then
        r=$("$FIGURES" --pfm-linear "$v-dfb.pfm" "$v-dfb.png") ||
            fail "$name: the PFM is not the PNG's frame in linear light: $r"
        echo "    pfm linear vs png (values, raw and read-back 8-bit mismatches, mid-tones, mid-tones apart): $r"
    fi
}

view az30 transparent --azimuth 30 --elevation 35
# Every GL method composites through the shared GLSL (frag_glsl.h): on the
# hard case the other exact methods equal DFB in linear light too (on the
# source mesh, from az30; dp and ddp where ddp can order the case).
if [ "$KIND" = hard ]; then
    cam=$(json_str view "$T/az30-stream.json")
    "$S" "$IN" --method dfb --colour-space linear --size "$SIZE" --view "$cam" \
        --out "$T/m-dfb.pfm" --quiet || fail "dfb on the mesh"
    for m in array pll ppll4 b3d dp ddp; do
        case "$m:$NAME" in ddp:coplanar*|ddp:touching) continue ;; esac
        "$S" "$IN" --method $m --colour-space linear --size "$SIZE" --view "$cam" \
            --out "$T/m-$m.pfm" --quiet || { fail "$m (linear)"; continue; }
        compare "linear: $m vs dfb (mesh)" "$T/m-$m.pfm" "$T/m-dfb.pfm" 0.1
    done
fi
view az210 transparent --azimuth 210 --elevation 35
view below transparent --azimuth 120 --elevation -25
view tl30 translucent --azimuth 30 --elevation 35

finish "$NAME (colour space)"
