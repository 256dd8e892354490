#!/bin/sh
# The tools render through liboit alone (tools/common/method_run.h): no
# tool defines a function of the renderer's static libraries (the capture,
# the streamer, the method interface, the baselines, the reference), whose
# one copy is liboit.so's. Reads the functions those libraries define
# (nm of their archives) and fails naming the tool and the functions it
# holds. First shows that it finds them: in an archive of their own.
# Usage: test_tools_nm.sh BUILD_DIR
set -eu
build=$1
libs="view/render/capture/liboit_capture.a view/stream/liboit_stream.a view/render/liboit_render.a
view/render/liboit_baselines.a view/render/reference/liboit_reference.a"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for l in $libs; do
    [ -f "$build/$l" ] || { echo "FAIL: $build/$l is not built"; exit 1; }
    nm --defined-only "$build/$l" 2>/dev/null | awk '$2 == "T" { print $3 }'
done | sort -u > "$tmp/renderer"
n=$(wc -l < "$tmp/renderer")
[ "$n" -ge 200 ] || { echo "FAIL: only $n functions in the renderer's libraries"; exit 1; }

# the functions of `file` that are the renderer's
held() {
    nm --defined-only "$1" 2>/dev/null | awk '$2 == "T" || $2 == "t" { print $3 }' |
        sort -u | comm -12 - "$tmp/renderer"
}

# self-test: the capture's own archive holds them
[ -n "$(held "$build/view/render/capture/liboit_capture.a")" ] ||
    { echo "FAIL: the check finds none of the capture's functions in its own archive"; exit 1; }

fail=0
tools=0
for t in oitstream oitbench oitstream-mpi oitgen oitprep oit_meshinfo; do
    f="$build/bin/$t"
    [ -f "$f" ] || continue
    tools=$((tools + 1))
    h=$(held "$f")
    if [ -n "$h" ]; then
        echo "FAIL: $t holds $(echo "$h" | wc -l) of the renderer's functions:" $(echo "$h" | head -8)
        fail=1
    fi
done
[ "$tools" -ge 3 ] || { echo "FAIL: only $tools tools built in $build/bin"; exit 1; }
[ $fail -eq 0 ] || exit 1
echo "ok: $tools tools hold none of the $n functions of the renderer's libraries"
