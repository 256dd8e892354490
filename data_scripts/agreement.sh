#!/bin/sh
# DFB against the Embree reference on every fetched model and on generated
# scenes, both shading modes, several views: the figures behind "DFB agrees
# with the reference" (issue 5), written as a markdown table.
#
# Usage: data_scripts/agreement.sh [BINDIR] [OUT.md] [WxH]
# Needs data_scripts/fetch_meshes.sh to have run (missing models are skipped).
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin} out=${2:-bench/agreement-$(hostname).md} size=${3:-256x256}
cache=${OIT_MESH_CACHE:-data_scripts/cache}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}

"$bin/oitgen" demo -o "$work/demo.ply" >/dev/null
"$bin/oitgen" plant --triangles 100000 -o "$work/plant100k.ply" >/dev/null
models="$work/demo.ply $work/plant100k.ply"
models="$models$(fetched_paths "$cache" $OIT_FETCHED_DRACO)"

field() { sed -n "s/.*\"$1\": *\([-0-9.eEinfa]*\).*/\1/p" "$2" | head -n 1; }

mkdir -p "$(dirname "$out")"
{
    echo "# DFB vs Embree reference"
    echo
    echo "Machine: $(uname -m), $(nproc) cores; GL: llvmpipe unless stated. Size $size."
    echo "Command: \`data_scripts/agreement.sh $bin $out $size\`"
    echo
    echo "\"off\" = % of pixels with a channel off by more than 1/255; \"off outside mask\" ="
    echo "the same over pixels the reference does not flag as ambiguous (pixel centre"
    echo "within 1/64 px of an edge, or hits tied in depth)."
    echo
    echo "| model | shading | azimuth | max layers | rmse | max abs | off % | masked px | off outside mask % |"
    echo "|---|---|---|---|---|---|---|---|---|"
} > "$out"
for m in $models; do
    name=$(basename "$m")
    for shading in transparent translucent; do
        for az in 0 120 240; do
            base="$work/f"
            "$bin/oitstream" "$m" --method dfb --size "$size" --azimuth "$az" \
                --shading "$shading" --out "$base-dfb.pfm" --stats "$base-dfb.json" --quiet
            "$bin/oitstream" "$m" --method reference --size "$size" --azimuth "$az" \
                --shading "$shading" --out "$base-ref.pfm" --ambiguity "$base-mask.png" --quiet
            "$bin/oitstream" --compare "$base-dfb.pfm" "$base-ref.pfm" --mask "$base-mask.png" \
                --json > "$base-cmp.json"
            printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$shading" "$az" \
                "$(field max_layers "$base-dfb.json")" "$(field rmse "$base-cmp.json")" \
                "$(field max_abs "$base-cmp.json")" "$(field pct_over_1_255 "$base-cmp.json")" \
                "$(field masked_pixels "$base-cmp.json")" \
                "$(field pct_over_1_255_outside_mask "$base-cmp.json")" >> "$out"
        done
    done
    echo "agreement: $name done" >&2
done
echo "agreement: wrote $out" >&2
