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
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
P="$OIT_BIN/oitprep"
C=${1:?usage: test_source_prims.sh TEST_SOURCES}
need_tools "$S" "$P" "$C"
scratch source_prims
SIZE=${OIT_SOURCE_PRIMS_SIZE:-128x128}
INDENT="    "

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

# views NAME FILE AZIMUTH: the stream of FILE from AZIMUTH (elevation 35)
# into $v-stream.pfm, v being $T/NAME-AZIMUTH, and its camera in cam; then
# DFB of FILE from that camera into $v-dfb.pfm. Fails (1) without a stream.
views() {
    v="$T/$1-$3"
    "$S" "$2" --method stream --size "$SIZE" --azimuth "$3" --elevation 35 \
        --out "$v-stream.pfm" --stats "$v.json" --quiet || { fail "$1 $3: stream"; return 1; }
    cam=$(json_str view "$v.json")
    dfb_at "$1 $3" "$2" "$v-dfb.pfm"
}
# dfb_at NAME SOURCE OUT: DFB of SOURCE from cam into OUT.
dfb_at() {
    "$S" "$2" --method dfb --size "$SIZE" --view "$cam" --out "$3" --quiet ||
        fail "$1: dfb on $(basename "$2")"
}

# (a) the hand-written file
"$C" --write-tie "$T/tie.oitp" || die "test_sources --write-tie"
"$C" --write-tie "$T/tie1m.oitp" 1000000 || die "test_sources --write-tie 1M"
for az in 30 210; do
    views tie "$T/tie.oitp" $az || continue
    # the same file claiming 1M source triangles
    dfb_at "tie $az" "$T/tie1m.oitp" "$v-dfb1m.pfm"
    for src in tie b_first; do
        dfb_at "tie $az" "$T/$src.ply" "$v-$src.pfm"
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
        views $scheme "$T/$scheme.oitp" $az || continue
        dfb_at "$scheme $az" "$T/interleaved.ply" "$v-mesh.pfm"
        echo "  interleaved source through oitprep --scheme $scheme, azimuth $az:"
        compare "stream vs dfb (source mesh), no mask" "$v-stream.pfm" "$v-mesh.pfm" 0.01
        compare "dfb (part file) vs dfb (source mesh), no mask" "$v-dfb.pfm" "$v-mesh.pfm" 0.01
    done
done
finish --clean "source prims"
