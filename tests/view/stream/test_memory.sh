#!/bin/sh
# GPU memory of the stream sized to the scene (bench/memory-llvmpipe.md): a
# 256x256 frame of a small model (`oitgen demo`, 100K triangles, and
# $OIT_MESH_CACHE/bunny00.off when fetched, each one part) takes at most
# 16 MB by the stats' gpu_bytes_peak (ring, cache, capture and the rest the
# stream allocates) in every pack mode and with early termination, and its
# image is bit for bit DFB's on the same file. Fails when an allocation
# starts at its budget again (the 64 MiB ring, the cache beside a ring that
# holds the whole file, K slots for every pixel of the frame).
# Usage: test_memory.sh
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
S="$OIT_BIN/oitstream"
scratch memory
LIMIT=16000000
need_tools "$OIT_BIN/oitgen" "$OIT_BIN/oitprep" "$S"

"$OIT_BIN/oitgen" demo -o "$T/demo.ply" >/dev/null || die "oitgen demo"
models="demo.ply"
have_mesh bunny00.off && models="$models $MESH"
for m in $models; do
    case $m in /*) src=$m ;; *) src=$T/$m ;; esac
    name=$(basename "$m" | sed 's/\..*//')
    P="$T/$name.oitp"
    "$OIT_BIN/oitprep" "$src" -o "$P" >"$T/$name.prep.txt" 2>&1 ||
        { fail "$name: oitprep: $(tail -n 1 "$T/$name.prep.txt")"; continue; }
    "$S" "$P" --method dfb --size 256x256 --out "$T/${name}_dfb.png" --quiet ||
        { fail "$name: dfb exited $?"; continue; }
    for mode in auto counted first-k disjoint epsilon; do
        case $mode in
        auto) opts="" ;;
        epsilon) opts="--epsilon 0.01" ;;
        *) opts="--pack $mode" ;;
        esac
        out="$T/${name}_$mode"
        # shellcheck disable=SC2086
        "$S" "$P" --size 256x256 --stats "$out.json" --out "$out.png" --quiet $opts ||
            { fail "$name $mode: stream exited $?"; continue; }
        peak=$(json_num gpu_bytes_peak <"$out.json")
        echo "$name $mode: gpu_bytes_peak $peak"
        [ -n "$peak" ] && [ "$peak" -gt 0 ] && [ "$peak" -le $LIMIT ] ||
            fail "$name $mode: gpu_bytes_peak ${peak:-missing} over $LIMIT"
        # epsilon > 0 drops what lies behind saturated pixels: not DFB's image
        [ "$mode" = epsilon ] && continue
        expect_equal "$name $mode vs dfb" "$out.png" "$T/${name}_dfb.png"
    done
done
finish "memory (limit $LIMIT bytes)"
