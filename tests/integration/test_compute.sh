#!/bin/sh
# The compute capture (view/render/capture/capture_compute.h) end to end, in core
# (oitstream --method compute: the mesh as one batch) and streamed
# (--method stream --capture compute, many packs under a small upload
# budget), against the Embree reference and DFB on the same triangles (the
# source mesh in core, the part file streamed), outside the reference's
# ambiguity mask (pixel centres within 1/64 pixel of a triangle edge, where
# the compute capture's fill rule and the rasterizer's may disagree):
#   against the reference, at most 0.01% of the other pixels over 1/255;
#   against DFB, at most 0.01% more than DFB's own share off the reference
#   (thin: 0.1%, slivers 1e-3 wide where GL's snapped vertices and the
#   exact pixel centres part; the compute capture matches the reference);
# on hard cases (coincident faces, perspective and orthographic; a decal
# 1e-5 above its surface; slivers and zero-area triangles; 64 slivers
# across the view; opaque boxes in a transparent sphere; 600 layers, seen
# from outside and from between the layers, the near plane cutting them; a
# lattice seen from inside, triangles behind the eye), the demo scene and
# the bunny where it was fetched (else noted). Then, on the demo: the
# translucent and linear shadings and a section plane (against DFB), early
# termination (within epsilon of exact, fewer fragments), and oitbench
# --methods compute,dfb. Small frames: the sweeps of 600 layers are slow on
# llvmpipe.
# PART (the first argument) runs a third of it, for ctest to run the three
# side by side: hard (the hard cases), models (the demo and the bunny) or
# options (on the demo: the shadings, a section plane, early termination,
# oitbench); all: every one.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
PART=${1:-all}
case "$PART" in all|hard|models|options) ;; *) die "usage: test_compute.sh [all|hard|models|options]" ;; esac
want() { [ "$PART" = all ] || [ "$PART" = "$1" ]; }
need_every_tool
scratch "compute_capture_$PART"
INDENT="  "

# against NAME IMG DFB REF MASK: IMG against REF within 0.01% and against
# DFB within 0.01% more than DFB is from REF, outside MASK.
against() {
    compare "$1 vs reference" "$2" "$4" "$5" 0.01
    "$S" --compare "$3" "$4" --mask "$5" --json >"$T/cmp.json" || { fail "$1: compare"; return; }
    _lim=$(awk -v p="$(json_num pct_over_1_255_outside_mask "$T/cmp.json")" \
        'BEGIN { printf "%.4f", p + 0.01 }')
    compare "$1 vs dfb" "$2" "$3" "$5" "$_lim"
}

# check NAME MESH SIZE VIEW...: compute in core on MESH and streamed on its
# part file (MESH with .oitp for its suffix), each against DFB and the
# reference on the same triangles.
check() {
    name=$1 mesh=$2 size=$3
    shift 3
    v="$T/$name" parts="${mesh%.*}.oitp"
    for in in mesh parts; do
        eval "src=\$$in"
        "$S" "$src" --method reference --size "$size" "$@" --out "$v-$in-ref.pfm" \
            --ambiguity "$v-$in-mask.png" --quiet || { fail "$name: reference ($in)"; return; }
        "$S" "$src" --method dfb --size "$size" "$@" --out "$v-$in-dfb.pfm" \
            --stats "$v-$in-dfb.json" --quiet || { fail "$name: dfb ($in)"; return; }
    done
    "$S" "$mesh" --method compute --size "$size" "$@" --out "$v-cs.pfm" --stats "$v-cs.json" \
        --quiet || { fail "$name: compute"; return; }
    "$S" "$parts" --method stream --capture compute --upload-budget 64K \
        --size "$size" "$@" --out "$v-st.pfm" --stats "$v-st.json" --quiet ||
        { fail "$name: stream --capture compute"; return; }
    echo "$name: layers $(json_num max_layers "$v-mesh-dfb.json"), fragments dfb" \
        "$(json_num fragments "$v-mesh-dfb.json"), compute $(json_num fragments "$v-cs.json");" \
        "part file: dfb $(json_num fragments "$v-parts-dfb.json"), stream" \
        "$(json_num fragments "$v-st.json") in $(json_num packs "$v-st.json") packs"
    against "compute" "$v-cs.pfm" "$v-mesh-dfb.pfm" "$v-mesh-ref.pfm" "$v-mesh-mask.png"
    against "stream --capture compute" "$v-st.pfm" "$v-parts-dfb.pfm" "$v-parts-ref.pfm" \
        "$v-parts-mask.png"
}

# mesh NAME: $T/NAME.ply (a hard case) and its part file, small parts.
mesh() {
    gen_hard "$1" "$T/$1.ply"
    prep_or_die "$T/$1.ply" "$T/$1.oitp" --max-piece-triangles 200
}

A="--azimuth 30 --elevation 35"
if want hard; then
for c in coplanar decal degenerate thin mixed stack dense; do mesh $c; done
# shellcheck disable=SC2086 # A is two options
check coplanar "$T/coplanar.ply" 64x64 $A
# shellcheck disable=SC2086
check coplanar_ortho "$T/coplanar.ply" 64x64 $A --ortho fit
check decal "$T/decal.ply" 64x64 --azimuth 210 --elevation 35
# shellcheck disable=SC2086
check degenerate "$T/degenerate.ply" 64x64 $A
# shellcheck disable=SC2086
check thin "$T/thin.ply" 64x64 $A
# shellcheck disable=SC2086
check mixed "$T/mixed.ply" 64x64 $A
# shellcheck disable=SC2086
check stack "$T/stack.ply" 24x24 $A
check stack_inside "$T/stack.ply" 24x24 --view 0.05,0.02,0.0015,0.05,0.02,1,0,1,0,70,0.05,5
check dense_inside "$T/dense.ply" 48x48 --view 0.01,0.02,0.03,1,0.7,0.4,0,0,1,80,0.1,10

fi

if want models || want options; then
"$G" demo -o "$T/demo.ply" >/dev/null || die "oitgen demo"
prep_or_die "$T/demo.ply" "$T/demo.oitp" --max-piece-triangles 1000
fi

if want models; then
# shellcheck disable=SC2086
check demo "$T/demo.ply" 96x96 $A
if have_mesh bunny00.off; then
    cp "$MESH" "$T/bunny.off" && prep_or_die "$T/bunny.off" "$T/bunny.oitp" \
        --max-piece-triangles 1000 &&
        check bunny "$T/bunny.off" 96x96 --azimuth 60 --elevation 20
fi
fi

if want options; then

# Shadings and a section plane on the demo, in core and streamed.
for opt in "--shading translucent" "--colour-space linear" "--clip 0.3,1,0.2,0"; do
    # shellcheck disable=SC2086 # opt is an option and its value
    "$S" "$T/demo.ply" --method dfb --size 64x64 $A $opt --out "$T/o-dfb.pfm" --quiet &&
        "$S" "$T/demo.ply" --method compute --size 64x64 $A $opt --out "$T/o-cs.pfm" --quiet &&
        "$S" "$T/demo.oitp" --method stream --capture compute --size 64x64 $A $opt \
            --upload-budget 64K --out "$T/o-st.pfm" --quiet || { fail "$opt: a method failed"; continue; }
    "$S" "$T/demo.ply" --method reference --size 64x64 $A $opt --out "$T/o-ref.pfm" \
        --ambiguity "$T/o-mask.png" --quiet || { fail "$opt: reference"; continue; }
    against "compute ($opt)" "$T/o-cs.pfm" "$T/o-dfb.pfm" "$T/o-ref.pfm" "$T/o-mask.png"
    "$S" "$T/demo.oitp" --method dfb --size 64x64 $A $opt --out "$T/o-pdfb.pfm" --quiet &&
        "$S" "$T/demo.oitp" --method reference --size 64x64 $A $opt --out "$T/o-pref.pfm" \
            --ambiguity "$T/o-pmask.png" --quiet || { fail "$opt: part file dfb, reference"; continue; }
    against "stream --capture compute ($opt)" "$T/o-st.pfm" "$T/o-pdfb.pfm" "$T/o-pref.pfm" \
        "$T/o-pmask.png"
done

# Early termination: within epsilon of the exact image, fewer fragments.
"$S" "$T/demo.oitp" --method stream --capture compute --epsilon 0.05 --upload-budget 64K \
    --size 64x64 $A --out "$T/e.pfm" --stats "$T/e.json" --quiet || fail "stream --epsilon 0.05"
"$S" "$T/demo.oitp" --method stream --capture compute --upload-budget 64K --size 64x64 $A \
    --out "$T/x.pfm" --stats "$T/x.json" --quiet || fail "stream exact"
"$S" --compare "$T/e.pfm" "$T/x.pfm" --json >"$T/cmp.json" || fail "compare epsilon"
ma=$(json_num max_abs "$T/cmp.json") fe=$(json_num fragments "$T/e.json") fx=$(json_num fragments "$T/x.json")
echo "epsilon 0.05: max_abs $ma from exact, fragments $fe of $fx"
at_most "$ma" 0.0540 || fail "epsilon 0.05: $ma from the exact image"
[ "$fe" -lt "$fx" ] || fail "epsilon 0.05: $fe fragments, no fewer than exact ($fx)"

# oitbench's method entry.
"$BN" "$T/demo.ply" --methods compute,dfb --size 64x64 --frames 1 --warmup 0 --orbit 1 \
    --out "$T/bench" >"$T/bench.txt" 2>&1 || fail "oitbench --methods compute,dfb: $(tail -n 2 "$T/bench.txt")"
grep -q '^compute' "$T/bench/"*.csv 2>/dev/null || grep -q 'compute' "$T/bench/"*.csv ||
    fail "oitbench wrote no compute row"

fi

finish --clean "compute_capture ($PART)"
