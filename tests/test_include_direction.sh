#!/bin/sh
# Dependencies point one way (docs/architecture.md): a folder includes only
# headers of its own and of the folders below it. A lower folder that reaches
# up fails here, naming the file and the include.
# usage: test_include_direction.sh SOURCE_DIR
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/lib.sh}"
cd "$1"

# Each line: a folder, then the folders whose headers it may include
# ("oit" is include/oit/; a folder allows its headers, a header path that
# header alone; "!path" forbids a folder or header that an entry before it
# allowed, e.g. the baselines below their parent view/render/; the tools reach
# the renderer through liboit alone: tools/common/method_run.h).
while read -r dir ok; do
    if [ ! -d "$dir" ]; then # a moved folder must move in this table too
        fail "no folder $dir: update this table"
        continue
    fi
    for f in "$dir"/*.c "$dir"/*.h "$dir"/*.cpp; do
        [ -f "$f" ] || continue
        # quoted includes that name a folder: "view/render/capture/dfb.h"
        for inc in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([a-z_]*\/[^"]*\)".*/\1/p' "$f"); do
            hit=0
            for a in $ok; do
                case $a in
                !*) case $inc in "${a#!}" | "${a#!}"/*) hit=0 ;; esac ;;
                *) case $inc in "$a" | "$a"/*) hit=1 ;; esac ;;
                esac
            done
            [ $hit = 1 ] ||
                fail "$f includes \"$inc\": $dir may include only: ${ok:-system headers and its own}"
        done
    done
done <<EOF
include/oit oit
base oit base
formats oit base formats
partfile oit base formats partfile
view/render/image oit base formats view/render/image
view/render/pick oit base formats partfile view/render/image view/render/pick
view/render/gl oit base formats view/render/image view/render/gl
view/render/capture oit base formats view/render/image view/render/gl view/render/capture
view/render oit base formats view/render !view/render/baselines !view/render/reference
view/render/reference oit base formats view/render/image view/render/method.h view/render/pick/pick.h view/render/reference
view/render/baselines oit base formats view/render !view/render/reference
view/plot oit base formats view/render/image view/plot
prepare/scenes oit base formats prepare/scenes
prepare/partition oit base formats partfile prepare/partition
prepare/convert oit base formats partfile prepare/partition prepare/convert
view/stream oit base formats partfile view/render view/stream
liboit oit base formats partfile view/render view/stream liboit
tools/common oit base formats partfile view/render !view/render/capture !view/render/baselines !view/render/reference !view/render/method.h tools/common
tools/oitgen oit base formats prepare/scenes tools/common tools/oitgen
tools/oitprep oit base formats partfile prepare/convert tools/common tools/oitprep
tools/oitstream oit base formats partfile view/render !view/render/capture !view/render/baselines !view/render/reference !view/render/method.h view/plot tools/common tools/oitstream
tools/oitbench oit base formats partfile view/render !view/render/capture !view/render/baselines !view/render/reference !view/render/method.h view/plot prepare/convert tools/common tools/oitbench
tools/oit_meshinfo oit tools/common/exit_code.h
tools/oitstream_mpi oit base formats partfile view/render !view/render/capture !view/render/baselines !view/render/reference !view/render/method.h tools/common tools/oitstream tools/oitstream_mpi
EOF
finish "include direction"
