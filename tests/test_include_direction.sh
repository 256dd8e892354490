#!/bin/sh
# Dependencies point one way (docs/architecture.md): a folder includes only
# headers of its own and of the folders below it. A lower folder that reaches
# up fails here, naming the file and the include.
# usage: test_include_direction.sh SOURCE_DIR
set -eu
cd "$1"
status=0

# Each line: a folder, then the folders whose headers it may include
# ("oit" is include/oit/; a header path allows that header alone).
while read -r dir ok; do
    if [ ! -d "$dir" ]; then # a moved folder must move in this table too
        echo "FAIL: no folder $dir: update this table" >&2
        status=1
        continue
    fi
    for f in "$dir"/*.c "$dir"/*.h "$dir"/*.cpp; do
        [ -f "$f" ] || continue
        # quoted includes that name a folder: "render/dfb.h"
        for inc in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([a-z_]*\/[^"]*\)".*/\1/p' "$f"); do
            top=${inc%%/*}
            hit=0
            for a in $ok; do
                [ "$a" = "$top" ] && hit=1
                [ "$a" = "$inc" ] && hit=1
            done
            if [ $hit = 0 ]; then
                echo "FAIL: $f includes \"$inc\": $dir may include only: ${ok:-system headers and its own}" >&2
                status=1
            fi
        done
    done
done <<EOF
include/oit
base oit base
formats oit base formats
render oit base formats render
scenes oit base formats scenes
partition oit base formats partition
preprocess oit base formats partition preprocess stream/order.h
stream oit base formats render partition preprocess stream
EOF
[ $status = 0 ] && echo "ok: every folder includes only its own headers and those below it"
exit $status
