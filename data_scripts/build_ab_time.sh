#!/bin/sh
# Two builds' frame times on the same models, interleaved (old, new, old,
# new, ...) so that a busy machine slows both alike: DFB on the source mesh
# and the stream on its part file (converted once, by the new build), an
# orbit of AB_VIEWS views a run, the first frame dropped (shader compiles),
# the median of the rest taken per run and the median of AB_REPS runs
# printed per build, with new/old. For refactors that must not cost time;
# pair it with build_identity.sh, which checks the images.
#
# Usage: data_scripts/build_ab_time.sh OLD_BIN NEW_BIN [MODEL...]
# MODEL: a path, or a name in data_scripts/cache; default: the demo scene, a
# 1M plant and 2CylinderEngine.glb. Knobs: AB_REPS (5), AB_VIEWS (6),
# AB_SIZE (1024x1024).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/models.sh"
two_builds "$1" "$2"
shift 2
reps=${AB_REPS:-5} views=${AB_VIEWS:-6} size=${AB_SIZE:-1024x1024}
if [ $# = 0 ]; then
    set -- $(generated_paths "$new" "$work" 1000000) "$here/cache/2CylinderEngine.glb"
fi

median() { sort -n | awk '{a[NR] = $1} END {if (NR) print a[int((NR + 1) / 2)]}'; }

# frame_ms BIN MODEL METHOD: the median warm frame of one orbit, ms.
frame_ms() {
    "$1/oitstream" "$2" --method "$3" --orbit "$views" --size "$size" 2>&1 |
        sed -n 's/^frame \([0-9]*\): [a-z0-9]* [0-9x]* \([0-9.]*\) ms.*/\1 \2/p' |
        awk '$1 > 0 {print $2}' | median
}

echo "| model | method | old ms | new ms | new / old |"
echo "|---|---|---|---|---|"
for m in "$@"; do
    [ -f "$m" ] || m=$here/cache/$m
    name=$(basename "$m")
    "$new/oitprep" "$m" -o "$work/m.oitp" >/dev/null
    for case in "dfb $m" "stream $work/m.oitp"; do
        set -- $case
        : > "$work/old" && : > "$work/new"
        i=0
        while [ $i -lt "$reps" ]; do
            frame_ms "$old" "$2" "$1" >> "$work/old"
            frame_ms "$new" "$2" "$1" >> "$work/new"
            i=$((i + 1))
        done
        o=$(median < "$work/old") n=$(median < "$work/new")
        [ -n "$o" ] && [ -n "$n" ] || { echo "build_ab_time: $name $1: no frame times" >&2; exit 1; }
        echo "| $name | $1 | $o | $n | $(awk -v a="$o" -v b="$n" 'BEGIN {printf "%.2f", b / a}') |"
    done
done
