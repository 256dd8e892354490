#!/bin/sh
# Large frames through oitstream: 2048x2048 (2^22 pixels, where a dispatch
# over the pixels in groups of 64 passes the 65535 groups GL promises) and
# 4096x2160 (past one 128 MiB storage binding for DFB's output and the
# capture's state: drawn in bands of rows) of a small scene (hard case
# rings, a few hundred triangles): the stream of its part file and the
# in-core exact methods against DFB of the source mesh, at most 0.01% of
# pixels over 1/255, and their figures (fragments, layers) as DFB's. The
# 8192x8192 frames and the fetched meshes are data_scripts/sizes.sh's (too
# slow for the suite on llvmpipe).
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
need_every_tool
scratch oitstream_sizes
gen_hard rings "$T/rings.ply"
prep_or_die "$T/rings.ply" "$T/rings.oitp"

# render NAME INPUT SIZE OPTION...: $T/NAME.png and its stats $T/NAME.json
render() {
    _name=$1 _in=$2 _size=$3
    shift 3
    "$S" "$_in" --size "$_size" --quiet --out "$T/$_name.png" --stats "$T/$_name.json" "$@" \
        >"$T/$_name.txt" 2>&1 || fail "$_name: $(tail -n 1 "$T/$_name.txt")"
}

# same_figures NAME: NAME's fragments and layers are DFB's (dfb-SIZE)
same_figures() {
    _f=$(json_num fragments "$T/$1.json") _ref=$(json_num fragments "$T/dfb-$2.json")
    # a pixel centre on an edge may go either way between band and frame
    _lo=$(( _ref - _ref / 10000 )) _hi=$(( _ref + _ref / 10000 ))
    [ -n "$_f" ] && [ "$_f" -ge "$_lo" ] && [ "$_f" -le "$_hi" ] ||
        fail "$1: ${_f:-no} fragments, DFB $_ref"
    [ "$(json_num max_layers "$T/$1.json")" = "$(json_num max_layers "$T/dfb-$2.json")" ] ||
        fail "$1: $(json_num max_layers "$T/$1.json") layers, DFB $(json_num max_layers "$T/dfb-$2.json")"
}

for size in 2048x2048 4096x2160; do
    render "dfb-$size" "$T/rings.ply" "$size"
    render "stream-$size" "$T/rings.oitp" "$size"
    compare "stream $size" "$T/dfb-$size.png" "$T/stream-$size.png" 0.01
    same_figures "stream-$size" "$size"
done
# The K-slot array capture in core; the stream's counted packs translucent
# (48 bytes a pixel of state). Every exact method in bands: tests/view/render's
# test_bands.c; all of them at 8192x8192: data_scripts/sizes.sh.
render array-2048x2048 "$T/rings.ply" 2048x2048 --method array
compare "array 2048x2048" "$T/dfb-2048x2048.png" "$T/array-2048x2048.png" 0.01
same_figures array-2048x2048 2048x2048
render dfb-tl "$T/rings.ply" 4096x2160 --shading translucent
render stream-tl "$T/rings.oitp" 4096x2160 --shading translucent --pack counted
compare "stream translucent 4096x2160" "$T/dfb-tl.png" "$T/stream-tl.png" 0.01
finish --clean oitstream_sizes
