#!/bin/sh
# oitstream --method stream --epsilon E (early termination) against DFB on
# the test_streamer grid, 3 orbit views, both shading modes.
# Usage: test_epsilon.sh WRITER   (WRITER: test_streamer, writes the file)
# E = 0 must equal DFB exactly (max_abs 0). E > 0 drops only what lies
# behind pixels whose transmittance fell below E, so the error stays within
# E + 1/255 (the PNG rounding) and the fragment count must fall, more for
# larger E; the stats must report the E they ran with.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
scratch epsilon

P="$T/grid.oitp"
"$1" "$P" || die "cannot write the part file"

# run SHADING E: stream with early termination E, compared view by view
# with DFB; prints the figures and sets FRAGS to the fragments of all views.
run() {
    sh=$1 e=$2 d="$T/${1}_$2"
    "$S" "$P" --size 128x128 --orbit 3 --shading "$sh" --epsilon "$e" --out "$d" \
        --stats "$d.json" --quiet || { fail "$sh E=$e: stream exited $?"; FRAGS=0; return; }
    FRAGS=$(json_sum fragments < "$d.json")
    ms=$(json_sum ms < "$d.json")
    [ "$(json_all epsilon "$d.json" |
         awk -v e="$e" '$1 - e > 1e-6 || e - $1 > 1e-6 {bad = 1} END {print bad + 0}')" -eq 0 ] ||
        fail "$sh E=$e: stats report another epsilon: $(grep -o '"epsilon": [^,}]*' "$d.json" | head -n 1)"
    worst=0
    for i in 000 001 002; do
        c=$("$S" --compare "$d/frame_$i.png" "$T/${sh}_dfb/frame_$i.png" --json) ||
            { fail "$sh E=$e view $i: compare failed"; continue; }
        m=$(echo "$c" | json_num max_abs)
        worst=$(awk -v a="$m" -v b="$worst" 'BEGIN{print (a > b) ? a : b}')
    done
    bound=$(awk -v e="$e" 'BEGIN{print e + 1.0 / 255 + 1e-6}')
    [ "$e" = 0 ] && bound=0
    echo "$sh E=$e: fragments $FRAGS, ms $ms (3 views), max_abs vs dfb $worst (bound $bound)"
    awk -v m="$worst" -v b="$bound" 'BEGIN{exit !(m <= b)}' ||
        fail "$sh E=$e: max_abs $worst exceeds $bound"
}

for sh in transparent translucent; do
    "$S" "$P" --method dfb --size 128x128 --orbit 3 --shading "$sh" --out "$T/${sh}_dfb" \
        --quiet || { fail "$sh: dfb exited $?"; continue; }
    run "$sh" 0; f0=$FRAGS
    run "$sh" 0.01; f1=$FRAGS
    run "$sh" 0.05; f5=$FRAGS
    [ "$f0" -gt 0 ] && [ "$f1" -le "$f0" ] && [ "$f5" -lt "$f0" ] && [ "$f5" -le "$f1" ] ||
        fail "$sh: fragments do not fall with epsilon: $f0 (E=0), $f1 (0.01), $f5 (0.05)"
done

# Whole parts behind saturated tiles (view/render/capture/saturation.h): on 600 stacked
# squares seen head on, E = 0.02 saturates every pixel after ~123 layers, so
# parts must be skipped (neither uploaded nor drawn), drawn + skipped must
# be the parts E = 0 draws, uploads must fall, and the error stays in bound.
# K-slot packs (--pack disjoint): the counted capture takes the stack in
# one pack, before any tile can saturate.
"$OIT_BIN/oitgen" hard --case stack -o "$T/stack.ply" >/dev/null &&
    "$OIT_BIN/oitprep" "$T/stack.ply" -o "$T/stack.oitp" >/dev/null ||
    fail "cannot make the stack part file"
V=0,0,5,0,0,0,0,1,0,18
for e in 0 0.02; do
    "$S" "$T/stack.oitp" --size 128x128 --view $V --epsilon $e --pack disjoint \
        --out "$T/stack_$e.pfm" \
        --stats "$T/stack_$e.json" --quiet || fail "stack E=$e: stream exited $?"
done
d0=$(json_num parts_drawn < "$T/stack_0.json") s0=$(json_num parts_skipped < "$T/stack_0.json")
d2=$(json_num parts_drawn < "$T/stack_0.02.json") s2=$(json_num parts_skipped < "$T/stack_0.02.json")
b0=$(json_num bytes_uploaded < "$T/stack_0.json") b2=$(json_num bytes_uploaded < "$T/stack_0.02.json")
m=$("$S" --compare "$T/stack_0.02.pfm" "$T/stack_0.pfm" --json | json_num max_abs)
echo "stack E=0: $d0 parts drawn, $s0 skipped, $b0 bytes; E=0.02: $d2 drawn, $s2 skipped, $b2 bytes, max_abs $m"
[ "$s0" = 0 ] || fail "stack E=0 skipped $s0 parts"
[ "${s2:-0}" -gt 0 ] && [ $((d2 + s2)) -eq "$d0" ] && [ "$b2" -lt "$b0" ] ||
    fail "stack E=0.02: no parts skipped, or drawn + skipped != $d0, or uploads did not fall"
awk -v m="$m" 'BEGIN{exit !(m <= 0.02 + 1e-6)}' || fail "stack E=0.02: max_abs $m exceeds 0.02"

# Every pack mode skips whole parts: the counted and first-K packs (auto
# is first-K) are cut front first (view/stream/pack.h), so the stack's front
# parts saturate the screen before the rest is read. E = 1/510 keeps every
# float value within 1/510 of the exact image (the same for every mode), so
# no 8-bit value can move by more than one step. 64x64: 16 tiles of 16.
"$S" "$T/stack.oitp" --size 64x64 --view $V --out "$T/stack64_0.pfm" --stats "$T/stack64_0.json" \
    --quiet || fail "stack 64x64 E=0: exited $?"
d64=$(json_num parts_drawn < "$T/stack64_0.json")
for mode in auto counted first-k budget; do
    for e in 0.02 0.00196078; do
        r="$T/stack64_${mode}_$e"
        "$S" "$T/stack.oitp" --size 64x64 --view $V --epsilon $e --pack $mode \
            --out "$r.pfm" --stats "$r.json" --quiet || { fail "stack $mode E=$e: exited $?"; continue; }
        d=$(json_num parts_drawn < "$r.json") s=$(json_num parts_skipped < "$r.json")
        m=$("$S" --compare "$r.pfm" "$T/stack64_0.pfm" --json | json_num max_abs)
        echo "stack --pack $mode E=$e: $d drawn, $s skipped, max_abs $m"
        [ "${s:-0}" -gt 0 ] && [ $((d + s)) -eq "$d64" ] ||
            fail "stack $mode E=$e: no parts skipped, or drawn + skipped != $d64"
        awk -v m="${m:-1}" -v e="$e" 'BEGIN{exit !(m <= e + 1e-6)}' ||
            fail "stack $mode E=$e: max_abs $m beyond $e"
    done
done

# A strongly coloured translucent shell: eight closed red boxes in a row,
# seen end on over black. The medium absorbs green and blue (optical depth
# about 3 a box) but not red, so after the first box T is tiny in green and
# blue while red keeps 0.96 a face: no pixel is saturated in every channel,
# E = 0.05 may drop nothing, and the image must equal DFB's (PFM, per
# channel). A test on the smallest channel instead of the largest drops
# everything behind the first box and loses the red. Wang & Xie's scheme, so
# the boxes are many parts in many packs: fragments are dropped only from
# the pack after a pixel saturates, and the fast scheme makes one part.
awk 'BEGIN {
    n = 8; print "ply\nformat ascii 1.0\nelement vertex", 8 * n
    print "property float x\nproperty float y\nproperty float z"
    print "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha"
    print "element face", 12 * n; print "property list uchar int vertex_indices\nend_header"
    for (b = 0; b < n; b++)
        for (c = 0; c < 8; c++)
            printf "%g %g %g 255 0 0 255\n", c % 2 ? 1 : -1, int(c / 2) % 2 ? 1 : -1, 1.5 * b + (c >= 4)
    split("0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5", f, " ")
    for (b = 0; b < n; b++)
        for (q = 0; q < 6; q++) {
            a = f[4 * q + 1] + 8 * b; e = f[4 * q + 2] + 8 * b
            c = f[4 * q + 3] + 8 * b; d = f[4 * q + 4] + 8 * b
            print 3, a, e, c; print 3, a, c, d
        }
}' > "$T/shell.ply" && "$OIT_BIN/oitprep" "$T/shell.ply" -o "$T/shell.oitp" --scheme guaranteed >/dev/null ||
    fail "cannot make the red shell part file"
V=0.3,0.2,-6,0,0,6,0,1,0,30
SH="--size 96x96 --view $V --shading translucent --absorption 40 --background 0,0,0 --quiet"
"$S" "$T/shell.oitp" --method dfb $SH --out "$T/shell_dfb.pfm" || fail "red shell: dfb exited $?"
for e in 0 0.05; do
    "$S" "$T/shell.oitp" $SH --epsilon $e --out "$T/shell_$e.pfm" --stats "$T/shell_$e.json" ||
        fail "red shell E=$e: stream exited $?"
done
f0=$(json_sum fragments < "$T/shell_0.json") f5=$(json_sum fragments < "$T/shell_0.05.json")
m=$("$S" --compare "$T/shell_0.05.pfm" "$T/shell_dfb.pfm" --json | json_num max_abs)
echo "red shell: E=0 $f0 fragments, E=0.05 $f5 fragments, max_abs vs dfb $m (per channel)"
[ "${f0:-0}" -gt 0 ] && [ "$f5" = "$f0" ] ||
    fail "red shell: E=0.05 dropped fragments ($f5 of $f0) though red is never saturated"
awk -v m="${m:-1}" 'BEGIN{exit !(m <= 1e-6)}' || fail "red shell E=0.05: max_abs $m against DFB"

# Early termination belongs to the streamer, and E = 1 would drop everything.
"$S" "$P" --epsilon 1 --size 16x16 --quiet >/dev/null 2>&1
[ $? -eq 2 ] || fail "--epsilon 1 was not refused as a usage error"
"$S" "$P" --method dfb --epsilon 0.1 --size 16x16 --quiet >/dev/null 2>&1
[ $? -eq 2 ] || fail "--method dfb --epsilon 0.1 was not refused as a usage error"

finish epsilon
