#!/bin/sh
# What a pick costs (oitstream MODEL --pick X,Y, the whole process as a
# user runs it): on the plant of TRIANGLES triangles (oitgen plant) at
# SIZE, PIXELS pixels of its default view across the frame, picked
#   part file  the walk over the part file, a part at a time (the stream's
#              input, out of core);
#   mesh       the walk over the source mesh loaded in core (dfb);
#   reference  Embree's own hits on the mesh loaded in core;
# methods interleaved per pixel, medians of the wall clock and the largest
# peak RSS (/usr/bin/time), and whether the three listed the same source
# triangles (they may differ on edge pixels only: the reference's
# ambiguity mask).
# Usage: pick_bench.sh BINDIR OUT.md   (env: TRIANGLES, default 1000000;
#        SIZE, default 1024x1024; PIXELS, default 9)
set -eu
bin=$1 out=$2
tris=${TRIANGLES:-1000000} size=${SIZE:-1024x1024} pixels=${PIXELS:-9}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
[ -x /usr/bin/time ] || { echo "pick_bench: needs /usr/bin/time" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/oitgen" plant --triangles "$tris" -o "$work/plant.ply" > /dev/null 2>&1
"$bin/oitprep" "$work/plant.ply" -o "$work/plant.oitp" > /dev/null 2>&1
w=${size%x*} h=${size#*x}

# pick KIND X,Y: appends "ms rss_kb" to $work/KIND and the sources to $work/KIND.src
pick() {
    case $1 in
    part) set -- "$1" "$2" "$work/plant.oitp" ;;
    mesh) set -- "$1" "$2" "$work/plant.ply" --method dfb ;;
    *) set -- "$1" "$2" "$work/plant.ply" --method reference ;;
    esac
    kind=$1 px=$2
    shift 2
    t0=$(date +%s%N)
    /usr/bin/time -f "%M" -o "$work/rss" "$bin/oitstream" "$@" --size "$size" --pick "$px" \
        > "$work/pick.json"
    t1=$(date +%s%N)
    echo "$(( (t1 - t0) / 1000000 )) $(cat "$work/rss")" >> "$work/$kind"
    grep -o '"source_triangle": [0-9]*' "$work/pick.json" | tr -d '\n' >> "$work/$kind.src"
    echo >> "$work/$kind.src"
    grep -o '"count": [0-9]*' "$work/pick.json" | sed 's/.*: //' >> "$work/$kind.count"
}

i=0
while [ "$i" -lt "$pixels" ]; do
    # across the frame, a little below its middle (the plant's floor is
    # there in the default view)
    x=$(( w * (i + 1) / (pixels + 1) )) y=$(( h * 11 / 20 ))
    for kind in part mesh reference; do pick "$kind" "$x,$y"; done
    i=$((i + 1))
done
median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2 ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2)}'; }
same_pm=$(cmp -s "$work/part.src" "$work/mesh.src" && echo yes || echo no)
same_mr=$(paste -d'|' "$work/mesh.src" "$work/reference.src" | awk -F'|' '$1 != $2' | wc -l)
deep=$(sort -n "$work/part.count" | tail -1)
{
    echo "# Pick cost: oitstream --pick on the ${tris}-triangle plant ($(date -u +%Y-%m-%d), $(nproc) cores)"
    echo
    echo "\`data_scripts/pick_bench.sh\` at $size, $pixels pixels of the default view"
    echo "(layers at each: $(tr '\n' ' ' < "$work/part.count")), each a whole process."
    echo
    echo "| picked through | wall ms (median) | slowest ms | peak RSS MB (largest) |"
    echo "|---|---|---|---|"
    for kind in part mesh reference; do
        ms=$(cut -d' ' -f1 "$work/$kind" | median)
        slow=$(cut -d' ' -f1 "$work/$kind" | sort -n | tail -1)
        rss=$(cut -d' ' -f2 "$work/$kind" | sort -n | tail -1)
        case $kind in
        part) what="the part file, walked a part at a time" ;;
        mesh) what="the mesh in core, walked (dfb)" ;;
        *) what="the mesh in core, Embree (reference)" ;;
        esac
        echo "| $what | $ms | $slow | $(awk -v k="$rss" 'BEGIN{printf "%.0f", k / 1024}') |"
    done
    echo
    echo "Same source triangles, part file and mesh: $same_pm; mesh and reference:"
    echo "$same_mr of $pixels pixels differ (an edge pixel may)."
} > "$out"
cat "$out"
