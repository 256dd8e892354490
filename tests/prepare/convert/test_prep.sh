#!/bin/sh
# oitprep end to end on a generated plant (oitgen plant, 10K triangles),
# Wang & Xie's guaranteed scheme unless said otherwise:
#   convert at --max-layers 16 with --stats (every documented key present,
#   triangles conserved), `info` and `verify` (0 violations); the file is
#   byte-identical for --threads 1/2 and under a --memory small enough to
#   spill, in both schemes; oitstream --method stream equals --method dfb on it (2 views, no
#   pixel over 1/255, no overflow); bad inputs exit 3 naming the file, a
#   missing one exits 1. At the default K = 8, `oitgen demo` and a
#   16-sector saddle (a wide part) convert, verify, and stream exactly, and
#   8 diagonal bars side by side become a slab cell with nothing clipped;
#   the demo has cutting planes, which save triangles over --slabs
#   separating, and verifies alike in one Embree scene or many; a 100K plant streams unsplit though a few pixels pass 32
#   layers.
# PART (the first argument) runs a third of it, for ctest to run the three
# side by side: plant (a-e, g, h), demo (f, f2) or p100k (i); all: every one.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
PART=${1:-all}
case "$PART" in all|plant|demo|p100k) ;; *) die "usage: test_prep.sh [all|plant|demo|p100k]" ;; esac
want() { [ "$PART" = all ] || [ "$PART" = "$1" ]; }
P="$OIT_BIN/oitprep"
# Wang & Xie's scheme, whose guarantees (layer bounds, slabs, wide parts) this
# file checks; the default fast scheme has tests/prepare/convert/test_fast_scheme.sh, and
# here its determinism (b, c).
GUAR="--scheme guaranteed"
G="$OIT_BIN/oitgen"
S="$OIT_BIN/oitstream"
need_tools "$P" "$G" "$S"
scratch "prep_$PART"

# verify_clean NAME FILE: oitprep verify FILE exits 0 and reports no layer
# and no order violation (its report left in $T/out.txt).
verify_clean() {
    expect_rc 0 "$P" verify "$2"
    grep -q "; 0 violations" "$T/out.txt" && grep -q "order: 0 violations" "$T/out.txt" ||
        fail "$1: verify: $(cat "$T/out.txt")"
}

# stream_vs_dfb NAME FILE "STREAM_OPTIONS" OPTION...: the stream of FILE
# with STREAM_OPTIONS and OPTION... (size and view; image $T/vs.png, stats
# $T/vs.json) against DFB with OPTION... ($T/vd.png): no overflow pixel, and
# at most 0.1% of the pixels off by more than 1/255.
stream_vs_dfb() {
    name=$1 file=$2 stream_opts=$3
    shift 3
    # shellcheck disable=SC2086
    "$S" "$file" $stream_opts "$@" --out "$T/vs.png" --stats "$T/vs.json" --quiet &&
        "$S" "$file" --method dfb "$@" --out "$T/vd.png" --quiet || fail "$name: oitstream $*"
    grep -q '"overflow_pixels": 0,' "$T/vs.json" || fail "$name: stream overflow ($*)"
    compare "$name: stream vs dfb" "$T/vs.png" "$T/vd.png" 0.1
}

if want plant; then
# (a) conversion, its figures, info and verify
M="$T/plant.ply"
gen_plant 10000 "$M"
expect_rc 0 "$P" "$M" $GUAR -o "$T/t0.oitp" --max-layers 16 --stats "$T/s.json"
for key in triangles_in triangles_out degenerate_dropped split_added pieces parts slabs \
    cells subgrid_depth seconds stages peak_rss_bytes; do
    grep -q "\"$key\":" "$T/s.json" || fail "stats JSON lacks \"$key\""
done
tin=$(json_num triangles_in <"$T/s.json")
tout=$(json_num triangles_out <"$T/s.json")
drop=$(json_num degenerate_dropped <"$T/s.json")
split=$(json_num split_added <"$T/s.json")
parts=$(json_num parts <"$T/s.json")
pieces=$(json_num pieces <"$T/s.json")
secs=$(json_num total <"$T/s.json")
echo "plant: triangles in $tin, out $tout (split +$split, degenerate -$drop)," \
    "$pieces pieces, $parts parts, $secs s"
# Every input triangle is stored or accounted for: nothing may be lost.
[ -n "$tin" ] && [ "$tin" -ge 9990 ] && [ "$tin" -le 10010 ] ||
    fail "triangles_in $tin, want 10000 +- 0.1%"
[ -n "$tout" ] && [ "$tout" -eq $((tin + split - drop)) ] ||
    fail "triangles_out $tout != in $tin + split $split - dropped $drop"
[ -n "$parts" ] && [ "$parts" -ge 1 ] || fail "parts $parts"

expect_rc 0 "$P" info "$T/t0.oitp" --json
itri=$(json_num triangles <"$T/out.txt")
iparts=$(json_num parts <"$T/out.txt")
[ "$itri" = "$tout" ] && [ "$iparts" = "$parts" ] ||
    fail "info says $itri triangles / $iparts parts, stats $tout / $parts"
expect_rc 0 "$P" verify "$T/t0.oitp"
cat "$T/out.txt"
grep -q "; 0 violations" "$T/out.txt" || fail "verify: layer violations"
grep -q "order: 0 violations" "$T/out.txt" || fail "verify: order violations"

# (b), (c) determinism across threads and the spill path
expect_rc 0 "$P" "$M" $GUAR -o "$T/t1.oitp" --max-layers 16 --threads 1
expect_rc 0 "$P" "$M" $GUAR -o "$T/t2.oitp" --max-layers 16 --threads 2
cmp -s "$T/t1.oitp" "$T/t2.oitp" || fail "--threads 1 and --threads 2 differ"
cmp -s "$T/t0.oitp" "$T/t1.oitp" || fail "--threads 1 differs from the default"
expect_rc 0 "$P" "$M" $GUAR -o "$T/m.oitp" --max-layers 16 --threads 2 --memory 64K \
    --stats "$T/m.json"
cmp -s "$T/t1.oitp" "$T/m.oitp" || fail "--memory 64K (spill) changes the file"
spilled=$(json_num spilled_bytes <"$T/m.json")
[ -n "$spilled" ] && [ "$spilled" -gt 0 ] || fail "--memory 64K did not spill ($spilled bytes)"
echo "determinism: threads 1/2 and --memory 64K (spilled $spilled bytes) byte-identical" \
    "($(wc -c <"$T/t1.oitp") bytes)"
expect_rc 0 "$P" "$M" -o "$T/f1.oitp" --threads 1
expect_rc 0 "$P" "$M" -o "$T/f2.oitp" --threads 2 --memory 64K --stats "$T/f.json"
cmp -s "$T/f1.oitp" "$T/f2.oitp" || fail "fast scheme: --threads 2 --memory 64K changes the file"
grep -q '"scheme": "fast"' "$T/f.json" || fail "the default scheme is not fast"
[ "$(json_num spilled_bytes <"$T/f.json")" -gt 0 ] || fail "fast scheme: --memory 64K did not spill"
cmp -s "$T/f1.oitp" "$T/t1.oitp" && fail "the fast and guaranteed files are the same"

# (d) streamed image equals DFB on the converted file
if "$S" "$T/t0.oitp" --method stream --max-layers 16 --size 96x96 --orbit 2 \
        --out "$T/s.png" --stats "$T/st.json" --quiet >"$T/out.txt" 2>&1 &&
    "$S" "$T/t0.oitp" --method dfb --size 96x96 --orbit 2 --out "$T/d.png" --quiet \
        >>"$T/out.txt" 2>&1; then
    for o in $(json_all overflow_pixels "$T/st.json"); do
        [ "$o" -eq 0 ] || fail "stream: $o overflow pixels"
    done
    grep -q '"overflow_pixels"' "$T/st.json" || fail "stream stats lack overflow_pixels"
    for i in 000 001; do
        # The plant is clash-free, so no two parts' surfaces cross. Where
        # they do (oitgen plant --clashes allow), a pixel can get fragments
        # of equal depth from two packs, which DFB orders by primitive id
        # and the stream by pack order: a pixel or two, never more.
        compare "view $i: stream vs dfb" "$T/s_$i.png" "$T/d_$i.png" 0.01
    done
else
    fail "oitstream on the part file: $(tail -n 2 "$T/out.txt")"
fi

# (e) bad and missing inputs
# Cut in the middle of the binary body, not in the header.
head -c $(($(wc -c <"$M") / 2)) "$M" >"$T/trunc.ply"
expect_rc 3 "$P" "$T/trunc.ply" -o "$T/x.oitp" --max-layers 16
grep -q "trunc.ply" "$T/err.txt" || fail "truncated input: stderr does not name the file"
echo "truncated input: $(head -n 1 "$T/err.txt")"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2 zz\n' >"$T/garbage.ply"
expect_rc 3 "$P" "$T/garbage.ply" -o "$T/x.oitp" --max-layers 16
grep -q "garbage.ply" "$T/err.txt" || fail "garbage input: stderr does not name the file"
expect_rc 1 "$P" "$T/missing.ply" -o "$T/x.oitp"
grep -q "missing.ply" "$T/err.txt" || fail "missing input: stderr does not name the file"
expect_rc 2 "$P" "$M" -o "$T/x.oitp" --max-layers 7

fi

if want demo; then
# (f) the default K (8): `oitgen demo`, and a saddle of 16 sectors around one
# vertex, alternately up and down. No box around that vertex holds fewer
# than its 8 two-plane pieces (16 layers), so it must become a wide part:
# converted, verified, and streamed exactly with zero overflow.
# The centre is off every grid and kd plane (those would cut it into
# quadrants, each with few enough sectors).
awk 'BEGIN { n = 16; print "OFF"; print n + 1, n, 0; print 0.31, 0.17, 0.05;
    for (i = 0; i < n; i++) { a = 2 * 3.14159265358979 * i / n;
        printf "%.9f %.9f %.9f\n", 0.31 + cos(a), 0.17 + sin(a), (i % 2 ? -0.55 : 0.65) }
    for (i = 0; i < n; i++) print 3, 0, 1 + i, 1 + (i + 1) % n }' >"$T/saddle.off"
"$G" demo -o "$T/demo.ply" >/dev/null || fail "oitgen demo"
for case in demo.ply saddle.off; do
    expect_rc 0 "$P" "$T/$case" $GUAR -o "$T/$case.oitp" --stats "$T/$case.json"
    verify_clean "$case" "$T/$case.oitp"
    cp "$T/out.txt" "$T/verify_$case.txt" # (f2) reads the demo's again
    wide=$(json_num wide_parts <"$T/$case.json")
    lb=$(json_num max_layer_bound <"$T/$case.json")
    echo "$case at K=8: $(json_num triangles_in <"$T/$case.json") -> " \
        "$(json_num triangles_out <"$T/$case.json") triangles," \
        "$(json_num pieces_clustered <"$T/$case.json") pieces clustered," \
        "$(json_num parts <"$T/$case.json") parts, $wide wide (max bound $lb)"
    stream_vs_dfb "$case" "$T/$case.oitp" "--pack disjoint" --size 96x96 --azimuth 30 --elevation 60
done
# (f2) cutting planes (prepare/partition/kd_cut.h): the demo has nodes of at most
# 2K layers that no axis plane splits cleanly and no gap separates; some
# become two parts either side of an integer-normal plane. verify above
# checked their seam vertices exactly on the plane and the stream equal to
# DFB; here: there are some, and without them (--slabs separating) the kd's
# axis splits clip more triangles into more parts.
cuts=$(json_num cut_slabs <"$T/demo.ply.json")
grep -q "slabs: $(json_num slabs <"$T/demo.ply.json"), 0 vertices" "$T/verify_demo.ply.txt" ||
    fail "demo: verify slab sides: $(cat "$T/verify_demo.ply.txt")"
expect_rc 0 "$P" "$T/demo.ply" $GUAR -o "$T/sep.oitp" --slabs separating --stats "$T/sep.json"
t_cut=$(json_num triangles_out <"$T/demo.ply.json")
t_sep=$(json_num triangles_out <"$T/sep.json")
echo "demo: $cuts cutting planes; $t_cut triangles, $t_sep with --slabs separating"
[ "$cuts" -gt 0 ] && [ "$(json_num cut_slabs <"$T/sep.json")" -eq 0 ] &&
    [ "$t_cut" -lt "$t_sep" ] ||
    fail "demo: $cuts cutting planes, $t_cut triangles; --slabs separating: $t_sep"
# verify in Embree scenes of at most 20K triangles, built one at a time,
# gives the same figures as one scene (hits merged per ray across scenes).
cp "$T/verify_demo.ply.txt" "$T/v1.txt" # (f)'s verify, in one scene
"$P" verify "$T/demo.ply.oitp" --chunk-triangles 20K >"$T/vc.txt" 2>&1
scenes=$(sed -n 's/.*parts (\([0-9]*\) Embree scenes*).*/\1/p' "$T/vc.txt")
sed 's/ ([0-9]* Embree scenes*)//' "$T/v1.txt" >"$T/v1s.txt"
sed 's/ ([0-9]* Embree scenes*)//' "$T/vc.txt" >"$T/vcs.txt"
echo "demo: verify in $scenes scenes of <= 20K triangles: $(head -n 1 "$T/vcs.txt")"
[ -n "$scenes" ] && [ "$scenes" -gt 1 ] && cmp -s "$T/v1s.txt" "$T/vcs.txt" ||
    fail "verify --chunk-triangles 20K ($scenes scenes) differs: $(diff "$T/v1s.txt" "$T/vcs.txt")"
"$P" info "$T/demo.ply.oitp" --json >"$T/info.json" 2>&1
[ "$(json_num cut_slabs <"$T/info.json")" = "$cuts" ] ||
    fail "info --json: cut_slabs $(json_num cut_slabs <"$T/info.json"), the conversion made $cuts"
# oitprep parts: every stored triangle written once, coloured by kind, and
# the PLY renders.
expect_rc 0 "$P" parts "$T/demo.ply.oitp" -o "$T/parts.ply" --colour kind
echo "demo parts: $(cat "$T/out.txt")"
grep -q "$(json_num parts <"$T/demo.ply.json") parts, $t_cut triangles" "$T/out.txt" &&
    ! grep -q " 0 of cutting planes" "$T/out.txt" ||
    fail "oitprep parts: $(cat "$T/out.txt"), want $t_cut triangles and cutting-plane parts"
"$S" "$T/parts.ply" --method dfb --size 64x64 --out "$T/parts.png" --quiet ||
    fail "oitstream cannot render the parts PLY"
expect_rc 2 "$P" parts "$T/demo.ply.oitp" -o "$T/parts.ply" --colour hue
expect_rc 2 "$P" parts "$T/demo.ply.oitp"
expect_rc 3 "$P" parts "$T/demo.ply" -o "$T/parts.ply"
expect_rc 2 "$P" "$T/demo.ply" $GUAR -o "$T/x.oitp" --slabs some
grep -q "want all, separating or none" "$T/err.txt" || fail "--slabs some: $(cat "$T/err.txt")"

[ "$(json_num wide_parts <"$T/saddle.off.json")" -ge 1 ] &&
    [ "$(json_num max_layer_bound <"$T/saddle.off.json")" -gt 8 ] ||
    fail "saddle: no wide part (the star was split or refused)"

fi

if want plant; then
# (g) the management schemes of Wang & Xie's Table 1 on the plant: each is one
# kd-tree over the model (--grid 1: one top cell an axis, two where the
# bounds straddle a power-of-two coordinate); kd-facets keeps no convex
# piece of more than one triangle, so every part's bound is its facet count.
# Each must verify and stream exactly.
for m in kd-parts kd-facets; do
    expect_rc 0 "$P" "$M" -o "$T/$m.oitp" --manage $m --stats "$T/$m.json"
    grep -q "\"manage\": \"$m\"" "$T/$m.json" || fail "$m: stats do not name the scheme"
    grep -q '"grid": \[[12], [12], [12]\]' "$T/$m.json" ||
        fail "$m: top grid $(grep -o '"grid": [^]]*]' "$T/$m.json"), want one cell an axis (two where the bounds straddle a power of two)"
    verify_clean "$m" "$T/$m.oitp"
    stream_vs_dfb "$m" "$T/$m.oitp" "" --size 96x96 --azimuth 30 --elevation 40
    echo "--manage $m: $(json_num parts <"$T/$m.json") parts," \
        "$(json_num pieces <"$T/$m.json") pieces, $(json_num triangles_out <"$T/$m.json")" \
        "triangles; stream vs dfb over 1/255 $PCT%"
done
# No two facets merged: at least one piece per input triangle (the cell clip
# may split a few), where convex clustering merges most of them.
[ "$(json_num pieces_clustered <"$T/kd-facets.json")" -ge "$tin" ] ||
    fail "kd-facets: $(json_num pieces_clustered <"$T/kd-facets.json") pieces clustered for $tin triangles"
[ "$(json_num pieces_clustered <"$T/kd-parts.json")" -lt $((tin / 2)) ] ||
    fail "kd-parts: $(json_num pieces_clustered <"$T/kd-parts.json") pieces clustered for $tin triangles"
expect_rc 2 "$P" "$M" -o "$T/x.oitp" --manage kd-facets --grid 4
grep -q "grid 4" "$T/err.txt" || fail "--manage kd-facets --grid 4: $(cat "$T/err.txt")"
expect_rc 2 "$P" "$M" -o "$T/x.oitp" --manage octree

# (h) separating slabs: 8 closed bars side by side (16 layers, 2K), all
# running diagonally in x-y. Every axis plane through their common box cuts
# some, so before slabs the kd clip cut them up; a diagonal plane parts 4
# from 4. Expected: a slab, 2 parts, no triangle added, verify (slab sides
# included) and the stream agreeing with DFB from views on both sides and
# from the gap between the groups, looking along the bars.
for nb in 8; do
    awk -v nb=$nb 'BEGIN { r = sqrt(0.5); print "OFF"; print 8 * nb, 12 * nb, 0;
        split("0 4 6 2 1 3 7 5 0 1 5 4 2 6 7 3 0 2 3 1 4 5 7 6", q, " ");
        for (i = 0; i < nb; i++) { o = (i - (nb - 1) / 2) * 0.07;
            for (k = 0; k < 8; k++) { a = k % 2 ? 0.3 : -0.3; b = int(k / 2) % 2 ? 0.02 : -0.02;
                e = k >= 4 ? 0.2 : -0.2;
                printf "%.9f %.9f %.9f\n", 0.5 + a * r - (o + b) * r, 0.5 + a * r + (o + b) * r, 0.5 + e } }
        for (i = 0; i < nb; i++) for (f = 0; f < 6; f++) { c = 8 * i;
            print 3, c + q[4 * f + 1], c + q[4 * f + 2], c + q[4 * f + 3];
            print 3, c + q[4 * f + 1], c + q[4 * f + 3], c + q[4 * f + 4] } }' >"$T/bars.off"
    expect_rc 0 "$P" "$T/bars.off" $GUAR -o "$T/bars.oitp" --grid 1 --stats "$T/bars.json"
    slabs=$(json_num slabs <"$T/bars.json")
    parts=$(json_num parts <"$T/bars.json")
    echo "$nb diagonal bars: $(json_num triangles_in <"$T/bars.json") -> $(json_num triangles_out <"$T/bars.json")" \
        "triangles, $parts parts, $slabs slabs"
    [ "$slabs" -ge 1 ] && [ "$(json_num split_added <"$T/bars.json")" -eq 0 ] &&
        [ "$parts" -eq $((nb / 4)) ] ||
        fail "$nb bars: $slabs slabs, $parts parts, $(json_num split_added <"$T/bars.json") triangles added; want a slab, $((nb / 4)) parts, no clip"
    verify_clean "$nb bars" "$T/bars.oitp"
    grep -q "slabs: $slabs, 0 vertices" "$T/out.txt" || fail "$nb bars: verify: $(cat "$T/out.txt")"
    for view in "--azimuth 45 --elevation 10" "--azimuth 135 --elevation 30" \
        "--azimuth 300 --elevation -20" "--view 0.5,0.5,0.5,1.5,1.5,0.5,0,0,1,60"; do
        # shellcheck disable=SC2086
        stream_vs_dfb "$nb bars $view" "$T/bars.oitp" "" --size 96x96 $view
    done
done

fi

if want p100k; then
# (i) the counted capture splits a batch for depth only when long lists hold
# much of it (capture_counted.h): a 100K plant seen whole has a few pixels
# past 32 layers among thousands of shallow ones, so its pack is one batch
# (a split would draw it again, then its halves), and still equals DFB.
"$G" plant --triangles 100000 -o "$T/p100k.ply" >/dev/null || fail "oitgen plant 100K"
expect_rc 0 "$P" "$T/p100k.ply" $GUAR -o "$T/p100k.oitp"
stream_vs_dfb "plant 100K" "$T/p100k.oitp" "" --size 128x128 --azimuth 30 --elevation 10
ml=$(json_num max_layers <"$T/vs.json")
pb=$(json_num batches <"$T/vs.json")
pp=$(json_num packs <"$T/vs.json")
echo "plant 100K: $ml layers at most, $pp packs, $pb batches"
[ "$ml" -gt 32 ] && [ "$pb" -eq "$pp" ] ||
    fail "plant 100K: $ml layers, $pb batches for $pp packs; want > 32 layers and no split"

fi

finish "oitprep ($PART)"
