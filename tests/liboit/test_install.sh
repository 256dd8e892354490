#!/bin/sh
# Installs liboit from a build folder into a temporary prefix (every tool
# of tools/ in its bin/, each answering --help from there), then builds a
# tiny outside project against it twice (find_package(oit) and pkg-config)
# and runs it without LD_LIBRARY_PATH (the prefix is no system folder: the
# run path comes from CMake or from oit.pc's Libs): it must link, load
# liboit.so and print the library's error for
# a missing part file; it must open a .glb (Draco too) through the glTF plugin
# installed beside liboit.so and a gzip mesh through the zlib liboit loads,
# and without the plugin fail naming the file and the plugin's path. Then
# the installed Python package: imported from the
# prefix alone (no OIT_LIBRARY), it must load the prefix's liboit.so, render
# pixels and convert with the prefix's oitprep.
# usage: test_install.sh BUILD_DIR C_COMPILER PYTHON ["EXTRA_FLAGS" [PRELOAD]]
# PRELOAD: the sanitizer runtime python needs to load an instrumented liboit.
# (Empty arguments are dropped on the way from ctest: the optional ones last.)
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
build=$1 cc=$2 python=$3 flags=${4:-} preload=${5:-}
# A build carried to a machine without cmake or a compiler (the GPU recipe)
# cannot install or build a consumer: skipped, saying which.
command -v cmake >/dev/null 2>&1 || skip "cmake not installed here"
command -v "$cc" >/dev/null 2>&1 || skip "$cc not installed here"
"$python" -c 'import numpy' 2>/dev/null || skip "$python has no numpy"
src_dir=$(cd "$(dirname "$0")/../.." && pwd)
temp_scratch liboit-install
tmp=$T
mkdir -p "$tmp/src"

# Every folder of tools/ but common/ is a tool, so a new one is checked too.
# A tool is the executable its folder's CMakeLists.txt adds; an optional one
# (oitstream-mpi without MPI or IceT) is checked where this build made it.
tools=""
for d in "$src_dir"/tools/*/; do
    t=$(sed -n 's/^add_executable(\([^ ]*\).*/\1/p' "$d/CMakeLists.txt" | head -n 1)
    [ -n "$t" ] || continue
    [ "$t" != oitstream-mpi ] || grep -q '^OIT_HAVE_MPI_TOOL:INTERNAL=ON' "$build/CMakeCache.txt" ||
        continue
    tools="$tools$t "
done
# shellcheck disable=SC2086 # one target a tool
cmake --build "$build" --target oit $tools > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
for f in include/oit/oit.h include/oit/liboit.h include/oit/offscreen.h include/oit/partfile.h \
         share/doc/oit/part-file.md lib/liboit-gltf.so lib/liboit-assimp.so lib/liboit-occt.so lib/liboit-reference.so lib/pkgconfig/oit.pc lib/cmake/oit/oitConfig.cmake \
         lib/cmake/oit/oitConfigVersion.cmake \
         lib/python3/dist-packages/oit/__init__.py \
         lib/python3/dist-packages/oit/_install_paths.py; do
    [ -f "$tmp/prefix/$f" ] || { echo "FAIL: not installed: $f"; exit 1; }
done
for t in $tools; do
    [ -x "$tmp/prefix/bin/$t" ] || { echo "FAIL: the tool $t is not installed in bin/"; exit 1; }
    env -u LD_LIBRARY_PATH "$tmp/prefix/bin/$t" --help > "$tmp/help.txt" 2>&1 ||
        { cat "$tmp/help.txt"; echo "FAIL: the installed $t --help exits $?"; exit 1; }
done
echo "tools installed: $tools"
# Exactly the public headers: every one of include/oit/, and no internal one.
(cd "$src_dir" && ls include/oit/*.h) > "$tmp/want"
(cd "$tmp/prefix" && find include -name '*.h' | sort) > "$tmp/got"
cmp -s "$tmp/want" "$tmp/got" ||
    { echo "FAIL: installed headers differ from include/oit/:"; diff "$tmp/want" "$tmp/got"; exit 1; }

cat > "$tmp/src/main.c" <<'C'
#include <oit/oit.h>
#include <stdio.h>
int main(int argc, char **argv)
{
    oit_error err = {0};
    oit_scene *scene = NULL;
    oit_status s = oit_scene_open(argc > 1 ? argv[1] : "missing.oitp", NULL, &scene, &err);
    printf("%s: %s\n", oit_status_name(s), err.message);
    oit_scene_close(scene);
    return s == OIT_OK || s == OIT_ERR_IO ? 0 : 1;
}
C
cat > "$tmp/src/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.20)
project(outside C)
find_package(oit 0.5 REQUIRED)
add_executable(outside main.c)
target_link_libraries(outside PRIVATE oit::oit)
C

missing="$tmp/no-such-scene.oitp"
check_run() { # $1: how it was built, $2: the program
    out=$(env -u LD_LIBRARY_PATH "$2" "$missing") || {
        echo "FAIL ($1): $out"; exit 1; }
    echo "$1: $out"
    case $out in "i/o error: "*no-such-scene.oitp*) ;;
        *) echo "FAIL ($1): the error does not name the file"; exit 1 ;; esac
}

cmake -S "$tmp/src" -B "$tmp/cm" -DCMAKE_C_COMPILER="$cc" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      -DCMAKE_EXE_LINKER_FLAGS="$flags" > "$tmp/cm.log" 2>&1 || { cat "$tmp/cm.log"; exit 1; }
cmake --build "$tmp/cm" > "$tmp/cm-build.log" 2>&1 || { cat "$tmp/cm-build.log"; exit 1; }
check_run find_package "$tmp/cm/outside"

# Mesh files that liboit reads through what it loads at run time, from the
# prefix alone: the glTF and Open CASCADE plugins beside the installed
# liboit.so, and zlib.
corpus="$src_dir/tests/corpus"
open_scene() { # $1: a corpus file; prints the program's line
    env -u LD_LIBRARY_PATH "$tmp/cm/outside" "$corpus/$1"
}
for scene in gltf/scene.glb gltf/draco.glb gltf/scene.gltf.gz off/color.off.gz \
    assimp/wall_glass.ifc assimp/box.fbx step/parts.step step/parts.igs; do
    out=$(open_scene $scene) || { echo "FAIL (open $scene): $out"; exit 1; }
    echo "open $scene: $out"
    case $out in "ok: ") ;; *) echo "FAIL (open $scene): not opened"; exit 1 ;; esac
done
# Without the plugin a glTF file fails, saying which file and which plugin.
mv "$tmp/prefix/lib/liboit-gltf.so" "$tmp/plugin-aside.so"
out=$(open_scene gltf/scene.glb) && { echo "FAIL: opened a .glb without the plugin: $out"; exit 1; }
echo "without the plugin: $out"
case $out in "unsupported: $corpus/gltf/scene.glb: "*"glTF plugin $tmp/prefix/lib/liboit-gltf.so"*) ;;
    *) echo "FAIL: the error does not name the file and the installed plugin's path"; exit 1 ;; esac
mv "$tmp/plugin-aside.so" "$tmp/prefix/lib/liboit-gltf.so"
# Likewise without the assimp plugin, for a format read through assimp.
mv "$tmp/prefix/lib/liboit-assimp.so" "$tmp/plugin-aside.so"
out=$(open_scene assimp/box.fbx) && { echo "FAIL: opened a .fbx without the assimp plugin: $out"; exit 1; }
echo "without the assimp plugin: $out"
case $out in "unsupported: $corpus/assimp/box.fbx: "*"assimp plugin $tmp/prefix/lib/liboit-assimp.so"*) ;;
    *) echo "FAIL: the error does not name the file and the installed assimp plugin's path"; exit 1 ;; esac
mv "$tmp/plugin-aside.so" "$tmp/prefix/lib/liboit-assimp.so"

pc_flags=$(PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig" pkg-config --cflags --libs oit)
echo "pkg-config: $pc_flags"
# shellcheck disable=SC2086
"$cc" $flags "$tmp/src/main.c" $pc_flags -o "$tmp/outside-pc"
check_run pkg-config "$tmp/outside-pc"

# examples/embed_liboit.c against the installed package alone (only its
# public headers are on the include path), both ways, run headless on a
# mesh file (in core) and its part file (streamed, converted by the
# prefix's oitprep): the images must show the scene over the sky, alike.
mkdir -p "$tmp/ex"
cp "$src_dir/examples/embed_liboit.c" "$tmp/ex/"
cat > "$tmp/ex/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.20)
project(embed C)
find_package(oit 0.5 REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
add_executable(embed_liboit embed_liboit.c)
target_link_libraries(embed_liboit PRIVATE oit::oit OpenGL::OpenGL OpenGL::EGL m)
C
cmake -S "$tmp/ex" -B "$tmp/ex-cm" -DCMAKE_C_COMPILER="$cc" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      -DCMAKE_EXE_LINKER_FLAGS="$flags" > "$tmp/ex-cm.log" 2>&1 || { cat "$tmp/ex-cm.log"; exit 1; }
cmake --build "$tmp/ex-cm" > "$tmp/ex-build.log" 2>&1 || { cat "$tmp/ex-build.log"; exit 1; }
ex_flags=$(PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig" pkg-config --cflags --libs oit opengl egl)
echo "example, pkg-config: $ex_flags"
# shellcheck disable=SC2086
"$cc" $flags "$tmp/ex/embed_liboit.c" $ex_flags -lm -o "$tmp/embed-pc" ||
    { echo "FAIL: the example does not build with pkg-config"; exit 1; }
"$build/bin/oitgen" quads --count 24 -o "$tmp/quads.ply" > /dev/null
"$tmp/prefix/bin/oitprep" "$tmp/quads.ply" -o "$tmp/quads.oitp" --part-triangles 8 > /dev/null
for how in cm pc; do
    exe="$tmp/ex-cm/embed_liboit"
    [ $how = pc ] && exe="$tmp/embed-pc"
    for scene in quads.ply quads.oitp; do
        out=$(env -u LD_LIBRARY_PATH "$exe" "$tmp/$scene" "$tmp/$how-$scene.ppm" 96 72) || {
            echo "FAIL (example $how, $scene): $out"; exit 1; }
        echo "example $how: $out"
    done
done
cat > "$tmp/ppm_check.py" <<'P'
import sys
def load(path):
    data = open(path, "rb").read()
    magic, w, h, top, rest = data.split(maxsplit=4)
    assert magic == b"P6" and top == b"255", path
    return int(w), int(h), rest
sky = bytes((115, 158, 217))
images = [load(p) for p in sys.argv[1:]]
for path, (w, h, px) in zip(sys.argv[1:], images):
    assert len(px) == w * h * 3, path
    covered = sum(px[i:i + 3] != sky for i in range(0, len(px), 3)) / (w * h)
    assert covered > 0.1, f"{path}: {covered:.1%} of the pixels show the scene"
    print(f"{path}: {covered:.1%} covered")
ref = images[0][2]
for path, (w, h, px) in zip(sys.argv[1:], images):
    far = sum(abs(a - b) > 1 for a, b in zip(px, ref)) / len(px)
    assert far <= 0.001, f"{path}: {far:.2%} of the values differ from {sys.argv[1]}"
P
"$python" "$tmp/ppm_check.py" "$tmp/cm-quads.ply.ppm" "$tmp/cm-quads.oitp.ppm" \
    "$tmp/pc-quads.ply.ppm" "$tmp/pc-quads.oitp.ppm" || { echo "FAIL: the example's images"; exit 1; }

# The Python package, from the prefix alone.
cat > "$tmp/py_check.py" <<'P'
import os, sys
import numpy as np
os.environ.pop("LD_PRELOAD", None)  # for this process only; oitprep has its own runtime
import oit
prefix = os.path.realpath(sys.argv[1])
lib = os.path.realpath(oit.lib_path())
assert lib.startswith(prefix + "/lib/"), f"liboit from {lib}, not the prefix {prefix}"
assert os.path.realpath(oit.prep_tool()) == prefix + "/bin/oitprep", oit.prep_tool()
pos = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]
img = oit.render_arrays(pos, [[0, 1, 2], [0, 2, 3]], np.array([[255, 0, 0, 128]] * 2, np.uint8),
                        size=(32, 32), view={"eye": (0, 0, 4), "target": (0, 0, 0), "fovy": 30})
assert tuple(img[16, 16]) == (255, 127, 127, 255), img[16, 16]
assert tuple(img[0, 0]) == (255, 255, 255, 255), img[0, 0]
ply = os.path.join(sys.argv[2], "tri.ply")
with open(ply, "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
oit.prep(ply, os.path.join(sys.argv[2], "tri.oitp"))
with oit.Scene.open(os.path.join(sys.argv[2], "tri.oitp")) as s:
    assert s.info["triangles"] == 1 and not s.info["in_core"], s.info
print("python: liboit from", lib, "; pixels and oit.prep OK")
P
# shellcheck disable=SC2016
env -u OIT_LIBRARY -u OIT_PREP PYTHONPATH="$tmp/prefix/lib/python3/dist-packages" \
    PYTHONDONTWRITEBYTECODE=1 ${preload:+LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0} \
    "$python" "$tmp/py_check.py" "$tmp/prefix" "$tmp" || {
    echo "FAIL (python): the installed package"; exit 1; }
echo "install: OK"
