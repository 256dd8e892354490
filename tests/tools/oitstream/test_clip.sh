#!/bin/sh
# Section planes (oitstream --clip, view/render/image/clip.h) through every method, on
# 12 translucent quads at 12 depths (z symmetric about 0, one part each in
# the part file):
#   agree    an oblique plane: every exact method and the stream equal the
#            Embree reference within 0.01% of pixels (and differ from the
#            unclipped image: the plane cuts)
#   slab     two planes keep one quad: every method, the approximate ones
#            too (one layer is exact for them), equals the reference
#   empty    a plane that removes everything: the background, every method;
#            the stream draws and uploads no part
#   cull     z <= 0 keeps 6 quads: the stream neither uploads nor draws the
#            other 6 parts (--stats parts_clipped, bytes_clipped), and its
#            uploaded bytes plus the clipped ones are the unclipped frame's
#   opaque   a plane through the opaque boxes of the hard case `mixed`:
#            what the cut-away opaque halves hid shows again, so the opaque
#            pre-pass must drop clipped fragments as the captures do; DFB,
#            array slots and the stream equal the reference
#   errors   bad --clip input: exit 2 and a message naming the fault
#   window   (under X) the viewer's X makes the plane it prints, the frame
#            equals --clip with that plane; ] moves it by 1/25 of the radius
# usage: test_clip.sh PART PNG_FIGURES
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
PART=$1 FIG=$2
need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep" "$OIT_BIN/oitstream"
S="$OIT_BIN/oitstream"
scratch "clip_$PART"
cd "$T" || exit 1
SIZE=128x128
"$OIT_BIN/oitgen" quads --count 12 --coverage 0.6 -o q.ply >/dev/null || die "oitgen quads"
"$OIT_BIN/oitprep" q.ply -o q.oitp --part-triangles 2 >/dev/null || die "oitprep"
EXACT="dfb array stencil pll ppll4 b3d dp ddp guarded"
ALL="$EXACT unsorted wboit f2b"

# render NAME METHOD CLIP...: q.ply (q.oitp for stream) into NAME.png;
# returns 1 when the method cannot run on this driver (stencil routing
# where its self-test fails, as on llvmpipe: view/render/capture/capture_stencil_probe.h)
render() {
    _n=$1 _m=$2
    shift 2
    _in=q.ply
    [ "$_m" = stream ] && _in=q.oitp
    _k=""
    [ "$_m" = stencil ] && _k="--max-layers 4" # llvmpipe's multisample limit
    # shellcheck disable=SC2086
    "$S" $_in --method "$_m" --size $SIZE $_k "$@" --out "$_n.png" --stats "$_n.json" \
        --quiet >"$_n.txt" 2>&1 && return 0
    if grep -q "self-test failed" "$_n.txt"; then
        echo "$_m: not on this driver ($(cat "$_n.txt"))"
        return 1
    fi
    cat "$_n.txt"
    fail "$_n: $_m $* failed"
    return 1
}

case $PART in
opaque)
    gen_hard mixed mixed.ply
    prep_or_die mixed.ply mixed.oitp --part-triangles 64
    for m in reference dfb array stream; do
        _in=mixed.ply
        [ "$m" = stream ] && _in=mixed.oitp
        "$S" $_in --method "$m" --size $SIZE --clip 0,0,-1,0 --out "o_$m.png" --quiet ||
            fail "opaque: $m --clip failed"
    done
    "$S" mixed.ply --method reference --size $SIZE --out o_plain.png --quiet || fail "reference"
    expect_differ "the plane cuts the opaque boxes" o_reference.png o_plain.png 500
    for m in dfb array stream; do
        compare "opaque $m vs reference" o_reference.png "o_$m.png" 0.01
    done
    ;;
agree)
    CLIP="--clip 0.4,0.3,-1,0.05"
    render ref reference $CLIP
    render plain reference
    expect_differ "the plane cuts" ref.png plain.png 1000
    for m in $EXACT stream; do
        render "$m" "$m" $CLIP || continue
        compare "$m vs reference" ref.png "$m.png" 0.01
    done
    ;;
slab)
    # Quad 8 of 12 lies at z = 0.4167: keep 0.35 <= z <= 0.5.
    CLIP="--clip 0,0,1,-0.35 --clip 0,0,-1,0.5"
    render ref reference $CLIP
    render plain reference
    expect_differ "the slab cuts" ref.png plain.png 1000
    set -- $("$FIG" ref.png)
    [ "$3" -gt 1000 ] || fail "the slab keeps nothing ($3 non-white pixels)"
    for m in $ALL stream; do
        render "$m" "$m" $CLIP || continue
        compare "$m vs reference" ref.png "$m.png" 0.01
    done
    ;;
empty)
    for m in reference $ALL stream; do
        render "$m" "$m" --clip 0.1,0,-1,-2 || continue
        set -- $("$FIG" "$m.png")
        [ "$3" -eq 0 ] || fail "$m: $3 pixels not the background behind a plane that cuts all"
    done
    [ "$(json_num parts_drawn stream.json)" = 0 ] || fail "stream drew parts cut away"
    [ "$(json_num bytes_uploaded stream.json)" = 0 ] || fail "stream uploaded parts cut away"
    [ "$(json_num parts_clipped stream.json)" = 12 ] ||
        fail "parts_clipped $(json_num parts_clipped stream.json), want 12"
    ;;
cull)
    render all stream
    render half stream --clip 0,0,-1,0
    json_str clip half.json | grep -q '^0,0,-1,0$' ||
        fail "--stats clip: '$(json_str clip half.json)', want 0,0,-1,0"
    DRAWN=$(json_num parts_drawn half.json) CLIPPED=$(json_num parts_clipped half.json)
    echo "z <= 0: $DRAWN parts drawn, $CLIPPED clipped"
    [ "$CLIPPED" = 6 ] || fail "parts_clipped $CLIPPED, want the 6 quads with z > 0"
    [ "$DRAWN" = 6 ] || fail "parts_drawn $DRAWN, want 6"
    [ "$(json_num parts_clipped all.json)" = 0 ] || fail "clipped parts without a plane"
    UP=$(json_num bytes_uploaded half.json) CB=$(json_num bytes_clipped half.json)
    ALLUP=$(json_num bytes_uploaded all.json)
    [ $((UP + CB)) -eq "$ALLUP" ] && [ "$CB" -gt 0 ] ||
        fail "uploaded $UP + clipped $CB bytes, want the unclipped frame's $ALLUP"
    "$S" q.oitp --size $SIZE --clip 0,0,-1,0 2>/dev/null | grep -q "(0 culled, 6 clipped" ||
        fail "the frame line does not say 6 clipped"
    # The same cut in core: the stream's image is DFB's.
    render dfb dfb --clip 0,0,-1,0
    compare "stream vs dfb, z <= 0" dfb.png half.png 0.01
    ;;
errors)
    for bad in "1,2,3:expected four numbers" "1,0,0,x:expected four numbers" \
        "0,0,0,1:normal (a,b,c) is zero" "1,0,0,nan:expected four numbers" \
        "1,0,0,1,5:expected four numbers"; do
        val=${bad%%:*} want=${bad#*:}
        expect_rc 2 "$S" q.ply --clip "$val" --out x.png
        expect_err "$want" "--clip $val"
    done
    expect_rc 2 "$S" q.ply --clip 1,0,0,0 --clip 1,0,0,0 --clip 1,0,0,0 --clip 1,0,0,0 \
        --clip 1,0,0,0 --clip 1,0,0,0 --clip 1,0,0,0 --out x.png
    expect_err "at most 6 planes" "7 planes"
    [ ! -e x.png ] || fail "a refused --clip wrote x.png"
    "$S" --help | grep -q -- "--clip nx,ny,nz,d" || fail "--help does not document --clip"
    ;;
window)
    [ -n "${DISPLAY:-}" ] || skip "no DISPLAY (run under xvfb-run)"
    "$S" q.ply --window --no-overlay --size $SIZE --window-script "X" \
        --window-screenshot x.png >x.txt 2>&1 || { cat x.txt; fail "viewer X"; }
    PLANE=$(sed -n 's/^viewer: section plane 1 of 1: \([^ ]*\) keeps.*/\1/p' x.txt)
    [ -n "$PLANE" ] || { cat x.txt; fail "X printed no plane"; }
    render cli dfb --clip "$PLANE"
    EQUAL=0.002 expect_equal "X = --clip $PLANE" x.png cli.png
    render plain dfb
    expect_differ "X cuts" x.png plain.png 500
    "$S" q.ply --window --no-overlay --size $SIZE --window-script "X]]" \
        --window-screenshot m.png >m.txt 2>&1 || { cat m.txt; fail "viewer X]]"; }
    MOVED=$(sed -n 's/^viewer: section plane 1 of 1: \([^ ]*\) keeps.*/\1/p' m.txt | tail -1)
    render mcli dfb --clip "$MOVED"
    EQUAL=0.002 expect_equal "X]] = --clip $MOVED" m.png mcli.png
    expect_differ "] moves the plane" m.png x.png 100
    ;;
*) die "unknown part $PART" ;;
esac
finish "clip $PART"
