#!/bin/sh
# Issue 36 item 3: the guaranteed scheme (oitprep --scheme guaranteed, K 8)
# packed as Wang & Xie do, beside the fast scheme and DFB on the source
# mesh. Per model and view (an orbit of GP_VIEWS, elevation 20), one
# single-threaded run each (LP_NUM_THREADS=0: llvmpipe renders on the
# calling thread, so CPU seconds measure the work on a shared machine):
#   packs per frame, CPU seconds (user+sys of the whole run, start-up and
#   conversion excluded) and the share of pixels off by > 1/255 against DFB
#   on the source mesh, for: the fast scheme (default packs), the
#   guaranteed scheme with the default packs, --pack disjoint (the paper's
#   Fig. 6 rule, tree) and --pack disjoint --schedule wave (packs by level).
# Usage: data_scripts/guaranteed_packs.sh [BINDIR] [OUT.md] [WxH]
# GP_PLANT: the plant's triangles (0: none; default 1000000); GP_VIEWS (2).
set -eu
bin=${1:-build/bin} out=${2:-bench/guaranteed-packs-$(hostname).md} size=${3:-512x512}
views=${GP_VIEWS:-2} plant=${GP_PLANT:-1000000}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless} LP_NUM_THREADS=0
"$bin/oitgen" demo -o "$work/demo.ply" >/dev/null
models="$work/demo.ply"
if [ "$plant" != 0 ]; then
    "$bin/oitgen" plant --triangles "$plant" -o "$work/plant$plant.ply" >/dev/null
    models="$models $work/plant$plant.ply"
fi
cpu() { /usr/bin/time -f '%U %S' -o "$work/t" "$@" && awk '{ printf "%.2f", $1 + $2 }' "$work/t"; }
{
    echo "# Guaranteed-scheme packs (issue 36 item 3)"
    echo
    echo "Machine: $(uname -m), $(nproc) cores, shared; llvmpipe on one thread (LP_NUM_THREADS=0)."
    echo "Size $size; $views orbit views (elevation 20); CPU s = user+sys of one run over the views."
    echo "Command: \`data_scripts/guaranteed_packs.sh $bin $out $size\` (GP_VIEWS=$views, GP_PLANT=$plant)"
    echo
    echo "| model | file | packing | packs per frame | CPU s | worst % off DFB (mesh) |"
    echo "|---|---|---|---|---|---|"
} >"$out"
for m in $models; do
    name=$(basename "$m" .ply)
    "$bin/oitprep" "$m" -o "$work/g.oitp" --scheme guaranteed --max-layers 8 >/dev/null 2>&1
    "$bin/oitprep" "$m" -o "$work/f.oitp" >/dev/null 2>&1
    "$bin/oitstream" "$m" --method dfb --size "$size" --orbit "$views" --out "$work/dfb.png" --quiet
    for run in "f|default|" "g|default|" "g|disjoint (tree, Fig. 6)|--pack disjoint" \
               "g|disjoint by level (wave)|--pack disjoint --schedule wave"; do
        f=${run%%|*} rest=${run#*|} label=${rest%%|*} opts=${rest#*|}
        # shellcheck disable=SC2086
        s=$(cpu "$bin/oitstream" "$work/$f.oitp" --size "$size" --orbit "$views" $opts \
            --out "$work/o.png" --stats "$work/o.json" --quiet)
        packs=$(grep -o '"packs": [0-9]*' "$work/o.json" | sed 's/.*: //' | paste -sd/ -)
        off=0
        i=0
        while [ "$i" -lt "$views" ]; do
            k=$(printf %03d "$i")
            p=$("$bin/oitstream" --compare "$work/o_$k.png" "$work/dfb_$k.png" --json |
                sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
            off=$(awk -v a="$off" -v b="$p" 'BEGIN { print (b > a ? b : a) }')
            i=$((i + 1))
        done
        scheme=$([ "$f" = g ] && echo guaranteed || echo fast)
        echo "| $name | $scheme | $label | $packs | $s | $off |" | tee -a "$out" >&2
    done
done
