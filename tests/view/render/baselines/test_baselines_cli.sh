#!/bin/sh
# The baselines end to end, oitstream --method M against --method dfb:
# the storing methods (pll, ppll4 paged lists, b3d fixed arrays) and guarded
# at --epsilon 0 must equal DFB on a closed-solid scene (ties included); dp
# and ddp on a scene of quads at distinct depths; f2b at --epsilon 0 on the
# quads seen head-on (its centroid order is then the depth order), and
# within its threshold at the default; unsorted and wboit must render and
# differ from DFB by a finite amount. ddp refuses translucent shading (exit
# 3), --epsilon is refused for a method without a threshold (exit 2), and
# oitbench runs every new method. Prints every comparison.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../../lib.sh}"
S="$OIT_BIN/oitstream"
G="$OIT_BIN/oitgen"
B="$OIT_BIN/oitbench"
scratch baselines_cli

# render MODEL METHOD OUT [OPTION...]
render() {
    model=$1; x=$2; out=$3; shift 3
    "$S" "$model" --method "$x" --size 160x120 --out "$out" --quiet "$@" 2>"$T/err.txt" ||
        { fail "$(basename "$out"): $(cat "$T/err.txt")"; return 1; }
}

# vs_dfb MODEL METHOD MAX [OPTION...]: renders the method with the options
# (and DFB, once per model and options other than --epsilon), prints the
# comparison, checks max_abs <= MAX.
vs_dfb() {
    model=$1; m=$2; max=$3; shift 3
    opts=$(echo "$*" | sed 's/--epsilon [^ ]*//' | tr -c 'a-z0-9.\n' '_')
    ref="$T/$(basename "$model" .ply)$opts.dfb.pfm"
    tag=$(basename "$model" .ply)_$m$(echo "$*" | tr -c 'a-z0-9.\n' '_')
    [ -s "$ref" ] || render "$model" dfb "$ref" $(echo "$*" | sed 's/--epsilon [^ ]*//') ||
        return
    render "$model" "$m" "$T/$tag.pfm" "$@" || return
    j=$("$S" --compare "$ref" "$T/$tag.pfm" --json) ||
        { fail "$tag: compare $m"; return; }
    echo "$tag $m vs dfb: $j" | tr '\n' ' '; echo
    got=$(echo "$j" | json_num max_abs)
    awk -v g="$got" -v m="$max" 'BEGIN { exit !(g != "" && g + 0 == g && g <= m) }' ||
        fail "$tag: $m differs from dfb by $got (allowed $max)"
}

"$G" plant --triangles 10000 -o "$T/plant.ply" >/dev/null || fail "oitgen plant"
"$G" quads --count 24 -o "$T/quads.ply" >/dev/null || fail "oitgen quads"
HEAD_ON="0,0,4,0,0,0,0,1,0,45"
for m in pll ppll4 b3d; do
    vs_dfb "$T/plant.ply" $m 0.0039216
    vs_dfb "$T/quads.ply" $m 0.0039216
done
vs_dfb "$T/plant.ply" guarded 0.0039216 --epsilon 0
vs_dfb "$T/quads.ply" dp 0.0039216
vs_dfb "$T/quads.ply" ddp 0.0039216
vs_dfb "$T/quads.ply" f2b 0.0039216 --epsilon 0 --view "$HEAD_ON"
vs_dfb "$T/quads.ply" f2b 0.0239216 --view "$HEAD_ON"
vs_dfb "$T/plant.ply" guarded 1
vs_dfb "$T/plant.ply" f2b 1
vs_dfb "$T/plant.ply" wboit 1
vs_dfb "$T/plant.ply" unsorted 1

expect_rc 3 "$S" "$T/quads.ply" --method ddp --shading translucent --size 16x16 --quiet \
    --out "$T/ddp_translucent.png"
expect_err 'dual peeling: translucent' "ddp translucent"
expect_rc 2 "$S" "$T/quads.ply" --method pll --epsilon 0.1 --size 16x16 --quiet

"$B" "$T/quads.ply" --methods ppll4,b3d,ddp,guarded,f2b --orbit 1 --size 48x48 \
    --frames 1 --warmup 0 --out "$T/bench" 2>"$T/err.txt" || fail "oitbench: $(cat "$T/err.txt")"
for m in ppll4 b3d ddp guarded f2b; do
    grep -q "^summary,$m,,ok," "$T/bench/results.csv" ||
        fail "oitbench: no ok summary for $m: $(grep "^summary,$m," "$T/bench/results.csv")"
done
for m in ppll4 b3d ddp guarded f2b; do
    "$S" --help | grep -q "$m" || fail "oitstream --help does not name $m"
    "$B" --help | grep -q "$m" || fail "oitbench --help does not name $m"
done
finish test_baselines_cli
