#!/bin/sh
# No source file over 600 lines: one concern a file, split by concern (not
# in halves) and kept short enough that the next change has room. Every
# *.c, *.cpp and *.h under the source folders counts (tests/ and build*/
# folders do not); tests/view/render/test_render_layout.sh holds view/render/ to the
# same rule with checks of its own. The files still over are allowed below,
# each with its line count as a ceiling: one may shrink, never grow, and
# leaves the list once at 600 or under, so the list only shortens. Fails
# naming each file over the limit or its ceiling, and each entry of the list
# that is under the limit or gone.
# usage: test_file_sizes.sh SOURCE_DIR [TMP_DIR]
#          with TMP_DIR, first plants each fault in a tree of its own there
#          and checks that each is named and clean files are not, so that a
#          check that stopped matching cannot pass for clean sources.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/lib.sh}"
MAX_LINES=600
FOLDERS="base formats partfile view/render prepare/partition prepare/convert prepare/scenes view/stream liboit tools view/plot include
examples python"

# The files still over MAX_LINES, a path and its ceiling a line. Only take
# lines out: split a file by concern, then remove its entry (this test says
# when). OIT_FILE_SIZES_ALLOWED replaces the list (the self-test's).
ALLOWED=${OIT_FILE_SIZES_ALLOWED-"
"}

# lines N: N lines of C comments
lines() {
    i=0
    while [ $i -lt "$1" ]; do
        echo "/* $i */"
        i=$((i + 1))
    done
}

if [ $# -ge 2 ]; then
    dir="$2/file_sizes_selftest"
    rm -rf "$dir"
    for f in $FOLDERS; do mkdir -p "$dir/$f"; done
    mkdir -p "$dir/tests" "$dir/formats/build-x" "$dir/tools/t"
    lines $((MAX_LINES + 1)) >"$dir/formats/long.c"        # over, not allowed
    lines $MAX_LINES >"$dir/partfile/full.h"               # at the limit: fine
    lines 651 >"$dir/include/grown.h"                      # over its ceiling of 650
    lines 640 >"$dir/view/stream/kept.cpp"                      # within its ceiling of 650
    lines $MAX_LINES >"$dir/tools/t/shrunk.c"              # allowed, now at the limit
    lines 900 >"$dir/tests/long_test.c"                    # tests/: not counted
    lines 900 >"$dir/formats/build-x/generated.c"          # a build folder: not counted
    lines 900 >"$dir/formats/notes.txt"                    # not source
    allowed="include/grown.h 650
view/stream/kept.cpp 650
tools/t/shrunk.c 700
python/gone.c 700"
    if out=$(OIT_FILE_SIZES_ALLOWED=$allowed sh "$0" "$dir" 2>&1); then
        die "planted faults passed: $out"
    fi
    case $out in *"formats/long.c: 601 lines"*) ;; *) die "long file not named: $out" ;; esac
    case $out in *"include/grown.h: 651 lines"*) ;; *) die "grown file not named: $out" ;; esac
    case $out in *"tools/t/shrunk.c: 600 lines"*) ;; *) die "shrunk file not named: $out" ;; esac
    case $out in *"python/gone.c"*) ;; *) die "missing file not named: $out" ;; esac
    case $out in *full.h* | *kept.cpp* | *long_test.c* | *generated.c* | *notes.txt*)
        die "a clean file was named: $out" ;;
    esac
    rm -rf "$dir"
    echo "ok: the planted long, grown, shrunk and missing files are named"
fi

cd "$1"
for f in $FOLDERS; do
    [ -d "$f" ] || fail "no folder $f: update FOLDERS in this test"
done
# ceiling FILE: its ceiling on the list, or nothing
ceiling() {
    while read -r path max; do
        [ "$path" != "$1" ] || echo "$max"
    done <<EOF
$ALLOWED
EOF
}
for f in $(find $FOLDERS -type d -name 'build*' -prune -o -type f \
    \( -name '*.c' -o -name '*.cpp' -o -name '*.h' \) -print | sort); do
    n=$(wc -l <"$f")
    [ "$n" -gt $MAX_LINES ] || continue
    max=$(ceiling "$f")
    if [ -z "$max" ]; then
        fail "$f: $n lines, more than $MAX_LINES: split it by concern"
    elif [ "$n" -gt "$max" ]; then
        fail "$f: $n lines, more than its ceiling of $max in this test's list: it may only shrink"
    fi
done
while read -r path max; do
    [ -n "$path" ] || continue
    if [ ! -f "$path" ]; then
        fail "$path: in this test's list of files over $MAX_LINES lines, but not there: take it off"
    elif [ "$(wc -l <"$path")" -le $MAX_LINES ]; then
        fail "$path: $(wc -l <"$path") lines, at most $MAX_LINES now: take it off this test's list"
    fi
done <<EOF
$ALLOWED
EOF
finish "file sizes"
