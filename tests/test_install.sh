#!/bin/sh
# Installs liboit from a build folder into a temporary prefix, then builds a
# tiny outside project against it twice (find_package(oit) and pkg-config)
# and runs it: it must link, load liboit.so and print the library's error for
# a missing part file.
# usage: test_install.sh BUILD_DIR C_COMPILER "EXTRA_FLAGS"
set -eu
build=$1 cc=$2 flags=${3:-}
tmp=${OIT_TEST_TMP:-/tmp}/liboit-install.$$
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/src"

cmake --build "$build" --target oit > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
for f in include/oit/oit.h include/oit/liboit.h include/oit/offscreen.h include/oit/partfile.h \
         lib/pkgconfig/oit.pc lib/cmake/oit/oitConfig.cmake \
         lib/cmake/oit/oitConfigVersion.cmake; do
    [ -f "$tmp/prefix/$f" ] || { echo "FAIL: not installed: $f"; exit 1; }
done
# Only the public headers: render/ and stream/ internals must not leak.
extra=$(find "$tmp/prefix/include" -name '*.h' | wc -l)
[ "$extra" -eq 6 ] || { echo "FAIL: $extra headers installed, expected 6"; exit 1; }

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
    return s == OIT_ERR_IO ? 0 : 1;
}
C
cat > "$tmp/src/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.20)
project(outside C)
find_package(oit 0.1 REQUIRED)
add_executable(outside main.c)
target_link_libraries(outside PRIVATE oit::oit)
C

missing="$tmp/no-such-scene.oitp"
check_run() { # $1: how it was built, $2: the program
    out=$(LD_LIBRARY_PATH="$tmp/prefix/lib" "$2" "$missing") || {
        echo "FAIL ($1): $out"; exit 1; }
    echo "$1: $out"
    case $out in "i/o error: "*no-such-scene.oitp*) ;;
        *) echo "FAIL ($1): the error does not name the file"; exit 1 ;; esac
}

cmake -S "$tmp/src" -B "$tmp/cm" -DCMAKE_C_COMPILER="$cc" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      -DCMAKE_EXE_LINKER_FLAGS="$flags" > "$tmp/cm.log" 2>&1 || { cat "$tmp/cm.log"; exit 1; }
cmake --build "$tmp/cm" > "$tmp/cm-build.log" 2>&1 || { cat "$tmp/cm-build.log"; exit 1; }
check_run find_package "$tmp/cm/outside"

pc_flags=$(PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig" pkg-config --cflags --libs oit)
echo "pkg-config: $pc_flags"
# shellcheck disable=SC2086
"$cc" $flags "$tmp/src/main.c" $pc_flags -o "$tmp/outside-pc"
check_run pkg-config "$tmp/outside-pc"
echo "install: OK"
