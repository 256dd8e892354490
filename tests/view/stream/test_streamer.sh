#!/bin/sh
# oitstream --method stream against --method dfb on the same part file.
# Usage: test_streamer.sh grid WRITER   (WRITER: test_streamer, writes the file)
#        test_streamer.sh demo          (`oitgen demo` converted by oitprep in
#                                       parts of 2K triangles: the default
#                                       128K makes it one part, and the
#                                       ring, cache and packs need many)
#        test_streamer.sh bunny         ($OIT_MESH_CACHE/bunny00.off converted)
# Same triangles, same fragments, same tie-break: the images must agree to
# 1/255 on >= 99.9% of pixels, with zero overflow, at least one pack, bytes
# uploaded in the first frame and every later frame's parts uploaded or
# drawn from the residency cache, from 3 orbit views and one eye inside the
# model, in both shading modes; on the small file also with the disjoint
# rule, an upload ring small enough to wrap many times per frame, and K = 2
# (wide parts), and the upload pipeline's own checks (residency below).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
MODE=${1:-grid}
S="$OIT_BIN/oitstream"
scratch "streamer_$MODE"
# frame_figures JSON: "parts_drawn bytes_uploaded cache_hits", one frame a line
frame_figures() {
    sed -n 's/.*"parts_drawn": \([0-9]*\).*"bytes_uploaded": \([0-9]*\), "cache_hits": \([0-9]*\).*/\1 \2 \3/p' "$1"
}

P="$T/scene.oitp"
case "$MODE" in
grid)
    "$2" "$P" || die "cannot write the part file" ;;
demo)
    need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep"
    "$OIT_BIN/oitgen" demo -o "$T/demo.ply" >/dev/null || die "oitgen demo"
    prep_or_die "$T/demo.ply" "$P" --part-triangles 2048 ;;
bunny)
    need_mesh bunny00.off
    need_tools "$OIT_BIN/oitprep"
    prep_or_die "$MESH" "$P" ;;
*) echo "usage: $0 grid WRITER | demo | bunny" >&2; exit 2 ;;
esac

# agree NAME STREAM_OPTS...: stream and dfb on 3 orbit views, compared.
# DFB's images depend on the file, the views and the shading only: drawn
# once a shading mode, for every agree that uses it.
agree() {
    name=$1; shift
    "$S" "$P" --size 128x128 --orbit 3 --out "$T/${name}_s.png" --stats "$T/${name}_s.json" \
        --quiet "$@" || { fail "$name: stream exited $?"; return; }
    shading=$(echo "$@" | sed -n 's/.*--shading \([a-z]*\).*/\1/p')
    d="$T/dfb_${shading:-transparent}"
    if [ ! -f "${d}_002.png" ]; then
        "$S" "$P" --method dfb --size 128x128 --orbit 3 --out "$d.png" --quiet \
            --shading "${shading:-transparent}" || { fail "$name: dfb exited $?"; return; }
    fi
    for i in 000 001 002; do
        compare "$name view $i: stream vs dfb" "$T/${name}_s_$i.png" "${d}_$i.png" 0.1
    done
    check_stats "$name" "$T/${name}_s.json"
}

check_stats() {
    for o in $(json_all overflow_pixels < "$2"); do
        [ "$o" -eq 0 ] || fail "$1: $o overflow pixels"
    done
    for p in $(json_all packs < "$2"); do
        [ "$p" -ge 1 ] || fail "$1: $p packs"
    done
    # Only the first-K capture takes a second pass; every other mode says 0,
    # and so does a frame the automatic mode took counted (auto_first_k 0).
    case $1 in
    firstk*) ;;
    *) bad=$(sed -n 's/.*"second_pass_pixels": \([0-9]*\), "second_pass_packs": \([0-9]*\).*"auto_first_k": \([01]\).*/\1 \2 \3/p' "$2" |
             awk '$3 == 0 && ($1 + $2) > 0' | wc -l)
       [ "$(grep -c '"auto_first_k"' "$2")" -eq "$(grep -c '"ms"' "$2")" ] && [ "$bad" -eq 0 ] ||
           fail "$1: second_pass_pixels/packs not 0 outside first-k ($bad frames)" ;;
    esac
    b=$(json_num bytes_uploaded < "$2")
    [ "${b:-0}" -gt 0 ] || fail "$1: ${b:-no} bytes uploaded in the first frame"
    # A later frame may draw everything from the cache, but not nothing.
    frame_figures "$2" | awk '$2 == 0 && $3 != $1 {bad = 1} END {exit bad}' ||
        fail "$1: a frame uploaded nothing yet drew parts the cache did not hold" \
             "(drawn, uploaded, hits: $(frame_figures "$2" | tr '\n' ';'))"
    for f in $(json_all fragments < "$2"); do
        [ "$f" -gt 0 ] || fail "$1: $f fragments (blank frame)"
    done
    echo "$1: packs per frame: $(json_all packs < "$2" | tr '\n' ' ')" \
         "bytes uploaded: $(json_all bytes_uploaded < "$2" | tr '\n' ' ')" \
         "GPU peak: $(json_all gpu_bytes_peak < "$2" | head -n 1)"
}

# The upload pipeline (issue 6) on one view drawn twice (--walk with the
# same line twice): with the residency cache the second frame uploads
# nothing and draws every part from the cache; without it, it uploads what
# the first did; so does reading on the render thread (--upload-threads 0)
# and a 64K ring that wraps and waits on fences many times a frame; a cache
# smaller than the file keeps part of it. Every image is the same bit for
# bit (PFM, cmp). On an orbit the cache uploads less than no cache.
residency() {
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$T/budget_s.json" | head -n 1 > "$T/twice.txt"
    cat "$T/twice.txt" "$T/twice.txt" > "$T/twice2.txt"
    for cfg in "cache" "zero --cache-budget 0" "nocache --cache-budget off" "inline --upload-threads 0 --cache-budget off" \
               "ring --upload-budget 64K --cache-budget off" "small --cache-budget 64K"; do
        set -- $cfg
        n=$1; shift
        "$S" "$P" --size 128x128 --walk "$T/twice2.txt" --out "$T/res_$n.pfm" \
            --stats "$T/res_$n.json" --quiet "$@" || { fail "residency $n: exited $?"; continue; }
        for i in 000 001; do
            cmp -s "$T/res_cache_000.pfm" "$T/res_${n}_$i.pfm" ||
                fail "residency $n frame $i: image differs from the cached run's first frame"
        done
        set -- $(frame_figures "$T/res_$n.json" | tr '\n' ' ')
        echo "residency $n: frame 0: $1 parts, $2 bytes, $3 hits; frame 1: $4 parts, $5 bytes, $6 hits"
        case $n in
        cache) b0=$2
            [ "$2" -gt 0 ] && [ "$5" -eq 0 ] && [ "$6" -eq "$4" ] && [ "$3" -eq 0 ] ||
                fail "residency cache: the second frame uploaded $5 bytes, $6 of $4 parts cached" ;;
        zero) # 0 is the default budget (liboit's meaning), not "off"
            [ "$2" -eq "$b0" ] && [ "$5" -eq 0 ] && [ "$6" -eq "$4" ] ||
                fail "residency zero: --cache-budget 0 uploaded $5 bytes in frame 1, $6 of $4 cached" ;;
        small)
            [ "$2" -eq "$b0" ] && [ "$5" -gt 0 ] && [ "$5" -lt "$2" ] && [ "$6" -gt 0 ] ||
                fail "residency small: frame 1 uploaded $5 of $2 bytes with $6 hits" ;;
        *)
            [ "$2" -eq "$b0" ] && [ "$5" -eq "$2" ] && [ "$3" -eq 0 ] && [ "$6" -eq 0 ] ||
                fail "residency $n: uploads $2 then $5 bytes (cached run: $b0), hits $3, $6" ;;
        esac
    done
    for c in 256M off; do
        "$S" "$P" --size 64x64 --orbit 8 --cache-budget $c --stats "$T/orbit_$c.json" --quiet ||
            fail "orbit, cache $c: exited $?"
    done
    on=$(json_sum bytes_uploaded < "$T/orbit_256M.json")
    off=$(json_sum bytes_uploaded < "$T/orbit_off.json")
    echo "orbit 8: $on bytes uploaded with the cache, $off without"
    # Every frame times its ordering and packing: 8 figures each, none negative.
    for k in order_ms pack_ms; do
        n=$(json_all $k < "$T/orbit_off.json" | awk '$1 >= 0 {n++} END {print n + 0}')
        [ "$n" -eq 8 ] || fail "orbit 8: $n frames with a $k >= 0, want 8"
    done
    [ "$on" -gt 0 ] && [ "$on" -lt "$off" ] || fail "orbit 8: cache uploads $on, none $off"
    look_around "$b0"

    for bad in "--cache-budget 1K" "--cache-budget -1" "--upload-threads 65"; do
        "$S" "$P" --size 8x8 --quiet $bad >/dev/null 2>&1
        [ $? -eq 2 ] || fail "$bad was not refused as a usage error"
    done
}

# A walk that turns on the spot inside the model (fov 100: a frame draws
# about half the file, a 64K cache holds less than two), so each frame culls
# parts the one before drew and parts come back after idling two frames: a tiny
# cache evicts and refills, and every frame must equal the cache-off frame
# bit for bit (a lookup that handed out an evicted part's stale bytes
# would draw another part's triangles there).
look_around() {
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$T/budget_s.json" | head -n 1 |
        awk -F, '{r = 0.02 * sqrt(($1-$4)^2 + ($2-$5)^2 + ($3-$6)^2)
             split("1 0 -1 0 1 0 0 -1 1 0 0 1 -1 0 0 -1", d, " ")
             for (i = 0; i < 12; i++) { j = (i * 3) % 8
                 printf "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,0,1,0,100\n", $4, $5, $6,
                        $4 + r * d[2*j+1], $5, $6 + r * d[2*j+2] }}' > "$T/around.txt"
    for c in 64K off; do
        "$S" "$P" --size 96x96 --walk "$T/around.txt" --cache-budget $c --out "$T/around_$c.pfm" \
            --stats "$T/around_$c.json" --quiet || fail "look-around, cache $c: exited $?"
    done
    for i in 000 001 002 003 004 005 006 007 008 009 010 011; do
        cmp -s "$T/around_64K_$i.pfm" "$T/around_off_$i.pfm" ||
            fail "look-around frame $i: a 64K cache changes the image (or a frame is missing)"
    done
    hits=$(frame_figures "$T/around_64K.json" | awk 'NR > 2 {s += $3} END {print s + 0}')
    up=$(frame_figures "$T/around_64K.json" | awk '{s += $2} END {print s + 0}')
    echo "look-around, 12 frames, cache 64K: $hits cache hits after frame 2, $up bytes" \
         "uploaded (the file's parts: $1)"
    # More bytes than the file holds: some part was evicted and uploaded again.
    [ "$hits" -gt 0 ] && [ "$up" -gt "$1" ] ||
        fail "look-around: the 64K cache never hit after frame 2, or never evicted"
}

agree budget --pack budget
agree translucent --shading translucent --pack budget
agree translucent_counted --shading translucent --pack counted
agree translucent_auto --shading translucent
# Packs filled front to back across the screen (view/stream/schedule.h): the
# same image from a different pack order.
agree wave --schedule wave --pack budget
# The counted capture (view/render/capture/capture_counted.h): no layer limit, packs cut
# by bytes only, halved where they exceed the fragment budget; the K-slot
# packs are the two rules above and below. The default (auto) takes
# first-K packs or counted ones by the frame before (view/stream/streamer.h).
agree counted --pack counted
agree counted_split --pack counted --store-budget 64K
agree auto
# The first-K capture (view/render/capture/capture_firstk.h): the counted packs, drawn
# once into K slots a pixel, again only for the pixels that got more; with
# a 64K slot budget its packs are too wide for 2 slots a pixel and are
# captured counted instead.
agree firstk --pack first-k
agree firstk_translucent --pack first-k --shading translucent
agree firstk_counted --pack first-k --slot-budget 64K
if [ "$MODE" = grid ]; then
    # Converted models have ~10^4 parts, so the other rules run on the
    # small file only, where they are cheap.
    agree disjoint --pack disjoint
    agree wave_counted --schedule wave --pack counted
    agree ring --upload-budget 64K --cache-budget off
    # K = 2: many pixels overflow the slots and take the second pass.
    agree firstk_k2 --pack first-k --max-layers 2
    # K = 2 turns every part into a wide part (layer bound > K): captured
    # with more slots per pixel over smaller tiles, still exact.
    agree wide --max-layers 2 --pack disjoint
    # A slot budget of 64K (512 pixels of K = 8 slots) at 128x128 captures
    # every pack in many screen tiles, the output in the idle slots.
    agree tiled --slot-budget 64K --pack disjoint
    agree tiled_wide --slot-budget 64K --max-layers 2 --pack disjoint
    residency
    # GPU memory at 1024x1024 outside the three budgets stays below 64 MB
    # (per-pixel counts and state), whatever the model (issue 6), with both
    # captures: the counted and first-K fragment stores are the store
    # budget.
    for pk in counted disjoint first-k; do
        "$S" "$P" --size 1024x1024 --upload-budget 1M --slot-budget 8M --store-budget 8M \
            --cache-budget 1M \
            --pack $pk --out "$T/big.png" --stats "$T/big.json" --quiet ||
            fail "1024x1024 --pack $pk: stream exited $?"
        g=$(json_num gpu_bytes_peak < "$T/big.json")
        echo "1024x1024 --pack $pk, upload budget 1M, slot and store budgets 8M, cache budget 1M: GPU peak $g bytes"
        [ -n "$g" ] && [ "$g" -le $((64000000 + 10 * 1048576)) ] ||
            fail "1024x1024 --pack $pk: GPU peak $g bytes, more than 64 MB beyond the budgets"
    done
fi

# An eye inside the model: boxes crossing the near plane cover the screen.
C=$("$OIT_BIN/oitprep" info "$P" --json 2>/dev/null | tr -d '\n ')
VIEW=$(awk -v s="$("$S" "$P" --size 8x8 --stats "$T/v.json" --quiet >/dev/null && sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$T/v.json")" \
    'BEGIN{split(s, v, ","); ex=v[4]+0.15*(v[1]-v[4]); ey=v[5]+0.15*(v[2]-v[5]); ez=v[6]+0.15*(v[3]-v[6]);
     printf "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,0,1,0,60", ex, ey, ez, v[4]-(v[1]-v[4]), v[5], v[6]-(v[3]-v[6])}')
"$S" "$P" --size 128x128 --view "$VIEW" --out "$T/in_s.png" --stats "$T/in_s.json" --quiet ||
    fail "inside: stream exited $?"
"$S" "$P" --method dfb --size 128x128 --view "$VIEW" --out "$T/in_d.png" --quiet ||
    fail "inside: dfb exited $?"
compare "inside ($VIEW): stream vs dfb" "$T/in_s.png" "$T/in_d.png" 0.1
check_stats inside "$T/in_s.json"


# The counted capture splits a pack only when its fragments need more store
# than the budget: the demo's one pack with a budget of exactly its store
# stays one batch, at 3/4 of it is split (drawn again in halves), and
# equals DFB either way.
if [ "$MODE" = demo ]; then
    V="--size 192x192 --azimuth 30 --elevation 35 --pack counted --quiet"
    # shellcheck disable=SC2086
    "$S" "$P" $V --stats "$T/cb.json" --out "$T/cb.png" || fail "counted budget: exited $?"
    F=$(json_num fragments < "$T/cb.json") packs=$(json_num packs < "$T/cb.json")
    # The ring is never larger than the file's parts (4.6 MiB expanded), nor
    # the cache: the whole stream of this 192x192 frame fits in 16 MiB.
    g=$(json_num gpu_bytes_peak < "$T/cb.json")
    echo "demo at 192x192: $g GPU bytes at peak (ring, cache and capture)"
    [ "$g" -lt 16777216 ] || fail "demo: $g GPU bytes at peak, a 64 MiB ring for a 4.6 MiB file?"
    [ "$packs" = 1 ] || fail "counted budget: the demo took $packs packs, the check wants 1"
    for k in roomy tight; do
        case $k in roomy) b=$((F * 16)) ;; tight) b=$((F * 12)) ;; esac
        [ "$b" -ge 65536 ] || fail "counted budget: $F fragments are too few for the check"
        # shellcheck disable=SC2086
        "$S" "$P" $V --store-budget "$b" --stats "$T/cb_$k.json" --out "$T/cb_$k.png" ||
            fail "counted budget $k: exited $?"
        nb=$(json_num batches < "$T/cb_$k.json")
        echo "counted budget: $F fragments, store budget $b bytes ($k): $nb batches"
        case $k in
        roomy) [ "$nb" = 1 ] || fail "counted budget: $nb batches where the store fits" ;;
        tight) [ "$nb" -gt 1 ] || fail "counted budget: 1 batch over twice the budget" ;;
        esac
        compare "counted budget $k: stream vs dfb" "$T/cb_$k.png" "$T/cb.png" 0.1
    done
fi

finish "streamer $MODE"
