#!/bin/sh
# Extracts IceT (the sort-last compositor oitstream-mpi uses) from Debian 12's
# ParaView packages into DIR, without installing ParaView.
#
# Usage: fetch-icet.sh [DIR]     (default: setup/cache/icet, git-ignored)
#
# Debian ships IceT only inside ParaView 5.11: the headers in paraview-dev
# (usr/include/paraview-5.11/vtkicet/src/include/), the libraries in paraview
# (libvtkIceTCore-pv5.11.so.1, libvtkIceTMPI-pv5.11.so.1). Installing
# paraview-dev pulls about 440 MB of packages (Qt, VTK, GDAL, HDF5, ...),
# while the two .debs are 72 MB and the files we need 200 KB. The extraction
# is self-contained: readelf -d shows IceTCore needs only libc and libm, and
# IceTMPI needs IceTCore and libmpi.so.40 (libopenmpi3, which libopenmpi-dev
# of setup/debian-packages.txt installs); the headers include only each
# other, stdlib.h and mpi.h. So `apt-get download` + `dpkg -x` (no root, as
# data_scripts/fetch_meshes.sh does) and a copy of six files; the .debs are
# deleted after, so DIR holds 200 KB, and a re-run with DIR complete does
# nothing. CMake looks here (OIT_ICET_DIR) and in /usr (paraview-dev installed).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
dir=${1:-$here/cache/icet}
inc=usr/include/paraview-5.11/vtkicet/src/include
lib=usr/lib/x86_64-linux-gnu
headers="IceT.h IceTConfig.h IceTMPI.h"
libs="libvtkIceTCore-pv5.11 libvtkIceTMPI-pv5.11"

complete() {
    for h in $headers; do [ -e "$dir/include/$h" ] || return 1; done
    for l in $libs; do [ -e "$dir/lib/$l.so" ] || return 1; done
    return 0
}
if complete; then
    exit 0
fi
command -v apt-get >/dev/null 2>&1 || { echo "fetch-icet: no apt-get: install paraview-dev, or put IceT in $dir" >&2; exit 1; }
mkdir -p "$dir"
work=$(mktemp -d "$dir/.x-XXXXXX")
trap 'rm -rf "$work"' EXIT
# apt-get download writes into the working directory, and checks each .deb
# against the signed package lists. A clean system (a container image) may
# have no lists: refresh them once, as install-deps.sh does.
download() { (cd "$work" && apt-get download -q paraview paraview-dev >&2); }
if ! download; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || { command -v sudo >/dev/null 2>&1 && sudo=sudo; }
    echo "fetch-icet: refreshing the package lists and retrying" >&2
    # shellcheck disable=SC2086
    if ! { $sudo apt-get update -q >&2 && download; }; then
        echo "fetch-icet: apt-get download paraview paraview-dev failed (no network to the" \
             "Debian mirror, or no root for apt-get update?)" >&2
        exit 1
    fi
fi
for deb in "$work"/*.deb; do
    dpkg -x "$deb" "$work/x"
done
mkdir -p "$dir/include" "$dir/lib"
for h in $headers; do
    cp "$work/x/$inc/$h" "$dir/include/$h"
done
for l in $libs; do
    # The real file, its soname link (what binaries record) and the link the
    # linker finds.
    cp "$work/x/$lib/$l.so.5.11" "$dir/lib/"
    ln -sf "$l.so.5.11" "$dir/lib/$l.so.1"
    ln -sf "$l.so.1" "$dir/lib/$l.so"
done
echo "fetch-icet: IceT headers and libraries in $dir" >&2
