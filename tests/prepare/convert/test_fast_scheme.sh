#!/bin/sh
# oitprep --scheme fast (prepare/partition/kd_fast.h) on one scene: a hard case
# (oitgen hard --case NAME), the demo (demo), or a fetched mesh (mesh:FILE,
# skipped when the cache lacks it). Checks:
#   the conversion succeeds, the file passes `oitprep info` (flagged as of
#   measured bounds) and `oitprep verify` exits 0 with 0 order and 0 slab
#   violations (hits over a measured bound are reported, not failed);
#   for demo and mesh:FILE, triangles out <= 1.10 x triangles in, and the
#   parts are large: fewer than one part per 1,000 input triangles (the
#   guaranteed scheme makes one per 6-60);
#   on two views (three for stack and dense, one from inside) the stream
#   (counted packs, the default) equals DFB on the same file: at most 0.1%
#   of pixels off by more than 1/255 and 0 overflow pixels.
# Prints every figure.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
NAME=${1:?usage: test_fast_scheme.sh CASE|demo|mesh:FILE}
P="$OIT_BIN/oitprep"
S="$OIT_BIN/oitstream"
scratch "fast_$(echo "$NAME" | tr ':/.' '___')"
SIZE=${OIT_FAST_SIZE:-128x128}
FAIL_PREFIX="$NAME: "
INDENT="  "

ratio_check=0
case "$NAME" in
demo)
    IN="$T/in.ply"
    "$OIT_BIN/oitgen" demo -o "$IN" >/dev/null || die "oitgen demo"
    ratio_check=1 ;;
mesh:*)
    need_mesh "${NAME#mesh:}"
    IN=$MESH
    ratio_check=1 ;;
*)
    IN="$T/in.ply"
    gen_hard "$NAME" "$IN" ;;
esac

prep_or_die "$IN" "$T/f.oitp" --scheme fast --stats "$T/prep.json"
tin=$(json_num triangles_in "$T/prep.json")
tout=$(json_num triangles_out "$T/prep.json")
parts=$(json_num parts "$T/prep.json")
echo "$NAME: fast scheme: triangles $tin -> $tout, parts $parts, max measured layers" \
    "$(json_num max_measured_layers "$T/prep.json"), clamped $(json_num clamped_parts "$T/prep.json")," \
    "$(json_num total "$T/prep.json") s"
grep -q '"scheme": "fast"' "$T/prep.json" || fail "stats do not name the fast scheme"
# No part of the fast scheme is wide (the guaranteed scheme's vertex star):
# a part measured above K is only deep, in the stats and in the kinds' PLY.
[ "$(json_num wide_parts "$T/prep.json")" = 0 ] ||
    fail "the fast scheme's stats call $(json_num wide_parts "$T/prep.json") parts wide"
"$P" parts "$T/f.oitp" -o "$T/kinds.ply" --colour kind >"$T/kinds.txt" 2>&1 ||
    fail "oitprep parts --colour kind: $(cat "$T/kinds.txt")"
grep -q ", 0 wide)" "$T/kinds.txt" || fail "oitprep parts calls fast parts wide: $(cat "$T/kinds.txt")"
if [ "$ratio_check" = 1 ]; then
    at_most "$tout" "$tin * 1.10" || fail "triangles out $tout > 1.10 x in $tin"
    at_most "$parts * 1000" "$tin" || fail "$parts parts for $tin triangles: parts are not large"
fi

if [ "$NAME" = demo ]; then
    # The scheme's own options: a bad name and a scheme that builds its own
    # trees under --manage kd-parts are usage errors (2), naming the option.
    expect_rc 2 "$P" "$IN" -o "$T/x.oitp" --scheme quick
    expect_err "want fast or guaranteed"
    for opt in "--manage kd-parts" "--slabs none" "--max-piece-triangles 64"; do
        # shellcheck disable=SC2086
        expect_rc 2 "$P" "$IN" -o "$T/x.oitp" --scheme fast $opt
        expect_err "${opt% *} applies to --scheme guaranteed only"
    done
    # Without --scheme, Wang & Xie's options select its scheme.
    "$P" "$IN" -o "$T/g.oitp" --slabs none --stats "$T/g.json" >/dev/null 2>&1 &&
        grep -q '"scheme": "guaranteed"' "$T/g.json" || fail "--slabs none did not select guaranteed"
    [ -f "$T/x.oitp" ] && fail "a refused conversion wrote $T/x.oitp"
    expect_rc 2 "$P" "$IN" -o "$T/x.oitp" --scheme fast --part-triangles 0
    # Smaller parts: more of them, each within T (the stats' most per part
    # is not reported, so: at least in / T parts).
    "$P" "$IN" -o "$T/s.oitp" --scheme fast --part-triangles 4096 --stats "$T/s.json" >/dev/null 2>&1 ||
        fail "--part-triangles 4096"
    sp=$(json_num parts "$T/s.json")
    echo "demo at --part-triangles 4096: $sp parts, $(json_num triangles_out "$T/s.json") triangles"
    [ "$sp" -ge $((tin / 4096)) ] && [ "$sp" -gt "$parts" ] || fail "--part-triangles 4096: $sp parts"
fi
"$P" info "$T/f.oitp" --json >"$T/info.json" 2>"$T/info.err" || fail "info: $(cat "$T/info.err")"
grep -q '"measured_bounds": true' "$T/info.json" || fail "info: not flagged as measured bounds"
[ "$(json_num triangles "$T/info.json")" = "$tout" ] || fail "info: triangles differ from the stats"
"$P" verify "$T/f.oitp" >"$T/verify.txt" 2>&1 || fail "verify exited $?: $(tail -n 4 "$T/verify.txt" | tr '\n' ' ')"
sed -n 's/^ *\(layers[^:]*\|order\|slabs\):/  verify \1:/p' "$T/verify.txt"
grep -q "order: 0 violations" "$T/verify.txt" || fail "verify: order violations"
grep -q "slabs: 0, 0 vertices" "$T/verify.txt" || fail "verify: slabs in a fast-scheme file"
grep -q "measured bounds, not guaranteed" "$T/verify.txt" || fail "verify: bounds not reported as measured"

view() {
    vname=$1; shift
    v="$T/$vname"
    "$S" "$T/f.oitp" --method stream --size "$SIZE" "$@" --out "$v-stream.pfm" \
        --stats "$v-stream.json" --quiet || { fail "$vname: stream"; return; }
    "$S" "$T/f.oitp" --method dfb --size "$SIZE" "$@" --out "$v-dfb.pfm" --quiet ||
        { fail "$vname: dfb"; return; }
    ovf=$(json_num overflow_pixels "$v-stream.json")
    echo "  view $vname: packs $(json_num packs "$v-stream.json"), layers" \
        "$(json_num max_layers "$v-stream.json"), overflow $ovf"
    [ "$ovf" = 0 ] || fail "$vname: $ovf overflow pixels"
    compare "$vname: stream vs dfb" "$v-stream.pfm" "$v-dfb.pfm" 0.1
}
view az30 --azimuth 30 --elevation 35
view az210 --azimuth 210 --elevation 35
case "$NAME" in
stack) view inside --view 0.05,0.02,0.0015,0.05,0.02,1,0,1,0,70,0.05,5 ;;
dense) view inside --view 0.01,0.02,0.03,1,0.7,0.4,0,0,1,80,0.1,10 ;;
esac

finish "$NAME"
