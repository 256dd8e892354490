#!/bin/sh
# The part codecs of version 5 against alternatives (zlib, meshopt's
# triangle index codec) over part files: builds data_scripts/codec_compare.c
# against the Release build's liboit_formats.a and prints a markdown table a
# file.
# Usage: data_scripts/codec_compare.sh BUILD FILE.oitp...
set -eu
b=$1 && shift
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(mktemp) && trap 'rm -f "$exe"' EXIT
cc -std=c11 -O2 -I"$here/include" -I"$here" "$here/data_scripts/codec_compare.c" \
    "$b/formats/liboit_formats.a" -lmeshoptimizer -ldraco -lz -lstdc++ -lm -o "$exe"
for f in "$@"; do
    echo "$(basename "$f"):"
    echo
    "$exe" "$f"
    echo
done
