#!/bin/sh
# Part file bytes against the source's binary PLY bytes (the issue's goal:
# a part file no larger than the model it came from), for every fetched
# model, the demo scene and generated plants, with the default scheme and
# with --scheme guaranteed for reference. Appends a markdown table to OUT.
#
# Usage: data_scripts/part_bytes.sh [BINDIR] [OUT.md] [PLANT_SIZES]
#   PLANT_SIZES: `oitgen plant --triangles N` scenes (default
#   "100000 1000000 12000000"); the 12M plant takes about a minute and 3 GB.
# PLY bytes are computed, not written: a binary little-endian PLY with float
# x y z (and uchar rgba when the source has colour), a uchar count and three
# int indices a face, from oit_meshinfo's vertex and triangle counts (for
# STL, a soup, that is three vertices a triangle, as its reader delivers).
# oitgen's scenes are that PLY already, so theirs is the file's size.
# `oitgen instances --count 1` is no substitute: it adds a colour per copy.
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin} out=${2:-bench/part-bytes-$(hostname).md}
plants=${3:-100000 1000000 12000000}
cache=${OIT_MESH_CACHE:-data_scripts/cache}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT

models="$(fetched_paths "$cache")"
models="$models$(generated_paths "$bin" "$work" $plants)"

info() { sed -n "s/^$1 \(.*\)/\1/p" "$2" | head -n 1; }
jfield() { sed -n "s/.*\"$1\": *\([0-9]*\).*/\1/p" "$2" | head -n 1; }

# The binary PLY of the counts in $1 (oit_meshinfo output).
ply_bytes() {
    v=$(info vertices "$1") t=$(info triangles "$1")
    colour=$(info attributes "$1" | grep -c color || true)
    hdr="ply
format binary_little_endian 1.0
element vertex $v
property float x
property float y
property float z
"
    stride=12
    if [ "$colour" -gt 0 ]; then
        hdr="${hdr}property uchar red
property uchar green
property uchar blue
property uchar alpha
"
        stride=16
    fi
    hdr="${hdr}element face $t
property list uchar int vertex_indices
end_header
"
    echo $(( $(printf '%s' "$hdr" | wc -c) + v * stride + t * 13 ))
}

# Bytes of the part file oitprep writes for $1 with options $2...; "?" when
# it refuses.
part_bytes() {
    m=$1 && shift
    if "$bin/oitprep" "$m" -o "$work/p.oitp" "$@" >/dev/null 2>"$work/err.txt"; then
        "$bin/oitprep" info "$work/p.oitp" --json > "$work/i.json"
        echo "$(jfield bytes "$work/i.json") $(jfield triangles "$work/i.json")"
    else
        echo "? ?"
    fi
    rm -f "$work/p.oitp"
}

ratio() { [ "$1" = "?" ] && echo "?" || awk "BEGIN{printf \"%.2f\", $1/$2}"; }

mkdir -p "$(dirname "$out")"
{
    echo
    echo "## Part file bytes against binary PLY bytes ($(date -u +%Y-%m-%d), commit $(git rev-parse --short HEAD 2>/dev/null || echo '?'))"
    echo
    printf 'Command: `data_scripts/part_bytes.sh %s %s "%s"`\n' "$bin" "$out" "$plants"
    echo
    echo "PLY: the source as binary little-endian PLY (computed from oit_meshinfo"
    echo "counts; oitgen scenes: the file). fast: default scheme; guaranteed:"
    echo '`--scheme guaranteed`. tris: triangles stored (after clipping).'
    echo
    echo "| model | vertices | triangles | PLY bytes | fast bytes | fast tris | fast / PLY | guaranteed bytes | guaranteed tris | guaranteed / PLY |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
} >> "$out"
for m in $models; do
    name=$(basename "$m")
    echo "$name ..." >&2
    "$bin/oit_meshinfo" "$m" > "$work/m.txt"
    case "$m" in
        "$work"/*) ply=$(wc -c < "$m") ;;
        *) ply=$(ply_bytes "$work/m.txt") ;;
    esac
    set -- $(part_bytes "$m")
    fb=$1 ft=$2
    set -- $(part_bytes "$m" --scheme guaranteed)
    gb=$1 gt=$2
    echo "| $name | $(info vertices "$work/m.txt") | $(info triangles "$work/m.txt") | $ply |" \
        "$fb | $ft | $(ratio "$fb" "$ply") | $gb | $gt | $(ratio "$gb" "$ply") |" >> "$out"
done
