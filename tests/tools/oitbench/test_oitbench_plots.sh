#!/bin/sh
# oitbench's charts and threshold sweep end to end, on converted quad stacks
# at 64x64: --epsilon 0,0.1 runs stream once per value (stream@0,
# stream@0.1 rows; more error at 0.1), results.csv carries the triangle
# count and each view's depth, the run writes speed_vs_error.png and
# memory_vs_depth.png (valid PNGs of the chart size with drawn content) and
# report.md shows them; `oitbench plot` over two runs writes
# time_vs_triangles.png and memory_vs_depth.png; a malformed results.csv
# fails with exit 3 naming the file and line and writes nothing; bad
# --epsilon values and plot without runs are usage errors (exit 2).
# Usage: test_oitbench_plots.sh PNG_FIGURES   (tests/lib/png_figures.c)
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
FIG="$1"
B="$OIT_BIN/oitbench"
scratch oitbench_plots

# part file of N quads beside its mesh: stream runs on the file, the other
# methods on the mesh (found through the file's META). Wang & Xie's scheme:
# its many small parts let early termination drop whole parts between
# packs, where the fast scheme makes one part of the quads. 24 quads: the
# first front-first pack (view/stream/pack.h) takes up to K = 8 layers a tile
# exactly, so fewer would give E = 0.1 nothing behind a saturated pixel.
prep() {
    "$OIT_BIN/oitgen" quads --count "$1" -o "$T/q$1.ply" >/dev/null || die "oitgen quads --count $1"
    prep_or_die "$T/q$1.ply" "$T/q$1.oitp" --scheme guaranteed --threads 1
}
prep 24
prep 3

# check_png FILE: a PNG 1100 wide, at least 720 high, with drawn content
check_png() {
    [ -s "$1" ] || { fail "$1 missing"; return; }
    [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '211PNG' ] || { fail "$1: not a PNG"; return; }
    f=$("$FIG" "$1") || { fail "$1 does not read as an image"; return; }
    echo "$(basename "$1"): $f (width height non-white colours)"
    set -- "$1" $f
    [ "$2" -eq 1100 ] && [ "$3" -ge 720 ] || fail "$1: size $2x$3, expected 1100 x >= 720"
    [ "$4" -ge 3000 ] && [ "$5" -ge 5 ] || fail "$1: blank ($4 non-white pixels, $5 colours)"
}

"$B" "$T/q24.oitp" --methods stream,dfb --epsilon 0,0.1 --orbit 2 --size 64x64 --frames 1 \
    --warmup 0 --out "$T/R1" 2>"$T/err1.txt"
rc=$?
cat "$T/err1.txt"
[ "$rc" -eq 0 ] || fail "oitbench --epsilon 0,0.1 exited $rc"
CSV="$T/R1/results.csv"
[ -s "$CSV" ] || { fail "no results.csv"; exit 1; }
cat "$CSV"
head -n 1 "$CSV" | grep -q ',reason,triangles,view_max_layers,geometry,drawn_triangles,gpu_ms_median,gpu_mesh_bytes,pct_over_1_255_outside_ambiguity$' ||
    fail "header lacks triangles, view_max_layers, geometry, drawn_triangles, gpu_ms_median, gpu_mesh_bytes, pct_over_1_255_outside_ambiguity"
for m in stream@0 stream@0.1 dfb; do
    [ "$(grep -c "^view,$m,[01],ok," "$CSV")" -eq 2 ] || fail "expected 2 ok view rows of $m"
    grep -q "^summary,$m,,ok," "$CSV" || fail "no ok summary row of $m"
done
grep -q '^[a-z]*,stream,' "$CSV" && fail "plain 'stream' rows beside the swept ones"

# column NAME of the summary row of METHOD
col() {
    awk -F, -v m="$1" -v name="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) c = i; next }
        $1 == "summary" && $2 == m { print $c; exit }' "$CSV"
}
tri=$(sed -n 's/.*: \([0-9]*\) triangles, .*/\1/p' "$T/err1.txt")
[ -n "$tri" ] && [ "$(col dfb triangles)" = "$tri" ] || fail "triangles column '$(col dfb triangles)', oitbench said '$tri'"
[ "$(col dfb view_max_layers)" -ge 24 ] 2>/dev/null || fail "view_max_layers '$(col dfb view_max_layers)' below the 24 quads"
# GPU bytes count the mesh DFB holds (3 vertices of 16 bytes a triangle,
# worked out here), within its peak; the stream holds no mesh
dm=$(col dfb gpu_mesh_bytes) dp=$(col dfb gpu_bytes_peak) dt=$(col dfb drawn_triangles)
echo "dfb: gpu_bytes_peak $dp, gpu_mesh_bytes $dm, $dt triangles"
awk -v m="$dm" -v p="$dp" -v t="$dt" 'BEGIN { exit !(m != "" && t != "" && m + 0 >= t * 48 && p + 0 >= m + 0) }' ||
    fail "dfb: gpu_mesh_bytes '$dm' for $dt triangles, gpu_bytes_peak '$dp'"
[ "$(col stream@0 gpu_mesh_bytes)" = 0 ] || fail "stream@0: gpu_mesh_bytes '$(col stream@0 gpu_mesh_bytes)'"
grep -q '"gpu_mesh_bytes": '"$dm"',' "$T/R1/results.json" || fail "results.json lacks dfb's gpu_mesh_bytes $dm"
e0=$(col stream@0 rmse) e1=$(col stream@0.1 rmse)
echo "rmse: stream@0 $e0, stream@0.1 $e1"
awk -v a="$e0" -v b="$e1" 'BEGIN { exit !(a != "" && b != "" && b + 0 > a + 0) }' ||
    fail "stream@0.1 rmse $e1 not above stream@0's $e0"
grep -q '"name": "stream@0.1", "method": "stream", "epsilon": 0.1,' "$T/R1/results.json" ||
    fail "results.json lacks stream@0.1's method and epsilon"
grep -q "\"triangles\": $tri," "$T/R1/results.json" || fail "results.json lacks triangles"
check_png "$T/R1/speed_vs_error.png"
check_png "$T/R1/memory_vs_depth.png"
grep -q '](speed_vs_error.png)' "$T/R1/report.md" && grep -q '](memory_vs_depth.png)' "$T/R1/report.md" ||
    fail "report.md does not show its charts"

# a second run of another size, without a sweep, then the charts across both
"$B" "$T/q3.oitp" --methods stream,dfb --orbit 2 --size 64x64 --frames 1 --warmup 0 \
    --out "$T/R2" 2>/dev/null || fail "second oitbench run exited $?"
"$B" plot "$T/P" "$T/R1" "$T/R2" 2>"$T/errp.txt" || fail "oitbench plot exited $?: $(cat "$T/errp.txt")"
check_png "$T/P/time_vs_triangles.png"
check_png "$T/P/memory_vs_depth.png"

# a malformed results.csv: exit 3, the file and line named, nothing written
mkdir -p "$T/R3" && sed '3s/,ok,/,okay,/' "$CSV" >"$T/R3/results.csv"
"$B" plot "$T/P3" "$T/R1" "$T/R3" 2>"$T/err3.txt"
rc=$?
cat "$T/err3.txt"
[ "$rc" -eq 3 ] || fail "malformed results.csv: exit $rc, expected 3"
grep -q "R3/results.csv: line 3: column status: 'okay'" "$T/err3.txt" || fail "message does not name file, line and field"
[ ! -e "$T/P3/time_vs_triangles.png" ] || fail "a chart was written from a malformed run"
"$B" plot "$T/P4" "$T/R1" "$T/missing" 2>"$T/err4.txt"
rc=$?
[ "$rc" -eq 1 ] && grep -q 'missing/results.csv: cannot open' "$T/err4.txt" ||
    fail "missing run folder: exit $rc, '$(cat "$T/err4.txt")'"

# usage errors
for e in 1 -0.1 0.1,0.1 abc 0.1, ''; do
    "$B" "$T/q24.oitp" --methods stream --epsilon "$e" --out "$T/E" 2>/dev/null
    rc=$?
    [ "$rc" -eq 2 ] || fail "--epsilon '$e' exited $rc, expected 2"
done
"$B" "$T/q24.oitp" --methods dfb,pll --epsilon 0.1 --out "$T/E" 2>"$T/erre.txt"
[ $? -eq 2 ] && grep -q 'stream, guarded and f2b' "$T/erre.txt" || fail "--epsilon without a threshold method accepted"
"$B" plot "$T/P5" 2>/dev/null
[ $? -eq 2 ] || fail "plot without a run folder is not a usage error"
[ ! -e "$T/E" ] || fail "a usage error still wrote $T/E"
"$B" --help | grep -q -- '--epsilon LIST' && "$B" --help | grep -q 'oitbench plot OUT_DIR RUN_DIR' ||
    fail "--help does not document --epsilon and plot"

finish test_oitbench_plots
