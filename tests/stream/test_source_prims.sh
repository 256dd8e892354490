#!/bin/sh
# The stream's prim (the tie-break key of fragments at equal depth) is the
# source triangle index (docs/part-file.md, PART_DATA). Two unit boxes
# duplicated exactly, of two colours, so that every fragment of one ties in
# depth with one of the other and the source order decides which is in
# front:
#   (a) a hand-written part file (test_sources --write-tie) whose one part
#       stores box B's triangles before box A's, with their source indices
#       (A first in the source, tie.ply): streamed, and rendered by DFB on
#       the file (its in-core mesh sorted by source index), it equals DFB
#       on tie.ply on every pixel of two views, no ambiguity mask. Drawn by
#       position it would equal the B-first source instead, which differs
#       (checked: the views hold ties that decide colours). The same file
#       claiming 1M source triangles read (DFB's in-core mesh then sorted by
#       keys, not by counting) renders alike;
#   (b) the boxes with their triangles interleaved in the source (B's first,
#       all of A's, the rest of B's) through oitprep, both schemes: stream
#       and DFB on the file equal DFB on the source on every pixel but a
#       clipped edge's (0.01%).
# usage: test_source_prims.sh TEST_SOURCES
set -u
: "${OIT_BIN:?OIT_BIN must name the tools folder}"
: "${OIT_TEST_TMP:?OIT_TEST_TMP must name a scratch folder}"
S="$OIT_BIN/oitstream"
P="$OIT_BIN/oitprep"
C=${1:?usage: test_source_prims.sh TEST_SOURCES}
for tool in "$S" "$P" "$C"; do
    [ -x "$tool" ] || { echo "skip: $tool not built"; exit 77; }
done
T="$OIT_TEST_TMP/source_prims"
SIZE=${OIT_SOURCE_PRIMS_SIZE:-128x128}
rm -rf "$T" && mkdir -p "$T" || exit 1
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
FAILS=0
fail() { echo "FAIL: $*" >&2; FAILS=$((FAILS + 1)); }
json_num() { sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" "$2" | head -n 1; }
json_str() { sed -n "s/.*\"$1\": *\"\([^\"]*\)\".*/\1/p" "$2" | head -n 1; }
at_most() { awk "BEGIN{exit !($1 <= $2)}"; }

# boxes ORDER OUT: the two boxes as ASCII PLY; ORDER "interleaved" (B0, A0..11,
# B1..11), "a_first" (A0..11, B0..11) or "b_first" (B0..11, A0..11). Box A
# is red, B blue, alpha 100 (test_sources --write-tie writes the same).
boxes() {
    awk -v order="$1" 'BEGIN {
        nv = 16; nf = 24
        print "ply"; print "format ascii 1.0"
        print "element vertex " nv
        print "property float x"; print "property float y"; print "property float z"
        print "property uchar red"; print "property uchar green"; print "property uchar blue"
        print "property uchar alpha"
        print "element face " nf; print "property list uchar int vertex_indices"
        print "end_header"
        for (b = 0; b < 2; b++)
            for (i = 0; i < 8; i++)
                printf "%g %g %g %s\n", (i % 2) - 0.5, (int(i / 2) % 2) - 0.5,
                       int(i / 4) - 0.5, b ? "40 60 230 100" : "230 40 40 100"
        split("0 2 3 0 3 1 4 5 7 4 7 6 0 1 5 0 5 4 2 6 7 2 7 3 0 4 6 0 6 2 1 3 7 1 7 5", f, " ")
        for (t = 0; t < 12; t++) { A[t] = f[3*t+1] " " f[3*t+2] " " f[3*t+3] }
        for (t = 0; t < 12; t++) {
            split(A[t], q, " "); B[t] = (q[1] + 8) " " (q[2] + 8) " " (q[3] + 8)
        }
        if (order == "interleaved") {
            print "3 " B[0]
            for (t = 0; t < 12; t++) print "3 " A[t]
            for (t = 1; t < 12; t++) print "3 " B[t]
        } else if (order == "a_first") {
            for (t = 0; t < 12; t++) print "3 " A[t]
            for (t = 0; t < 12; t++) print "3 " B[t]
        } else {
            for (t = 0; t < 12; t++) print "3 " B[t]
            for (t = 0; t < 12; t++) print "3 " A[t]
        }
    }' > "$2"
}
boxes interleaved "$T/interleaved.ply"
boxes a_first "$T/tie.ply"
boxes b_first "$T/b_first.ply"

# compare NAME A B LIMIT%: the share of pixels off by > 1/255, printed and checked.
compare() {
    "$S" --compare "$2" "$3" --json >"$T/cmp.json" || { fail "$1: compare"; return; }
    p=$(json_num pct_over_1_255 "$T/cmp.json")
    echo "    $1: over 1/255 $p% (limit $4%)"
    at_most "$p" "$4" || fail "$1: $p% of pixels off by more than 1/255"
}

# (a) the hand-written file
"$C" --write-tie "$T/tie.oitp" || { echo "FAIL: test_sources --write-tie"; exit 1; }
"$C" --write-tie "$T/tie1m.oitp" 1000000 || { echo "FAIL: test_sources --write-tie 1M"; exit 1; }
for az in 30 210; do
    v="$T/tie-$az"
    "$S" "$T/tie.oitp" --method stream --size "$SIZE" --azimuth $az --elevation 35 \
        --out "$v-stream.pfm" --stats "$v.json" --quiet || { fail "tie $az: stream"; continue; }
    cam=$(json_str view "$v.json")
    "$S" "$T/tie.oitp" --method dfb --size "$SIZE" --view "$cam" --out "$v-dfb.pfm" \
        --quiet || fail "tie $az: dfb on the part file"
    "$S" "$T/tie1m.oitp" --method dfb --size "$SIZE" --view "$cam" --out "$v-dfb1m.pfm" \
        --quiet || fail "tie $az: dfb on the part file claiming 1M source triangles"
    for src in tie b_first; do
        "$S" "$T/$src.ply" --method dfb --size "$SIZE" --view "$cam" --out "$v-$src.pfm" \
            --quiet || fail "tie $az: dfb on $src.ply"
    done
    echo "  hand-written file (B stored first, A first in the source), azimuth $az:"
    compare "stream vs dfb (source mesh), no mask" "$v-stream.pfm" "$v-tie.pfm" 0
    compare "dfb (part file) vs dfb (source mesh), no mask" "$v-dfb.pfm" "$v-tie.pfm" 0
    compare "dfb (part file, 1M source triangles) vs dfb (source mesh)" "$v-dfb1m.pfm" \
        "$v-tie.pfm" 0
    "$S" --compare "$v-stream.pfm" "$v-b_first.pfm" --json >"$T/cmp.json"
    p=$(json_num pct_over_1_255 "$T/cmp.json")
    echo "    stream vs dfb (B-first source, what position prims give): over 1/255 $p% (must be > 1%)"
    at_most 1 "$p" || fail "tie $az: the stream equals the B-first order: no ties decided"
done

# (b) through the converter
for scheme in guaranteed fast; do
    "$P" "$T/interleaved.ply" -o "$T/$scheme.oitp" --scheme $scheme >"$T/prep.txt" 2>&1 ||
        { fail "$scheme: oitprep: $(tail -n 1 "$T/prep.txt")"; continue; }
    for az in 30 210; do
        v="$T/$scheme-$az"
        "$S" "$T/$scheme.oitp" --method stream --size "$SIZE" --azimuth $az --elevation 35 \
            --out "$v-stream.pfm" --stats "$v.json" --quiet || { fail "$scheme $az: stream"; continue; }
        cam=$(json_str view "$v.json")
        "$S" "$T/$scheme.oitp" --method dfb --size "$SIZE" --view "$cam" --out "$v-dfb.pfm" \
            --quiet || fail "$scheme $az: dfb on the part file"
        "$S" "$T/interleaved.ply" --method dfb --size "$SIZE" --view "$cam" \
            --out "$v-mesh.pfm" --quiet || fail "$scheme $az: dfb on the source"
        echo "  interleaved source through oitprep --scheme $scheme, azimuth $az:"
        compare "stream vs dfb (source mesh), no mask" "$v-stream.pfm" "$v-mesh.pfm" 0.01
        compare "dfb (part file) vs dfb (source mesh), no mask" "$v-dfb.pfm" "$v-mesh.pfm" 0.01
    done
done
[ "$FAILS" -eq 0 ] || { echo "$FAILS failure(s)"; exit 1; }
rm -rf "$T"
echo PASS
