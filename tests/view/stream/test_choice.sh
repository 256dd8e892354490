#!/bin/sh
# --pack auto's measured choice (view/stream/choice.h) through oitstream on a
# deep stack: it never holds a path its own figures say is slower.
#  - 600 stacked squares (oitgen hard --case stack, --scheme fast), seen
#    from the side of the stack's corner, 12 frames of that one view at
#    64x64: the first frame takes first-k ("seed") and finds more than 1
#    pixel in 50 over K (deep_pixels; it is drawn again counted, as
#    test_firstk.sh checks), so the second probes counted.
#  - every frame's --stats say which path it took, why, and the costs it
#    weighed (choice_first_k_ms, choice_counted_ms); each cost must come
#    from the frames before that drew its path: positive, and no more than
#    the slowest of them (wall or GPU ms; the judge takes the least, of wall
#    time or, with GPU figures, of each frame's larger figure); and every frame
#    not a probe must take the path whose cost is the lower (ties: either);
#    by the last frame both paths are measured.
#  - the images: every frame bit for bit --pack first-k's of the same view,
#    and DFB's on the source mesh to 1/255 on >= 99.9% of pixels.
#  - one image a process starts counted ("seed"), the same image.
# Checked to fail (7 frames flagged) with the judge preferring the higher
# cost (the comparisons of judge_probe and cheapest in view/stream/choice.c
# reversed). A judge_probe that keeps every probe alone is caught a frame
# later by oit_choice_begin's own re-check, so this run cannot see it; the
# unit test stream_choice does.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
scratch choice
need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
gen_hard stack "$T/stack.ply"
prep_or_die "$T/stack.ply" "$T/stack.oitp" --scheme fast
for i in 1 2 3 4 5 6 7 8 9 10 11 12; do echo "1.5,1.2,4,0,0,0,0,1,0,30"; done > "$T/still.txt"
W="--size 64x64 --walk $T/still.txt --quiet"
"$S" "$T/stack.oitp" $W --out "$T/auto/" --stats "$T/auto.json" || die "auto exited $?"
"$S" "$T/stack.oitp" $W --pack first-k --out "$T/firstk/" || die "--pack first-k exited $?"
"$S" "$T/stack.ply" --method dfb --size 64x64 --walk "$T/still.txt" --quiet --out "$T/dfb/" ||
    die "dfb on the mesh exited $?"

# One line a frame: path why first-k-cost counted-cost ms gpu_ms deep-pixels.
grep '"choice"' "$T/auto.json" | sed 's/.*"ms": \([-0-9.]*\), "gpu_ms": \([-0-9.]*\).*"deep_pixels": \([0-9]*\).*"choice": "\([^"]*\)", "choice_why": "\([^"]*\)", "choice_first_k_ms": \([-0-9.]*\), "choice_counted_ms": \([-0-9.]*\).*/\4|\5|\6|\7|\1|\2|\3/' \
    > "$T/frames.txt"
cat "$T/frames.txt"
[ "$(wc -l < "$T/frames.txt")" -eq 12 ] || fail "$(wc -l < "$T/frames.txt") frames with a choice, want 12"
awk -F'|' -v px=$((64 * 64)) '
function bad(m) { print "FAIL: frame " NR - 1 ": " m; fails++ }
{
    path = $1; why = $2; c["first-k"] = $3; c["counted"] = $4; ms = $5; gpu = $6
    if (NR == 1) {
        if (path != "first-k" || why != "seed" || $3 != -1 || $4 != -1)
            bad("the first frame is " path " (" why ", " $3 ", " $4 "), want first-k, seed, no costs")
        if ($7 * 50 <= px)
            bad("pixels over K " $7 " of " px ": the view is not deep enough to probe counted")
    }
    if (NR == 2 && (path != "counted" || why != "probe"))
        bad("the second frame is " path " (" why "), want the probe of counted")
    # each cost: what the frames before measured of its path
    for (p in c) {
        if (!(p in n)) {
            if (c[p] != -1) bad(p " costs " c[p] " before any frame took it")
            continue
        }
        hi = (most_gpu[p] > least[p] ? most_gpu[p] : least[p]) * 1.02 + 2
        if (c[p] <= 0 || c[p] > hi)
            bad(p " costs " c[p] ", its frames before measured " least[p] " ms at least, " most_gpu[p] " at most")
    }
    other = path == "first-k" ? "counted" : "first-k"
    if (why != "probe" && why != "seed" && c[path] >= 0 && c[other] >= 0 && c[path] > c[other])
        bad(path " (" why ") costs " c[path] ", " other " " c[other])
    if (!(path in n) || ms < least[path]) least[path] = ms
    slow = gpu > ms ? gpu : ms
    if (slow > most_gpu[path]) most_gpu[path] = slow
    n[path]++
    last_path = path; last_why = why; last_c = c[path]; last_o = c[other]
}
END {
    if (last_c < 0 || last_o < 0) bad("the last frame weighed " last_c " against " last_o ": not both measured")
    print "auto: " n["first-k"] + 0 " first-k frames (least " least["first-k"] " ms), " \
          n["counted"] + 0 " counted (least " least["counted"] " ms); last frame " last_path " (" last_why ")"
    exit fails > 0
}' "$T/frames.txt" || fail "the choice does not follow its measurements"

for i in 000 001 002 005 011; do
    cmp -s "$T/auto/frame_$i.png" "$T/firstk/frame_$i.png" ||
        fail "frame $i: auto differs from --pack first-k"
    compare "frame $i vs dfb on the mesh" "$T/auto/frame_$i.png" "$T/dfb/frame_$i.png" 0.1
done
# One image a process (oit_renderer_desc.frames = 1): auto starts with
# counted packs, which store exactly what the frame holds, not first-K's
# K-slot store that only later frames amortize; the image is the same.
"$S" "$T/stack.oitp" --size 64x64 --view "$(head -n 1 "$T/still.txt")" --out "$T/one.png" \
    --stats "$T/one.json" --quiet || die "one image exited $?"
grep -q '"choice": "counted", "choice_why": "seed"' "$T/one.json" ||
    fail "one image: auto did not start counted ($(grep -o '"choice[a-z_]*": "[^"]*"' "$T/one.json" | tr '\n' ' '))"
cmp -s "$T/one.png" "$T/firstk/frame_000.png" || fail "one image: differs from --pack first-k"
finish choice
