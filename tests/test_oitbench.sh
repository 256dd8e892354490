#!/bin/sh
# oitbench end to end on a quad stack: every method and view has a row,
# stream is reported (with its reason) as not runnable on a mesh, the exact
# methods (dfb, pll) stay within the DESIGN tolerance of the reference
# (<= 0.5% of pixels off by > 1/255) while the approximate ones (wboit,
# unsorted) show a larger rmse than dfb; report.md names the renderer; a
# bad method name is a usage error (exit 2). Prints the summary rows.
set -u
B="$OIT_BIN/oitbench"
G="$OIT_BIN/oitgen"
T="$OIT_TEST_TMP/oitbench"
rm -rf "$T"
mkdir -p "$T"
FAILS=0
fail() { echo "FAIL: $*" >&2; FAILS=$((FAILS + 1)); }

"$G" quads --count 12 --coverage 0.6 -o "$T/Q.ply" >/dev/null || { echo "oitgen quads failed" >&2; exit 1; }
"$B" "$T/Q.ply" --methods dfb,pll,wboit,unsorted,stream --orbit 2 --size 64x64 \
    --frames 2 --warmup 1 --out "$T/D" 2>"$T/err.txt"
rc=$?
cat "$T/err.txt"
[ "$rc" -eq 0 ] || fail "oitbench exited $rc"
CSV="$T/D/results.csv"
[ -s "$CSV" ] || { fail "no results.csv"; exit 1; }
grep '^summary,' "$CSV"

# field ROW METHOD VIEW COLUMN: one cell of results.csv, by header name.
field() {
    awk -F, -v row="$1" -v m="$2" -v v="$3" -v col="$4" '
        NR == 1 { for (i = 1; i <= NF; i++) if ($i == col) c = i; next }
        $1 == row && $2 == m && $3 == v { print $c; exit }' "$CSV"
}

for m in dfb pll wboit unsorted stream; do
    for v in 0 1; do
        grep -q "^view,$m,$v," "$CSV" || fail "no row for $m view $v"
    done
    grep -q "^summary,$m,," "$CSV" || fail "no summary row for $m"
done
rows=$(grep -c '^view,' "$CSV")
[ "$rows" -eq 10 ] || fail "expected 10 view rows (5 methods x 2 views), got $rows"

[ "$(field summary stream '' status)" = not_runnable ] || fail "stream on a mesh not reported as not_runnable"
grep '^summary,stream,' "$CSV" | grep -q 'part file' || fail "stream's reason does not say it needs a part file"

for m in dfb pll; do
    for v in 0 1; do
        pct=$(field view $m $v pct_over_1_255)
        awk -v p="$pct" 'BEGIN { exit !(p != "" && p + 0 <= 0.5) }' ||
            fail "$m view $v: $pct% of pixels off by > 1/255 (allowed 0.5%)"
    done
done
dfb_rmse=$(field summary dfb '' rmse)
for m in wboit unsorted; do
    r=$(field summary $m '' rmse)
    echo "rmse $m $r vs dfb $dfb_rmse"
    awk -v r="$r" -v d="$dfb_rmse" 'BEGIN { exit !(r != "" && d != "" && r + 0 > d + 0) }' ||
        fail "$m rmse $r not larger than dfb's $dfb_rmse"
done
# Timings must be real figures, and the frame counts add up in the JSON.
ms=$(field summary dfb '' ms_median)
awk -v x="$ms" 'BEGIN { exit !(x != "" && x + 0 > 0) }' || fail "dfb median ms '$ms'"
grep -q '"timed_frames": 4' "$T/D/results.json" || fail "results.json lacks 4 timed frames (2 views x 2)"

[ -s "$T/D/report.md" ] || fail "no report.md"
grep -q 'GL renderer: ..*' "$T/D/report.md" || fail "report.md does not name the GL renderer"
grep -q 'side by side' "$T/D/report.md" || fail "report.md lacks the note on timings"

"$B" "$T/Q.ply" --methods dfb,bogus --orbit 1 --out "$T/E" 2>/dev/null
rc=$?
[ "$rc" -eq 2 ] || fail "--methods bogus exited $rc, expected 2"
[ ! -e "$T/E" ] || fail "--methods bogus still wrote $T/E"
"$B" --help | grep -q -- '--warmup' || fail "--help does not document --warmup"

if [ "$FAILS" -ne 0 ]; then
    echo "test_oitbench: $FAILS failure(s)" >&2
    exit 1
fi
echo "test_oitbench: ok"
