#!/bin/sh
# No include cycle between modules (issue 48): a module is a file without
# its extension (x.c and x.h), and x depends on y when x.c or x.h includes
# y.h. A cycle is allowed only inside one folder through that folder's
# internal header, one state over several files (docs/architecture.md:
# streamer_internal.h, capture_backend.h, ...: a header whose name ends in
# _internal, _backend, _steps or _job); any other cycle fails, naming its
# modules (the one partfile/read.c <-> validate.c had).
# usage: test_include_cycles.sh SOURCE_DIR [TMP_DIR]
#          with TMP_DIR, first plants two modules that include each other
#          and checks that they are named.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/lib.sh}"

cycles() {
    (cd "$1" && find . -path ./tests -prune -o -path ./examples -prune -o -path './build*' -prune \
        -o -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) -print | sed 's|^\./||' |
        sort | python3 -c '
import os, re, sys
files = sys.stdin.read().split()
have = set(files)
inc = re.compile(r"^\s*#\s*include\s*\"([^\"]+)\"", re.M)
mod = lambda f: os.path.splitext(f)[0]
g = {}
for f in files:
    for h in inc.findall(open(f, errors="replace").read()):
        h = h if h in have else "include/" + h
        if h in have and mod(h) != mod(f):
            g.setdefault(mod(f), set()).add(mod(h))
index, low, stack, on, found = {}, {}, [], set(), []
def visit(v):  # Tarjan: the strongly connected components
    index[v] = low[v] = len(index)
    stack.append(v); on.add(v)
    for w in g.get(v, ()):
        if w not in index:
            visit(w); low[v] = min(low[v], low[w])
        elif w in on:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        comp = []
        while True:
            w = stack.pop(); on.discard(w); comp.append(w)
            if w == v: break
        if len(comp) > 1: found.append(sorted(comp))
sys.setrecursionlimit(100000)
for v in list(g):
    if v not in index: visit(v)
internal = re.compile(r"_(internal|backend|steps|job)$")
for comp in found:
    one_folder = len({os.path.dirname(m) for m in comp}) == 1
    if not (one_folder and any(internal.search(m) for m in comp)):
        print(" <-> ".join(comp))
')
}

if [ $# -ge 2 ]; then
    dir="$2/include_cycles_selftest"
    rm -rf "$dir"
    mkdir -p "$dir/a" "$dir/b"
    printf '#include "b/y.h"\n' >"$dir/a/x.c"
    printf '#include "a/x.h"\n' >"$dir/b/y.c"
    : >"$dir/a/x.h"
    : >"$dir/b/y.h"
    printf '#include "a/x.h"\n' >"$dir/a/x_internal.h"
    printf '#include "a/x_internal.h"\n' >"$dir/a/x2.c"
    got=$(cycles "$dir")
    [ "$got" = "a/x <-> b/y" ] || fail "self-test: the planted cycle is not named alone: '$got'"
fi

got=$(cycles "$1")
[ -z "$got" ] || fail "include cycles between modules: $got"
finish "include cycles"
