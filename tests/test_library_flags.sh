#!/bin/sh
# The library names no command-line flag (docs/architecture.md, "A
# setting's path"): its errors and documents name descriptor fields
# ("oit_renderer_desc.upload_budget"), and the tools spell them as their
# flags (tools/common/flag_spelling.c). Every *.c, *.cpp, *.h and *.glsl of
# the folders below tools/ (liboit.so's sources, include/oit/, and the
# conversion's) is read for a flag in its comments and string literals: two
# dashes and a word ("--capture"); code is not read, so a decrement
# ("--top") is not one, nor a linker option (CMake files are not read).
# usage: test_library_flags.sh SOURCE_DIR [TMP_DIR]
#          with TMP_DIR, first plants a flag in a comment and in a message
#          and checks that both are named and that decrements are not.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/lib.sh}"
FOLDERS="base formats partfile view/render view/plot prepare/scenes prepare/partition prepare/convert view/stream liboit include"

# flags DIR: "path:line: flag" of each flag in DIR's library folders.
flags() {
    (cd "$1" && find $FOLDERS -type f \( -name '*.c' -o -name '*.cpp' -o -name '*.h' \
        -o -name '*.glsl' \) 2>/dev/null | sort | python3 -c '
import re, sys
# comments and string literals; code between them is skipped
TEXT = re.compile(r"/\*.*?\*/|//[^\n]*|\"(?:\\.|[^\"\\\n])*\"|\x27(?:\\.|[^\x27\\\n])*\x27", re.S)
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9]*(?:-[a-z0-9]+)*(?![\w-])")
for path in sys.stdin.read().split():
    src = open(path, encoding="utf-8", errors="replace").read()
    for m in TEXT.finditer(src):
        for f in FLAG.finditer(m.group(0)):
            line = src.count("\n", 0, m.start() + f.start()) + 1
            print("%s:%d: %s" % (path, line, f.group(0)))
')
}

if [ $# -ge 2 ]; then
    dir="$2/library_flags_selftest"
    rm -rf "$dir"
    mkdir -p "$dir/view/stream" "$dir/include/oit"
    cat >"$dir/view/stream/planted.c" <<'C'
/* what --upload-budget says */
static int f(int *s, int top, int *a) { return a[--top] + --s[0] + (--top); }
static const char *m = "more than --gpu-budget %llu";
C
    printf '/* i--, x-- > 0, a -- b */\n' >"$dir/include/oit/clean.h"
    got=$(flags "$dir")
    case $got in *planted.c:1:*) ;; *) fail "self-test: the planted comment's flag was not found: $got" ;; esac
    case $got in *planted.c:3:*) ;; *) fail "self-test: the planted message's flag was not found: $got" ;; esac
    case $got in *planted.c:2:* | *clean.h*) fail "self-test: a decrement read as a flag: $got" ;; esac
    rm -rf "$dir"
fi

found=$(flags "$1")
if [ -n "$found" ]; then
    echo "$found" >&2
    fail "the library names command-line flags (name the descriptor field; the tools spell it)"
fi
finish library_flags
