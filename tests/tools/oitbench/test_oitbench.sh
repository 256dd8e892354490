#!/bin/sh
# oitbench end to end on a quad stack, the comparison a user makes: the
# in-core methods on the mesh against the stream on its part file.
#  - MESH: every method and view has a row; the in-core rows drew the mesh's
#    triangles (geometry source_mesh), the stream row has real figures from
#    a part file converted on the fly (geometry part_file, as many triangles
#    as oitprep makes), within the DESIGN tolerance of the reference
#    (<= 0.5% of pixels off by > 1/255) like dfb and pll, while wboit and
#    unsorted show a larger rmse; the temporary file is gone and nothing was
#    written beside the input.
#  - MESH --parts FILE: no conversion, the stream draws FILE; a FILE of
#    another model (other count, other box, same count and box but another
#    surface) is refused with exit 3 and names both files.
#  - FILE.oitp with its source beside it, without it, and with --mesh.
#  - beside pct_over_1_255, pct_over_1_255_outside_ambiguity (the reference's
#    ambiguity mask left out): ~0 for the exact methods, not for wboit, in
#    results.csv, results.json and report.md with what each means.
#  - MODEL alone: the default methods into ./oitbench-MODEL.
#  - --scheme fast and --save-parts; usage errors exit 2.
# Prints the summary rows.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
B="$OIT_BIN/oitbench"
G="$OIT_BIN/oitgen"
P="$OIT_BIN/oitprep"
scratch oitbench
mkdir -p "$T/tmp" "$T/alone"
SMALL="--orbit 2 --size 64x64 --frames 2 --warmup 1"

"$G" quads --count 12 --coverage 0.6 -o "$T/Q.ply" >/dev/null || die "oitgen quads"
"$G" quads --count 12 --coverage 0.6 --seed 2 -o "$T/Q2.ply" >/dev/null &&
    "$G" quads --count 9 --coverage 0.6 -o "$T/Q9.ply" >/dev/null || die "oitgen quads"
for q in Q Q2 Q9; do
    prep_or_die "$T/$q.ply" "$T/$q.oitp" --threads 1
done
SRC_TRIS=24                       # 12 quads
PART_TRIS=$("$P" info "$T/Q.oitp" --json | sed -n 's/.*"triangles": \([0-9]*\),.*/\1/p')
echo "Q.ply: $SRC_TRIS triangles; Q.oitp: $PART_TRIS"
[ -n "$PART_TRIS" ] || die "no triangle count from oitprep info"
# The default (fast) scheme keeps 12 quads in one part, nothing clipped:
# the reports say "part file", and "(clipped)" only where planes cut.
[ "$PART_TRIS" = "$SRC_TRIS" ] || die "Q.oitp: $PART_TRIS triangles, want $SRC_TRIS (one part, unclipped)"

# field CSV ROW METHOD VIEW COLUMN: one cell of a results.csv, by header name.
field() {
    awk -F, -v row="$2" -v m="$3" -v v="$4" -v col="$5" '
        NR == 1 { for (i = 1; i <= NF; i++) if ($i == col) c = i; next }
        $1 == row && $2 == m && $3 == v { print $c; exit }' "$1"
}
# is CSV METHOD GEOMETRY TRIANGLES: every row of METHOD drew that.
is() {
    g=$(field "$1" summary "$2" '' geometry) n=$(field "$1" summary "$2" '' drawn_triangles)
    [ "$g" = "$3" ] && [ "$n" = "$4" ] || fail "$1: $2 drew $g $n, expected $3 $4"
    bad=$(awk -F, -v m="$2" -v g="$3" -v n="$4" '$2 == m && ($16 != g || $17 != n)' "$1" | wc -l)
    [ "$bad" -eq 0 ] || fail "$1: $bad rows of $2 not $3 $4"
}
# exact CSV METHOD: it ran, with real figures, within the DESIGN tolerance.
exact() {
    [ "$(field "$1" summary "$2" '' status)" = ok ] || fail "$1: $2 did not run"
    ms=$(field "$1" summary "$2" '' ms_median)
    awk -v x="$ms" 'BEGIN { exit !(x != "" && x + 0 > 0) }' || fail "$1: $2 median ms '$ms'"
    for v in 0 1; do
        pct=$(field "$1" view "$2" $v pct_over_1_255)
        awk -v p="$pct" 'BEGIN { exit !(p != "" && p + 0 <= 0.5) }' ||
            fail "$1: $2 view $v: '$pct'% of pixels off by > 1/255 (allowed 0.5%)"
    done
}

# ---- a mesh: in-core methods on it, the stream on a conversion made now ----
TMPDIR="$T/tmp" "$B" "$T/Q.ply" --methods dfb,pll,wboit,unsorted,stream $SMALL \
    --out "$T/D" >"$T/table.txt" 2>"$T/err.txt"
rc=$?
cat "$T/err.txt" "$T/table.txt"
[ "$rc" -eq 0 ] || fail "oitbench on a mesh exited $rc"
CSV="$T/D/results.csv"
[ -s "$CSV" ] || { fail "no results.csv"; exit 1; }
grep '^summary,' "$CSV"
for m in dfb pll wboit unsorted stream; do
    for v in 0 1; do
        grep -q "^view,$m,$v," "$CSV" || fail "no row for $m view $v"
    done
    grep -q "^summary,$m,," "$CSV" || fail "no summary row for $m"
done
rows=$(grep -c '^view,' "$CSV")
[ "$rows" -eq 10 ] || fail "expected 10 view rows (5 methods x 2 views), got $rows"
for m in dfb pll wboit unsorted; do is "$CSV" $m source_mesh $SRC_TRIS; done
is "$CSV" stream part_file "$PART_TRIS"
[ "$(field "$CSV" summary stream '' triangles)" = $SRC_TRIS ] || fail "triangles column is not the source's $SRC_TRIS"
for m in dfb pll stream; do exact "$CSV" $m; done
dfb_rmse=$(field "$CSV" summary dfb '' rmse)
for m in wboit unsorted; do
    r=$(field "$CSV" summary $m '' rmse)
    echo "rmse $m $r vs dfb $dfb_rmse"
    awk -v r="$r" -v d="$dfb_rmse" 'BEGIN { exit !(r != "" && d != "" && r + 0 > d + 0) }' ||
        fail "$m rmse $r not larger than dfb's $dfb_rmse"
done
grep -q "converted .*Q.ply: $SRC_TRIS triangles in, $PART_TRIS out" "$T/err.txt" ||
    fail "stderr does not report the conversion's triangles in and out"
grep -q "^stream  *part file  *$PART_TRIS " "$T/table.txt" || fail "stdout table lacks the stream's row"
grep -q "clipped" "$T/table.txt" "$T/D/report.md" && fail "nothing was clipped, yet the reports say clipped"
grep -q "^dfb  *source mesh  *$SRC_TRIS " "$T/table.txt" || fail "stdout table lacks dfb's row"
grep -q '"conversion": {"scheme": "[a-z]*", .*"triangles_in": '$SRC_TRIS', "triangles_out": '$PART_TRIS',' \
    "$T/D/results.json" || fail "results.json lacks the conversion"
grep -q '"name": "stream", "method": "stream", "epsilon": null, "geometry": "part_file", "triangles": '$PART_TRIS \
    "$T/D/results.json" || fail "results.json lacks the stream's geometry"
grep -q 'converted in this run (temporary, removed)' "$T/D/report.md" || fail "report.md does not say the part file was temporary"
grep -q '| stream | part file | '$PART_TRIS' |' "$T/D/report.md" || fail "report.md's summary lacks the stream's geometry"
[ -z "$(ls -A "$T/tmp")" ] || fail "temporary files left in TMPDIR: $(ls "$T/tmp")"
ls "$T" | grep -v '^\(Q\|Q2\|Q9\)\.\(ply\|oitp\)$' | grep -q '\.oitp' && fail "a part file was written beside the input"
grep -q '"timed_frames": 4' "$T/D/results.json" || fail "results.json lacks 4 timed frames (2 views x 2)"
grep -q 'GL renderer: ..*' "$T/D/report.md" || fail "report.md does not name the GL renderer"
grep -q 'side by side' "$T/D/report.md" || fail "report.md lacks the note on timings"
# Beside the raw "% of pixels off", the same outside the reference's
# ambiguity mask (pixels whose centre lies within the ambiguity radius of an
# edge, where raster and ray may disagree): ~0 for the exact methods, not
# for wboit, explained in report.md and named in the CSV's header.
head -n 1 "$CSV" | grep -q ',pct_over_1_255,.*,pct_over_1_255_outside_ambiguity$' ||
    fail "results.csv's header lacks pct_over_1_255_outside_ambiguity: $(head -n 1 "$CSV")"
for m in dfb pll stream; do
    for v in 0 1; do
        p=$(field "$CSV" view $m $v pct_over_1_255_outside_ambiguity)
        awk -v p="$p" 'BEGIN { exit !(p != "" && p + 0 <= 0.001) }' ||
            fail "$m view $v: '$p'% of the unambiguous pixels off by > 1/255 (an exact method: ~0)"
    done
done
p=$(field "$CSV" summary wboit '' pct_over_1_255_outside_ambiguity)
awk -v p="$p" 'BEGIN { exit !(p != "" && p + 0 > 1) }' ||
    fail "wboit: '$p'% off outside the ambiguity mask (approximate: expected > 1)"
grep -q "outside the reference's ambiguity mask" "$T/D/report.md" &&
    grep -q 'pct_over_1_255_outside_ambiguity' "$T/D/report.md" ||
    fail "report.md does not explain the figure outside the ambiguity mask"
grep -q '"pct_over_1_255_outside_ambiguity": ' "$T/D/results.json" ||
    fail "results.json lacks pct_over_1_255_outside_ambiguity"

# ---- MODEL alone: the default methods, into the default folder ----
# (no --methods, no --out: --help names both; a method this driver cannot
# run would be a not_runnable row with its reason, the run still exit 0)
DEFAULT_METHODS="dfb stream compute pll wboit unsorted"
mkdir -p "$T/cwd"
(cd "$T/cwd" && TMPDIR="$T/tmp" "$B" "$T/Q.ply" $SMALL >"$T/tabled.txt" 2>"$T/errd.txt")
rc=$?
cat "$T/errd.txt" "$T/tabled.txt"
[ "$rc" -eq 0 ] || fail "oitbench MODEL alone exited $rc"
CSVD="$T/cwd/oitbench-Q/results.csv"
[ -s "$CSVD" ] || fail "oitbench MODEL alone wrote no $CSVD"
for m in $DEFAULT_METHODS; do
    grep -q "^summary,$m,,\(ok\|not_runnable\)," "$CSVD" || fail "default set: no summary row for $m"
    grep -q "^$m  " "$T/tabled.txt" || fail "default set: no stdout row for $m"
done
[ "$(grep -c '^summary,' "$CSVD")" -eq 6 ] || fail "default set: expected 6 entries: $(grep '^summary,' "$CSVD")"
for m in dfb stream wboit; do
    grep -q "^summary,$m,,ok," "$CSVD" || fail "default set: $m did not run"
done
grep -q 'default set' "$T/errd.txt" || fail "stderr does not say the default set ran"
"$B" --help | grep -q 'default: dfb,stream,compute,pll,wboit,unsorted' ||
    fail "--help does not name the default methods"
"$B" --help | grep -q 'default: ./oitbench-MODEL' || fail "--help does not name the default --out"

# ---- a mesh with --parts: the given file, no conversion ----
"$B" "$T/Q.ply" --parts "$T/Q.oitp" --methods dfb,stream $SMALL --out "$T/P" >/dev/null 2>"$T/errp.txt"
rc=$?
[ "$rc" -eq 0 ] || fail "--parts exited $rc: $(cat "$T/errp.txt")"
grep -q converted "$T/errp.txt" && fail "--parts still converted"
is "$T/P/results.csv" dfb source_mesh $SRC_TRIS
is "$T/P/results.csv" stream part_file "$PART_TRIS"
exact "$T/P/results.csv" stream
# another model: refused, naming both files, nothing written
for other in Q9 Q2; do
    "$B" "$T/Q.ply" --parts "$T/$other.oitp" --methods dfb,stream $SMALL --out "$T/M$other" \
        >/dev/null 2>"$T/errm.txt"
    rc=$?
    cat "$T/errm.txt"
    [ "$rc" -eq 3 ] || fail "--parts $other.oitp (another model) exited $rc, expected 3"
    grep -q "$other.oitp was not made from .*Q.ply" "$T/errm.txt" || fail "--parts $other.oitp: message does not name both files"
    [ ! -e "$T/M$other" ] || fail "--parts $other.oitp still wrote its folder"
done
# as many triangles in the same box, another surface: refused on the area
printf 'OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n1 0 1\n3 0 1 2\n3 3 4 5\n' >"$T/a.off"
printf 'OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n1 0.5 1\n3 0 1 2\n3 3 4 5\n' >"$T/b.off"
"$P" "$T/b.off" -o "$T/b.oitp" --threads 1 >/dev/null 2>&1 || fail "oitprep b.off failed"
"$B" "$T/a.off" --parts "$T/b.oitp" --methods dfb,stream --orbit 1 --size 16x16 --frames 1 \
    --out "$T/Mab" >/dev/null 2>"$T/errm.txt"
rc=$?
cat "$T/errm.txt"
[ "$rc" -eq 3 ] && grep -q 'surface area' "$T/errm.txt" || fail "same count and box, other surface: exit $rc, expected 3 on the area"

# ---- a part file: its source beside it, then alone, then with --mesh ----
"$B" "$T/Q.oitp" --methods dfb,stream $SMALL --out "$T/F" >/dev/null 2>"$T/errf.txt" ||
    fail "part file with its source beside exited $?: $(cat "$T/errf.txt")"
is "$T/F/results.csv" dfb source_mesh $SRC_TRIS
is "$T/F/results.csv" stream part_file "$PART_TRIS"
exact "$T/F/results.csv" dfb
cp "$T/Q.oitp" "$T/alone/Q.oitp"
"$B" "$T/alone/Q.oitp" --methods dfb,stream $SMALL --out "$T/A" >/dev/null 2>"$T/erra.txt" ||
    fail "part file alone exited $?: $(cat "$T/erra.txt")"
cat "$T/erra.txt"
is "$T/A/results.csv" dfb part_file "$PART_TRIS"
is "$T/A/results.csv" stream part_file "$PART_TRIS"
[ "$(field "$T/A/results.csv" summary dfb '' triangles)" = $SRC_TRIS ] || fail "alone: triangles column is not the META's $SRC_TRIS"
grep -q "source mesh 'Q.ply' recorded in .*alone/Q.oitp is not beside it" "$T/erra.txt" || fail "alone: stderr does not say the source is missing"
grep -q 'source mesh: not at hand' "$T/A/report.md" || fail "alone: report.md does not say the source is missing"
grep -q '| dfb | part file | '$PART_TRIS' |' "$T/A/report.md" || fail "alone: report.md does not say dfb drew the part file"
grep -q '"reference_geometry": "part_file"' "$T/A/results.json" || fail "alone: results.json does not say what the reference drew"
"$B" "$T/alone/Q.oitp" --mesh "$T/Q.ply" --methods dfb,stream $SMALL --out "$T/AM" >/dev/null 2>&1 ||
    fail "--mesh exited $?"
is "$T/AM/results.csv" dfb source_mesh $SRC_TRIS
"$B" "$T/alone/Q.oitp" --mesh "$T/Q9.ply" --methods dfb,stream $SMALL --out "$T/AM9" >/dev/null 2>"$T/errm.txt"
rc=$?
[ "$rc" -eq 3 ] || fail "--mesh of another model exited $rc, expected 3: $(cat "$T/errm.txt")"
# a mismatched mesh beside the file is not used, and said so
cp "$T/Q9.ply" "$T/alone/Q.ply"
"$B" "$T/alone/Q.oitp" --methods dfb --orbit 1 --size 16x16 --frames 1 --out "$T/AW" >/dev/null 2>"$T/errw.txt" ||
    fail "a wrong mesh beside the file exited $?"
is "$T/AW/results.csv" dfb part_file "$PART_TRIS"
grep -q 'is not its source' "$T/errw.txt" || fail "a wrong mesh beside the file: not said"
echo 'ply garbage' >"$T/alone/Q.ply"
"$B" "$T/alone/Q.oitp" --methods dfb --orbit 1 --size 16x16 --frames 1 --out "$T/AG" >/dev/null 2>"$T/errg.txt" ||
    fail "an unreadable mesh beside the file exited $?"
is "$T/AG/results.csv" dfb part_file "$PART_TRIS"
grep -q 'source beside .*cannot be read' "$T/errg.txt" || fail "an unreadable mesh beside the file: not said"

# ---- the conversion's options ----
"$B" "$T/Q.ply" --methods stream --scheme fast --part-triangles 8 --save-parts "$T/kept.oitp" \
    --orbit 1 --size 16x16 --frames 1 --out "$T/S" >/dev/null 2>"$T/errs.txt" || fail "--scheme fast --save-parts exited $?"
# A tilted triangle spanning the box with four small ones around it, in
# parts of at most 2 triangles: every split plane cuts the big one, and the
# reports say clipped (only) then. (Crossing triangles would not do: the
# fast scheme splits around their crossing line to its full depth.)
printf 'OFF\n15 5 0\n0 0 0\n10 5 0\n0 10 10\n1 9 1\n1.5 9 1\n1 9.5 1\n9 9 9\n9.5 9 9\n9 9.5 9\n9 1 1\n9.5 1 1\n9 1.5 1\n5 5 9\n5.5 5 9\n5 5.5 9\n3 0 1 2\n3 3 4 5\n3 6 7 8\n3 9 10 11\n3 12 13 14\n' >"$T/x.off"
"$B" "$T/x.off" --methods dfb,stream --scheme fast --part-triangles 2 --save-parts "$T/x.oitp" \
    --orbit 1 --size 16x16 --frames 1 --out "$T/X" >"$T/tablex.txt" 2>"$T/errx.txt" ||
    fail "the crossing squares exited $?: $(cat "$T/errx.txt")"
X_TRIS=$("$P" info "$T/x.oitp" --json | sed -n 's/.*"triangles": \([0-9]*\),.*/\1/p')
[ "${X_TRIS:-0}" -gt 5 ] || fail "parts of 2 triangles clipped nothing of the spanning one ($X_TRIS)"
grep -q "^stream  *part file (clipped)  *$X_TRIS " "$T/tablex.txt" &&
    grep -q '| stream | part file (clipped) | '"$X_TRIS"' |' "$T/X/report.md" ||
    fail "a clipped part file is not called clipped: $(cat "$T/tablex.txt")"
grep -q '"scheme": "fast", "part_triangles": 8,' "$T/S/results.json" || fail "results.json lacks scheme fast, part_triangles 8"
"$P" info "$T/kept.oitp" >/dev/null 2>&1 || fail "--save-parts did not keep a valid part file"
KEPT_PARTS=$("$P" info "$T/kept.oitp" --json | sed -n 's/.*"parts": \([0-9]*\),.*/\1/p')
[ "${KEPT_PARTS:-0}" -ge 2 ] || fail "--part-triangles 8 made '$KEPT_PARTS' parts of 24 triangles"

# ---- usage errors (exit 2, nothing written) ----
usage() {
    "$B" "$@" --orbit 1 --out "$T/E" 2>"$T/erru.txt"
    rc=$?
    [ "$rc" -eq 2 ] || fail "oitbench $* exited $rc, expected 2"
    [ ! -e "$T/E" ] || fail "oitbench $* still wrote $T/E"
}
usage "$T/Q.ply" --methods dfb,bogus
usage "$T/Q.ply" --methods dfb,stream --mesh "$T/Q.ply"
usage "$T/Q.oitp" --methods dfb,stream --parts "$T/Q.oitp"
usage "$T/Q.oitp" --methods stream --scheme fast
usage "$T/Q.ply" --methods dfb --parts "$T/Q.oitp"
usage "$T/Q.ply" --methods stream --parts "$T/Q.oitp" --scheme fast
usage "$T/Q.ply" --methods stream --scheme guaranteed --part-triangles 100
grep -q 'part-triangles 100 applies to the fast scheme' "$T/erru.txt" || fail "--part-triangles message: $(cat "$T/erru.txt")"
usage "$T/Q.ply" --methods stream --scheme slow
"$B" --help | grep -q -- '--warmup' || fail "--help does not document --warmup"
"$B" --help | grep -q -- '--parts FILE' || fail "--help does not document --parts"

# A STEP file's views turn about z, as oitstream's default views do, and
# oitbench says so.
STEP="$(cd "$(dirname "$0")/../../corpus/step" && pwd)/parts.step"
"$B" "$STEP" --methods dfb --orbit 1 --size 32x24 --frames 1 --warmup 0 --out "$T/S" \
    >/dev/null 2>"$T/errs.txt" || fail "oitbench on a STEP file: $(cat "$T/errs.txt")"
grep -q "the views turn about z (STEP and IGES are Z-up)" "$T/errs.txt" ||
    fail "oitbench does not say the STEP file's views turn about z: $(cat "$T/errs.txt")"

finish test_oitbench
