#!/bin/sh
# Memory of the stream against the scene (bench/memory-llvmpipe.md):
#  1. GPU peak (the stats' gpu_bytes_peak) of one 256x256 frame of every
#     fetched mesh and `oitgen demo`, converted by oitprep, in the automatic
#     pack mode, counted, first-k, disjoint and with --epsilon 0.01;
#  2. host peak RSS (/usr/bin/time %M) and GPU peak of the stream on the
#     plant's part file against DFB on its source mesh, at 1024x1024: one
#     frame, and an orbit of MEM_ORBIT views.
# Markdown tables on stdout.
#
#   data_scripts/memory.sh [BIN]          BIN default build/bin
#   MEM_PLANTS="2000000 1000000 100000"   plant sizes (default 2000000)
#   MEM_ORBIT=8   MEM_SIZE=256x256   MEM_BIG_SIZE=1024x1024
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/bin}
cache=${OIT_MESH_CACHE:-$here/cache}
plants=${MEM_PLANTS:-2000000}
orbit=${MEM_ORBIT:-8}
size=${MEM_SIZE:-256x256}
big=${MEM_BIG_SIZE:-1024x1024}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
for t in oitgen oitprep oitstream; do
    [ -x "$bin/$t" ] || { echo "memory.sh: $bin/$t: missing (nice make build)" >&2; exit 1; }
done
[ -x /usr/bin/time ] || { echo "memory.sh: /usr/bin/time missing (apt-get install time)" >&2; exit 1; }
work=$(mktemp -d /tmp/memory.XXXXXX)
trap 'rm -rf "$work"' EXIT
peak() { sed -n 's/.*"gpu_bytes_peak": \([0-9]*\).*/\1/p' "$1" | sort -n | tail -n 1; }
mb() { awk -v b="$1" 'BEGIN { printf "%.1f", b / 1e6 }'; }

echo "## GPU peak of one $size frame (MB, gpu_bytes_peak)"
echo
echo "| model | triangles | auto | counted | first-k | disjoint | epsilon 0.01 |"
echo "|---|---:|---:|---:|---:|---:|---:|"
"$bin/oitgen" demo -o "$work/demo.ply" >/dev/null || exit 1
for m in "$work/demo.ply" "$cache"/*; do
    case $m in *.off|*.stl|*.obj|*.ply|*.glb|*.gltf) ;; *) continue ;; esac
    name=$(basename "$m")
    p="$work/model.oitp"
    "$bin/oitprep" "$m" -o "$p" >"$work/prep.txt" 2>&1 ||
        { echo "| $name | oitprep failed: $(tail -n 1 "$work/prep.txt") |"; continue; }
    tris=$(sed -n 's/.* \([0-9]*\) out (.*/\1/p' "$work/prep.txt" | head -n 1)
    row="| $name | $tris |"
    for opts in "" "--pack counted" "--pack first-k" "--pack disjoint" "--epsilon 0.01"; do
        # shellcheck disable=SC2086
        if "$bin/oitstream" "$p" --size "$size" --stats "$work/s.json" --out "$work/o.png" \
            --quiet $opts; then
            row="$row $(mb "$(peak "$work/s.json")") |"
        else
            row="$row failed |"
        fi
    done
    echo "$row"
done

echo
echo "## Host peak RSS and GPU peak at $big: stream (part file) vs DFB (source mesh)"
echo
echo "| plant triangles | views | DFB RSS MB | stream RSS MB | DFB GPU MB | stream GPU MB |"
echo "|---:|---|---:|---:|---:|---:|"
for n in $plants; do
    "$bin/oitgen" plant --triangles "$n" -o "$work/plant.ply" >/dev/null || exit 1
    "$bin/oitprep" "$work/plant.ply" -o "$work/plant.oitp" >/dev/null 2>&1 || exit 1
    for views in 1 "$orbit"; do
        ov=""
        [ "$views" = 1 ] || ov="--orbit $views"
        row="| $n | $views |"
        rss=""
        for f in plant.ply plant.oitp; do
            # shellcheck disable=SC2086
            /usr/bin/time -f '%M' -o "$work/time.txt" "$bin/oitstream" "$work/$f" --size "$big" \
                --out "$work/o.png" --stats "$work/$f.json" --quiet $ov ||
                { echo "memory.sh: oitstream $f failed" >&2; continue; }
            rss="$rss $(awk '{ printf "%.0f", $1 / 1000 }' "$work/time.txt" | tail -n 1)"
        done
        set -- $rss
        row="$row ${1:-?} | ${2:-?} | $(mb "$(peak "$work/plant.ply.json")") | $(mb "$(peak "$work/plant.oitp.json")") |"
        echo "$row"
    done
done
