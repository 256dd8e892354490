#!/bin/sh
# Every frame size with every exact method (issue "Right on a real GPU",
# item 3): the demo (oitgen demo) and a fetched mesh (bunny00.off from
# data_scripts/cache, when there) at 2048x2048, 4096x2160 and 8192x8192,
# each through the stream of its part file (the default pack, counted,
# first-k) and in core through every other exact method (array, stencil
# where the driver routes per sample, pll, ppll4, b3d, dp, ddp), compared
# with DFB of the source mesh at the same size (oitstream --compare: the
# pixels more than 1/255 apart). Frames past one storage binding are drawn
# in bands of rows (view/render/gl/band.h); the frames of 2^22 pixels and more
# failed before (a dispatch of more work groups than GL promises).
#
# Usage: data_scripts/sizes.sh [BINDIR] [OUTDIR]
#   defaults: build/bin, bench; writes OUTDIR/sizes-TAG.md, TAG "llvmpipe"
#   or "nvidia" from the renderer DFB names, else the host's name.
# Knobs (environment):
#   SIZES="2048x2048 4096x2160"   these sizes instead
#   SIZES_MODELS="demo"           these models instead (demo, or a file name
#                                 in data_scripts/cache / OIT_MESH_CACHE)
#   SIZES_KEEP=DIR                keep the frames and stats in DIR
# Verdict per row: ok when at most 0.01% of the pixels are over 1/255 from
# DFB's, "differs" past that, "failed: MESSAGE" when the render fails,
# "not offered here: MESSAGE" for stencil on a driver that does not route
# per sample (llvmpipe). Exits 1 when any row is neither ok nor not offered.
# Duration on a loaded 2-core llvmpipe machine: about 11 minutes (the
# 8192x8192 frames: 67 M pixels, seconds to a minute each; dp and ddp peel
# the frame once a layer). Run it with nice.
set -eu
bin=${1:-build/bin} outdir=${2:-bench}
here=$(cd "$(dirname "$0")" && pwd)
cache=${OIT_MESH_CACHE:-$here/cache}
sizes=${SIZES:-2048x2048 4096x2160 8192x8192}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
S="$bin/oitstream"
for t in oitgen oitprep oitstream; do
    [ -x "$bin/$t" ] || { echo "sizes: $bin/$t: missing" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/sizes.XXXXXX")
trap 'rm -rf "$work"' EXIT
keep=${SIZES_KEEP:-}

num() { sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" "$2" | head -n 1; }

# models: "demo" and the fetched bunny, as NAME=PATH of the source mesh
models=""
for m in ${SIZES_MODELS:-demo bunny00.off}; do
    if [ "$m" = demo ]; then
        "$bin/oitgen" demo -o "$work/demo.ply" >/dev/null
        models="$models demo=$work/demo.ply"
    elif [ -f "$cache/$m" ]; then
        models="$models ${m%%.*}=$cache/$m"
    else
        echo "sizes: $cache/$m: not fetched (data_scripts/fetch_meshes.sh); left out" >&2
    fi
done

rows="$work/rows" bad=0 tag=""
: >"$rows"
# row MODEL METHOD SIZE NAME: renders NAME (its stats and log beside it)
# against dfb-SIZE of the model, one table row
row() {
    _model=$1 _method=$2 _size=$3 _f=$4
    if [ ! -f "$_f.png" ]; then
        _why=$(tail -n 1 "$_f.txt" | cut -c1-160)
        case $_method:$_why in
        stencil:*"self-test failed"* | stencil:*"multisample limit"*)
            echo "| $_model | $_method | $_size | - | - | - | not offered here: $_why |" >>"$rows" ;;
        *)
            echo "| $_model | $_method | $_size | - | - | - | failed: $_why |" >>"$rows"
            bad=1 ;;
        esac
        return
    fi
    "$S" --compare "$work/$_model-dfb-$_size.png" "$_f.png" --json >"$_f.cmp" ||
        { echo "| $_model | $_method | $_size | - | - | - | failed: compare |" >>"$rows"; bad=1; return; }
    _over=$(num pixels_over "$_f.cmp") _pct=$(num pct_over_1_255 "$_f.cmp")
    _ms=$(num ms "$_f.json") _frags=$(num fragments "$_f.json")
    if awk "BEGIN { exit !($_pct <= 0.01) }"; then _verdict=ok; else _verdict=differs; bad=1; fi
    printf '| %s | %s | %s | %.0f | %s | %s (%.5f%%) | %s |\n' "$_model" "$_method" "$_size" \
        "$_ms" "$_frags" "$_over" "$_pct" "$_verdict" >>"$rows"
}

# render MODEL SIZE NAME INPUT OPTION...: $work/MODEL-NAME-SIZE.{png,json,txt}
render() {
    _model=$1 _size=$2 _name=$3 _in=$4
    shift 4
    _f="$work/$_model-$_name-$_size"
    echo "sizes: $_model $_name $_size" >&2
    nice "$S" "$_in" --size "$_size" --quiet --out "$_f.png" --stats "$_f.json" "$@" \
        >"$_f.txt" 2>&1 || rm -f "$_f.png"
}

for entry in $models; do
    model=${entry%%=*} mesh=${entry#*=}
    nice "$bin/oitprep" "$mesh" -o "$work/$model.oitp" >"$work/$model.prep.txt" 2>&1 ||
        { echo "sizes: oitprep $mesh: $(tail -n 1 "$work/$model.prep.txt")" >&2; exit 1; }
    for size in $sizes; do
        render "$model" "$size" dfb "$mesh" --method dfb
        [ -f "$work/$model-dfb-$size.png" ] ||
            { echo "sizes: DFB $model $size: $(tail -n 1 "$work/$model-dfb-$size.txt")" >&2; exit 1; }
        if [ -z "$tag" ]; then
            case $(sed -n 's/.*"renderer": *"\([^"]*\)".*/\1/p' "$work/$model-dfb-$size.json") in
            *llvmpipe*) tag=llvmpipe ;;
            *NVIDIA*) tag=nvidia ;;
            *) tag=$(hostname) ;;
            esac
        fi
        printf '| %s | dfb | %s | %.0f | %s | reference | - |\n' "$model" "$size" \
            "$(num ms "$work/$model-dfb-$size.json")" \
            "$(num fragments "$work/$model-dfb-$size.json")" >>"$rows"
        for pack in auto counted first-k; do
            render "$model" "$size" "stream-$pack" "$work/$model.oitp" --pack "$pack"
            row "$model" "stream --pack $pack" "$size" "$work/$model-stream-$pack-$size"
        done
        for m in array stencil pll ppll4 b3d dp ddp; do
            render "$model" "$size" "$m" "$mesh" --method "$m"
            row "$model" "$m" "$size" "$work/$model-$m-$size"
        done
        if [ -n "$keep" ]; then
            mkdir -p "$keep" && cp "$work/$model"-*"-$size".* "$keep/"
        fi
        rm -f "$work/$model"-*"-$size".png
    done
done

out="$outdir/sizes-${tag:-unknown}.md"
mkdir -p "$outdir"
{
    echo "# Every frame size, every exact method ($tag)"
    echo
    echo "\`data_scripts/sizes.sh $bin $outdir\` on $(date -u +%Y-%m-%d): each frame"
    echo "against DFB of the source mesh at the same size (stream: its part file),"
    echo "the default view; ms is the frame's wall time (one frame: cold), fragments"
    echo "the frame's; \"over 1/255\" the pixels any channel of which is more than"
    echo "1/255 from DFB's. ok: at most 0.01%. Frames whose per-pixel state passes"
    echo "one storage binding (GL_MAX_SHADER_STORAGE_BLOCK_SIZE: 128 MiB on"
    echo "llvmpipe) are drawn in bands of rows, DFB's too."
    echo
    echo "| model | method | size | ms | fragments | over 1/255 | verdict |"
    echo "|---|---|---|---:|---:|---:|---|"
    cat "$rows"
} >"$out"
echo "sizes: wrote $out" >&2
exit $bad
