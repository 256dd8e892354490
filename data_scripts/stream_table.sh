#!/bin/sh
# The streamed renderer against DFB on every fetched model and on generated
# scenes, in the same run: ms per frame, packs, bytes uploaded, cache hits,
# GPU bytes at peak, and the image difference (issue 6's closing figures),
# written as a markdown table. Each model is converted with oitprep first;
# a model oitprep refuses is listed with its message.
#
# Usage: data_scripts/stream_table.sh [BINDIR] [OUT.md] [WxH] [VIEWS] [PLANTS]
#   VIEWS: orbit views (default 4); frame 0 of each method is a warm-up and
#   left out of the medians (it compiles shaders and fills the cache).
#   PLANTS: triangle counts of `oitgen plant` scenes (default "100000 1000000").
# Needs data_scripts/fetch_meshes.sh to have run (missing models are skipped).
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin} out=${2:-bench/stream-$(hostname).md} size=${3:-1024x1024}
views=${4:-4} plants=${5:-100000 1000000}
cache=${OIT_MESH_CACHE:-data_scripts/cache}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}

models="$(generated_paths "$bin" "$work" $plants)"
models="$models$(fetched_paths "$cache")"

# every value of a key in a stats file, frames 1.. (frame 0 left out)
after_first() { grep -o "\"$1\": [0-9.e+-]*" "$2" | sed 's/.*: //' | tail -n +2; }
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print v[int((NR + 1) / 2)]; else print "-" }'; }
most() { sort -g | tail -n 1; }

mkdir -p "$(dirname "$out")"
{
    echo "# Streamed rendering against DFB"
    echo
    echo "Machine: $(uname -m) ($(sed -n 's/^model name[^:]*: *//p' /proc/cpuinfo | head -n 1)), $(nproc) cores, $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo); $(date -u +%Y-%m-%d)."
    echo "Command: \`data_scripts/stream_table.sh $bin $out $size $views \"$plants\"\`"
    echo
    echo "Both methods render the same part file on the same $views orbit views at"
    echo "$size; ms are medians over views 1..$((views - 1)) (view 0 warms up: shader"
    echo "compilation, first uploads). stream: default options (counted packs,"
    echo "upload ring 64M, residency cache 256M, slot budget 32M). uploaded: bytes"
    echo "per frame after view 0 (the cache holds what earlier views uploaded)."
    echo "diff: share of pixels where stream and DFB differ by more than 1/255,"
    echo "worst view. GPU MB: at peak as each method reports it, all it holds: the"
    echo "stream's ring, cache, capture and per-pixel state, DFB's fragment buffers and"
    echo "the whole model, whose part is 'of it model MB' (gpu_mesh_bytes)."
    echo
    echo "| model | triangles (file) | parts | stream ms | DFB ms | packs | uploaded MB | cache hits | stream GPU MB | DFB GPU MB | of it model MB | diff |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$out"

for m in $models; do
    name=$(basename "$m")
    echo "$name ..." >&2
    if ! "$bin/oitprep" "$m" -o "$work/m.oitp" --stats "$work/prep.json" 2>"$work/prep.err" >/dev/null; then
        echo "| $name | refused by oitprep: $(tail -n 1 "$work/prep.err" | tr '|' '/') ||||||||||| " >>"$out"
        continue
    fi
    for meth in stream dfb; do
        "$bin/oitstream" "$work/m.oitp" --method $meth --size "$size" --orbit "$views" \
            --out "$work/$meth.png" --stats "$work/$meth.json" --quiet
    done
    worst=0
    i=0
    while [ $i -lt "$views" ]; do
        f=$(printf '%03d' $i)
        p=$("$bin/oitstream" --compare "$work/stream_$f.png" "$work/dfb_$f.png" --json |
            sed -n 's/.*"pct_over_1_255": *\([0-9.e+-]*\).*/\1/p')
        worst=$(awk -v a="$worst" -v b="$p" 'BEGIN { print (b > a ? b : a) }')
        i=$((i + 1))
    done
    tris=$(sed -n 's/.*"triangles_out": *\([0-9]*\).*/\1/p' "$work/prep.json")
    parts=$(sed -n 's/.*"parts": *\([0-9]*\).*/\1/p' "$work/prep.json")
    dfb_gpu=$(after_first gpu_bytes_peak "$work/dfb.json" | most | awk '{ print $1 / 1048576 }')
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %.1f | %.1f | %.1f | %s%% |\n' "$name" "$tris" "$parts" \
        "$(after_first ms "$work/stream.json" | median)" "$(after_first ms "$work/dfb.json" | median)" \
        "$(after_first packs "$work/stream.json" | median)" \
        "$(after_first bytes_uploaded "$work/stream.json" | median | awk '{ printf "%.1f", $1 / 1e6 }')" \
        "$(after_first cache_hits "$work/stream.json" | median)" \
        "$(after_first gpu_bytes_peak "$work/stream.json" | most | awk '{ print $1 / 1048576 }')" \
        "$dfb_gpu" "$(after_first gpu_mesh_bytes "$work/dfb.json" | most | awk '{ print $1 / 1048576 }')" \
        "$worst" >>"$out"
done
echo "wrote $out" >&2
