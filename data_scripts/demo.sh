#!/bin/sh
# Generates the built-in demo scene, renders it headless and prints where the
# image is. Usage: demo.sh BINDIR OUTDIR [WxH]
# Until the streaming path (issue 6) lands, the frame is rendered with DFB,
# the in-core exact method.
set -eu
bin=$1 out=$2 size=${3:-1024x1024}
mkdir -p "$out"
echo "demo: generating the demo scene -> $out/demo.ply"
"$bin/oitgen" demo -o "$out/demo.ply"
echo "demo: rendering $size with DFB (exact) -> $out/frame.png"
EGL_PLATFORM=${EGL_PLATFORM:-surfaceless} \
"$bin/oitstream" "$out/demo.ply" --method dfb --size "$size" \
    --out "$out/frame.png" --stats "$out/frame.json"
echo "demo: wrote $(pwd)/$out/frame.png (figures in $out/frame.json)"
