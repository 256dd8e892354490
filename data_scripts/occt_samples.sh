#!/bin/sh
# Rebuilds tests/corpus/step/{parts.step,parts.igs,box.step} with Open
# CASCADE's writers (data_scripts/occt_samples.cpp says what they hold).
# Needs libocct-data-exchange-dev and libocct-ocaf-dev (setup/debian-packages.txt).
# The files carry a timestamp in their header; their geometry and styles do not change.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/../tests/corpus/step}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
c++ -std=c++17 -O1 -I/usr/include/opencascade "$here/occt_samples.cpp" -o "$tmp/occt_samples" \
    -lTKXDESTEP -lTKXDEIGES -lTKSTEP -lTKIGES -lTKXSBase -lTKXCAF -lTKLCAF -lTKCAF -lTKCDF \
    -lTKPrim -lTKTopAlgo -lTKBRep -lTKGeomBase -lTKG3d -lTKMath -lTKernel
mkdir -p "$out"
"$tmp/occt_samples" "$out"
ls -l "$out"
