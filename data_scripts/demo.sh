#!/bin/sh
# The product end to end on the built-in demo scene: generate it, convert it
# into a part file (oitprep), check the file (oitprep verify), render it with
# the streaming renderer (oitstream, headless), render the same file and the
# source mesh with DFB, the in-core exact method (the mesh is what a user
# would render without converting), print how far the stream is from each,
# and draw the decomposition (oitprep parts, a hue per part).
# Usage: demo.sh BINDIR OUTDIR [WxH]
set -eu
bin=$1 out=$2 size=${3:-1024x1024}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
mkdir -p "$out"
echo "demo: generating the demo scene -> $out/demo.ply"
"$bin/oitgen" demo -o "$out/demo.ply"
echo "demo: converting -> $out/demo.oitp (figures in $out/prep.json)"
"$bin/oitprep" "$out/demo.ply" -o "$out/demo.oitp" --stats "$out/prep.json"
echo "demo: verifying the part file"
"$bin/oitprep" verify "$out/demo.oitp"
echo "demo: streaming $size -> $out/frame.png"
"$bin/oitstream" "$out/demo.oitp" --size "$size" --out "$out/frame.png" \
    --stats "$out/frame.json"
echo "demo: the same view with DFB -> $out/dfb.png"
"$bin/oitstream" "$out/demo.oitp" --method dfb --size "$size" --out "$out/dfb.png" \
    --stats "$out/dfb.json"
echo "demo: DFB on the source mesh -> $out/dfb_mesh.png"
"$bin/oitstream" "$out/demo.ply" --method dfb --size "$size" --out "$out/dfb_mesh.png" \
    --stats "$out/dfb_mesh.json" --quiet
echo "demo: stream against DFB: $("$bin/oitstream" --compare "$out/frame.png" "$out/dfb.png" --json)"
echo "demo: stream against DFB on the source mesh:" \
    "$("$bin/oitstream" --compare "$out/frame.png" "$out/dfb_mesh.png" --json)"
echo "demo: the decomposition -> $out/parts.png (a hue per part)"
"$bin/oitprep" parts "$out/demo.oitp" -o "$out/parts.ply" --colour part
"$bin/oitstream" "$out/parts.ply" --size "$size" --azimuth 30 --elevation 35 \
    --out "$out/parts.png" --quiet
case $out in /*) dir=$out ;; *) dir=$(pwd)/$out ;; esac
echo "demo: wrote $dir/frame.png (figures in $dir/frame.json)"
