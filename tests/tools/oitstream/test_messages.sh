#!/bin/sh
# What a newcomer meets first: exit codes, refusals, notes and --help.
# usage: test_messages.sh PART
#   driver     stencil routing the driver refuses (llvmpipe does not route per
#              sample) is a runtime failure, exit 1, the same for
#              `--method stencil` and `--capture stencil`, each message naming
#              the file and the self-test's reason (skipped where it routes)
#   noext      a model without a file extension: exit 3 from oitstream and
#              oitprep, saying so, naming the file and the extensions expected
#   pack       --capture compute with --pack first-k (compute has no K-slot
#              first pass) is a usage error naming both flags; the packs
#              compute does honour run
#   help       --help has one --stats entry, and neither array nor stencil
#              (which lose layers past K) among the exact methods
#   nonfinite  in core, triangles dropped for a NaN coordinate are said on
#              stderr with the file and the count; the rest is drawn, exit 0
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
PART=${1:-}
S="$OIT_BIN/oitstream"
P="$OIT_BIN/oitprep"
need_tools "$S" "$P"
scratch "messages_$PART"

# quads FILE: two translucent quads, one behind the other.
quads() {
    {
        printf 'ply\nformat ascii 1.0\nelement vertex 8\n'
        printf 'property float x\nproperty float y\nproperty float z\n'
        printf 'property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n'
        printf 'element face 4\nproperty list uchar int vertex_indices\nend_header\n'
        for z in 0.1 -0.2; do
            for xy in "-1 -1" "1 -1" "1 1" "-1 1"; do
                printf '%s %s 200 80 40 120\n' "$xy" "$z"
            done
        done
        printf '3 0 1 2\n3 0 2 3\n3 4 5 6\n3 4 6 7\n'
    } >"$1"
}

case "$PART" in
driver)
    quads "$T/quads.ply"
    "$P" "$T/quads.ply" -o "$T/quads.oitp" >/dev/null 2>&1 || die "oitprep quads.ply"
    expect_rc_any() { "$@" >"$T/out.txt" 2>"$T/err.txt"; rc=$?; }
    expect_rc_any "$S" "$T/quads.oitp" --capture stencil --max-layers 4 --size 32x32 --quiet
    [ "$rc" -ne 0 ] || skip "this driver routes fragments per sample: stencil runs"
    cat "$T/err.txt"
    expect_rc 1 "$S" "$T/quads.oitp" --capture stencil --max-layers 4 --size 32x32 --quiet
    expect_err "quads.oitp: " "--capture stencil's refusal does not name the file"
    expect_err "--capture stencil" "--capture stencil's refusal does not name the flag"
    expect_err "self-test failed\|exceeds" "--capture stencil's refusal gives no reason"
    expect_rc 1 "$S" "$T/quads.ply" --method stencil --max-layers 4 --size 32x32 --quiet
    cat "$T/err.txt"
    expect_err "quads.ply: " "--method stencil's refusal does not name the file"
    expect_err "self-test failed\|exceeds" "--method stencil's refusal gives no reason"
    # the part file's triangles in core: the same limit, the same code
    expect_rc 1 "$S" "$T/quads.oitp" --method stencil --max-layers 4 --size 32x32 --quiet
    ;;
noext)
    quads "$T/noext"
    want="noext: no file extension to tell its format by (expected .ply .obj"
    expect_rc 3 "$S" "$T/noext" --method reference --size 32x32 --quiet
    cat "$T/err.txt"
    expect_err "$want" "oitstream on a file without an extension"
    expect_err ".step .stp .iges .igs" "oitstream does not list the CAD extensions"
    expect_rc 3 "$P" "$T/noext" -o "$T/noext.oitp"
    expect_err "$want" "oitprep on a file without an extension"
    # a dot with nothing after it is no extension either
    cp "$T/noext" "$T/dot."
    expect_rc 3 "$S" "$T/dot." --method reference --size 32x32 --quiet
    expect_err "dot\.: no file extension" "a name ending in a dot"
    # an extension no reader takes is still named as such
    cp "$T/noext" "$T/x.xyz"
    expect_rc 3 "$S" "$T/x.xyz" --method reference --size 32x32 --quiet
    expect_err "unknown mesh format '.xyz'" "an unknown extension"
    ;;
pack)
    quads "$T/quads.ply"
    "$P" "$T/quads.ply" -o "$T/quads.oitp" >/dev/null 2>&1 || die "oitprep quads.ply"
    expect_rc 2 "$S" "$T/quads.oitp" --capture compute --pack first-k --size 32x32 --quiet
    cat "$T/err.txt"
    expect_err "--capture compute" "the refusal does not name --capture compute"
    expect_err "--pack first-k" "the refusal does not name --pack first-k"
    # what compute does run: auto and counted (its own packs), budget and
    # disjoint (packs cut by their rule, each captured in compute)
    for p in auto counted budget disjoint; do
        expect_rc 0 "$S" "$T/quads.oitp" --capture compute --pack "$p" --size 32x32 --quiet
    done
    ;;
help)
    expect_rc 0 "$S" --help
    n=$(grep -c '^  --stats ' "$T/out.txt")
    [ "$n" -eq 1 ] || fail "--help has $n --stats entries, want 1"
    grep -q 'window' "$T/out.txt" && sed -n '/^  --stats /,/^  --[a-z]/p' "$T/out.txt" |
        grep -q -- '--window' || fail "the --stats entry does not say what it holds with --window"
    # the --method entry, one line, each class up to the next
    m=$(sed -n '/^  --method /,/^  --pack /p' "$T/out.txt" | sed '$d' | tr -s ' \n' '  ')
    echo "--method: $m"
    exact=$(echo "$m" | sed -n 's/.*Exact:\(.*\)/\1/p' | sed 's/Bounded.*//; s/Approximate.*//')
    [ -n "$exact" ] || fail "--help lists no exact methods"
    echo "$exact" | grep -q 'dfb' || fail "dfb is not among the exact methods: $exact"
    for w in array stencil; do
        echo "$exact" | grep -qw "$w" && fail "$w (it loses layers past K) is listed as exact"
        echo "$m" | grep -qw "$w" || fail "$w is not described under --method"
    done
    ;;
nonfinite)
    printf 'v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n' >"$T/nf.obj"
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/one.obj"
    for m in dfb reference; do
        expect_rc 0 "$S" "$T/nf.obj" --method $m --size 32x32 --out "$T/nf_$m.png" --quiet
        cat "$T/err.txt"
        expect_err "nf.obj: 2 triangles in, 1 drawn (dropped 1 with a non-finite coordinate" \
            "$m: the dropped triangle is not reported"
        [ "$(grep -c . "$T/err.txt")" -eq 1 ] || fail "$m: the note is not one line"
        expect_rc 0 "$S" "$T/one.obj" --method $m --size 32x32 --out "$T/one_$m.png" --quiet
        [ -s "$T/err.txt" ] && fail "$m: a note where nothing was dropped: $(cat "$T/err.txt")"
        # the kept triangle is drawn: the same image as the file without the other
        expect_equal "$m: nf.obj vs its finite triangle alone" "$T/nf_$m.png" "$T/one_$m.png"
    done
    ;;
*) echo "usage: $0 driver|noext|pack|help|nonfinite" >&2; exit 2 ;;
esac
finish "test_messages $PART"
