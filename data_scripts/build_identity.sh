#!/bin/sh
# Two builds that should behave the same (before and after a refactor):
# each model converted by both builds' oitprep with both schemes and the
# part files compared byte for byte; then every in-core method, in both
# shadings, and the stream with each exact packing, rendered by both builds'
# oitstream into float PFMs and compared byte for byte (cmp). Prints a line
# a difference and the totals; any difference, or a run that fails in one
# build only, fails the script.
#
# Usage: data_scripts/build_identity.sh OLD_BIN NEW_BIN [MODEL...]
# MODEL: a path, or a name in data_scripts/cache; default: the demo scene, a
# 100K plant and the fetched models of models.sh that the cache holds.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/models.sh"
two_builds "$1" "$2"
shift 2
if [ $# = 0 ]; then
    set -- $(generated_paths "$new" "$work" 100000) $(fetched_paths "$here/cache")
fi
methods="dfb reference array compute unsorted wboit pll dp ppll4 b3d ddp guarded f2b"
size=192x160
same=0 differ=0 refused=0

# both WHAT EXT TOOL ARGS...: TOOL of each build with ARGS and then its own
# output path ($work/old.EXT, $work/new.EXT); the outputs compared byte for
# byte when both succeed.
both() {
    what=$1 ext=$2 tool=$3 && shift 3
    rm -f "$work/old.$ext" "$work/new.$ext"
    ro=0 rn=0
    "$old/$tool" "$@" "$work/old.$ext" >/dev/null 2>"$work/old.err" || ro=$?
    "$new/$tool" "$@" "$work/new.$ext" >/dev/null 2>"$work/new.err" || rn=$?
    if [ $ro != $rn ]; then
        echo "DIFFER: $what: exit $ro (old) against $rn (new): $(head -c 200 "$work/new.err")"
        differ=$((differ + 1))
    elif [ $ro != 0 ]; then
        refused=$((refused + 1)) # both refuse (e.g. ddp translucent): the same answer
    elif cmp -s "$work/old.$ext" "$work/new.$ext"; then
        same=$((same + 1))
    else
        echo "DIFFER: $what"
        differ=$((differ + 1))
    fi
}

for m in "$@"; do
    [ -f "$m" ] || m=$here/cache/$m
    name=$(basename "$m")
    rm -f "$work/parts.oitp"
    for scheme in fast guaranteed; do
        both "$name $scheme part file" oitp oitprep "$m" --scheme "$scheme" -o
        if [ $scheme = fast ] && [ -f "$work/new.oitp" ]; then
            mv "$work/new.oitp" "$work/parts.oitp"
        fi
    done
    for meth in $methods; do
        for sh in transparent translucent; do
            both "$name $meth $sh" pfm oitstream "$m" --method "$meth" --size $size \
                --shading "$sh" --out
        done
    done
    [ -f "$work/parts.oitp" ] || continue
    for pack in auto counted first-k; do
        for sh in transparent translucent; do
            both "$name stream $pack $sh" pfm oitstream "$work/parts.oitp" --method stream \
                --pack "$pack" --size $size --shading "$sh" --out
        done
    done
done
echo "identical: $same; different: $differ; refused by both builds: $refused"
[ $differ = 0 ]
