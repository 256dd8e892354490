#!/bin/sh
# Installs the Debian packages of setup/debian-packages.txt that are missing.
# Idempotent: does nothing (and needs no root) when all are present; runs
# `apt-get update` only when an install fails for want of package lists.
# Usage: install-deps.sh [LIST]   LIST: another package list of the same form
# (one package a line, '#' comments), e.g. setup/bench-packages.txt for the
# peer renderers of data_scripts/stream_vs_dfb.sh; default
# setup/debian-packages.txt.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
list=${1:-$here/debian-packages.txt}
if [ ! -r "$list" ]; then
    echo "install-deps: $list: no such package list" >&2
    exit 2
fi
missing=""
for p in $(grep -v '^#' "$list"); do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        missing="$missing $p"
done
[ -z "$missing" ] && exit 0

echo "install-deps: installing:$missing" >&2
if [ "$(id -u)" -eq 0 ]; then sudo=""; 
elif command -v sudo >/dev/null 2>&1; then sudo="sudo";
else
    echo "install-deps: missing packages:$missing; run as root or install them" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
# shellcheck disable=SC2086
if ! $sudo apt-get install -y -q --no-install-recommends $missing; then
    echo "install-deps: refreshing package lists and retrying" >&2
    $sudo apt-get update -q
    # shellcheck disable=SC2086
    $sudo apt-get install -y -q --no-install-recommends $missing
fi
