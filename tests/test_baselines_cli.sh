#!/bin/sh
# oitstream --method unsorted|wboit|pll|dp end to end, against --method dfb:
# pll must equal DFB on a closed-solid scene (ties included), dp on a scene
# of quads at distinct depths; unsorted and wboit must render and differ
# from DFB by a finite amount. Prints every comparison.
set -u
S="$OIT_BIN/oitstream"
G="$OIT_BIN/oitgen"
T="$OIT_TEST_TMP/baselines_cli"
mkdir -p "$T"
FAILS=0
fail() { echo "FAIL: $*" >&2; FAILS=$((FAILS + 1)); }
json_num() { sed -n "s/.*\"$1\": \([-0-9.e+]*\).*/\1/p" | head -n 1; }

# vs_dfb MODEL METHOD MAX: renders both, prints the comparison, checks max_abs <= MAX.
vs_dfb() {
    model=$1; m=$2; max=$3; base=$(basename "$model" .ply)
    for x in dfb "$m"; do
        "$S" "$model" --method "$x" --size 160x120 --out "$T/${base}_$x.pfm" \
            --stats "$T/${base}_$x.json" --quiet 2>"$T/err.txt" ||
            { fail "$base: --method $x: $(cat "$T/err.txt")"; return; }
    done
    j=$("$S" --compare "$T/${base}_dfb.pfm" "$T/${base}_$m.pfm" --json) ||
        { fail "$base: compare $m"; return; }
    echo "$base $m vs dfb: $j" | tr '\n' ' '; echo
    got=$(echo "$j" | json_num max_abs)
    awk -v g="$got" -v m="$max" 'BEGIN { exit !(g != "" && g + 0 == g && g <= m) }' ||
        fail "$base: $m differs from dfb by $got (allowed $max)"
}

"$G" plant --triangles 10000 -o "$T/plant.ply" >/dev/null || fail "oitgen plant"
"$G" quads --count 24 -o "$T/quads.ply" >/dev/null || fail "oitgen quads"
vs_dfb "$T/plant.ply" pll 0.0039216
vs_dfb "$T/quads.ply" pll 0.0039216
vs_dfb "$T/quads.ply" dp 0.0039216
vs_dfb "$T/plant.ply" wboit 1
vs_dfb "$T/plant.ply" unsorted 1
if [ "$FAILS" -ne 0 ]; then
    echo "test_baselines_cli: $FAILS failure(s)" >&2
    exit 1
fi
echo "test_baselines_cli: ok"
