#!/usr/bin/env bash
# Fetches the real meshes the integration tests and benchmarks read, from
# Debian packages (no root needed: `apt-get download` + `dpkg -x`, nothing is
# installed), into one flat folder.
#
# Usage: fetch_meshes.sh [CACHE_DIR]      (default: data_scripts/cache)
#
# Idempotent: files already in CACHE_DIR are kept, and the .deb files stay in
# CACHE_DIR/.debs so a re-run downloads nothing. At the end it prints a table
# of file, format, triangles and bounds; the figures come from oit_meshinfo
# (OIT_BIN, or build*/bin), "?" when no build has it.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
cache=${1:-$here/cache}
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)
debs=$cache/.debs
mkdir -p "$debs"

die() { echo "fetch_meshes: $*" >&2; exit 1; }
# Extraction folders are scratch, also when a step fails half-way.
trap 'rm -rf "$cache"/.x-*' EXIT

find_deb() {
    local f
    for f in "$debs/$1"_*.deb; do
        if [ -e "$f" ]; then
            echo "$f"
            return 0
        fi
    done
    return 0
}

# package -> files wanted from it: "path inside the package" or, for files
# inside an archive of the package, "archive!member".
cgal_data=usr/share/doc/libcgal-dev/data.tar.gz
models=usr/share/assimp/models
wanted_libcgal_demo=(
    "$cgal_data!data/meshes/bunny00.off"
    "$cgal_data!data/meshes/armadillo.off"
    "$cgal_data!data/meshes/refined_elephant.off"
    "$cgal_data!data/meshes/ChineseDragon-10kv.off"
    "$cgal_data!data/meshes/fandisk.off"
    "$cgal_data!data/meshes/turbine.off"
)
wanted_assimp_testmodels=(
    "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
    "$models/glTF2/draco/2CylinderEngine.gltf"
    "$models/glTF2/draco/2CylinderEngine.bin"
    "$models/PLY/Wuson.ply"
    "$models/OBJ/spider.obj"
    "$models/OBJ/spider.mtl"
    "$models/OBJ/SpiderTex.jpg"
    "$models/OBJ/wal67ar_small.jpg"
    "$models/OBJ/wal69ar_small.jpg"
    "$models/OBJ/drkwood2.jpg"
    "$models/OBJ/engineflare1.jpg"
    "$models/STL/Spider_binary.stl"
)
wanted_occt_misc=(
    "usr/share/opencascade/data/stl/head.stl"
    "usr/share/opencascade/data/stl/propeller.stl"
)

# The Draco glTF and the GLB share a base name; keep the Draco one apart (its
# buffer keeps its name, which is what the .gltf's "uri" says).
flat_name() {
    case $1 in
        */draco/2CylinderEngine.gltf) echo 2CylinderEngine-draco.gltf ;;
        *) basename "$1" ;;
    esac
}

all_present() {
    local item
    for item in "$@"; do
        [ -e "$cache/$(flat_name "${item#*!}")" ] || return 1
    done
}

fetch_package() {
    local pkg=$1
    shift
    if all_present "$@"; then
        echo "fetch_meshes: $pkg: all files present"
        return
    fi
    local deb
    deb=$(find_deb "$pkg")
    if [ -z "$deb" ]; then
        echo "fetch_meshes: $pkg: downloading"
        (cd "$debs" && apt-get download "$pkg" >/dev/null 2>"$debs/$pkg.log") ||
            die "$pkg: apt-get download failed (see $debs/$pkg.log; try apt-get update)"
        deb=$(find_deb "$pkg")
        [ -n "$deb" ] || die "$pkg: apt-get download produced no .deb"
    fi
    local root
    root=$(mktemp -d "$cache/.x-$pkg.XXXXXX")
    dpkg -x "$deb" "$root" || die "$pkg: dpkg -x $deb failed"
    local item path member out
    for item in "$@"; do
        out=$cache/$(flat_name "${item#*!}")
        [ -e "$out" ] && continue
        if [[ $item == *'!'* ]]; then
            path=${item%%!*}
            member=${item#*!}
            [ -f "$root/$path" ] || die "$pkg: archive /$path not in the package"
            tar -xzf "$root/$path" -O "$member" >"$out.part" 2>/dev/null ||
                { rm -f "$out.part"; die "$pkg: $member not in /$path"; }
        else
            [ -f "$root/$item" ] || die "$pkg: /$item not in the package"
            cp "$root/$item" "$out.part"
        fi
        mv "$out.part" "$out"
    done
    rm -rf "$root"
}

fetch_package libcgal-demo "${wanted_libcgal_demo[@]}"
fetch_package assimp-testmodels "${wanted_assimp_testmodels[@]}"
fetch_package occt-misc "${wanted_occt_misc[@]}"

meshinfo=""
for d in "${OIT_BIN:-}" "$here"/../build*/bin; do
    if [ -n "$d" ] && [ -x "$d/oit_meshinfo" ]; then
        meshinfo=$d/oit_meshinfo
        break
    fi
done

printf '%-28s %-6s %10s  %s\n' file format triangles bounds
for f in "$cache"/*; do
    name=$(basename "$f")
    ext=${name##*.}
    ext=${ext,,}
    case $ext in
        off | ply | obj | stl | gltf | glb) ;;
        *) continue ;;
    esac
    tris="?" bounds=""
    if [ -n "$meshinfo" ]; then
        # oit_meshinfo prints "triangles N" and "bounds x y z  X Y Z".
        if line=$("$meshinfo" "$f" 2>&1); then
            tris=$(awk '$1 == "triangles" { print $2 }' <<<"$line")
            bounds=$(awk '$1 == "bounds" { $1 = ""; print substr($0, 2) }' <<<"$line")
        else
            tris="error" bounds=$line
        fi
    fi
    printf '%-28s %-6s %10s  %s\n' "$name" "$ext" "$tris" "$bounds"
done
