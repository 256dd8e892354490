#!/bin/sh
# The shape issue 32 gave view/render/: no source file over 600 lines (one
# concern a file; split by concern, not in halves), and the capture's
# backend kind told apart in one place only, capture_create.c's table lookup
# and the create calls: every other file of view/render/capture/ reaches a backend
# through its table of operations (capture_backend.h). Fails naming each
# file over the limit and each line that names a backend kind elsewhere.
# usage: test_render_layout.sh SOURCE_DIR [TMP_DIR]
#          with TMP_DIR, first plants a long file and a branch on the kind
#          there and checks that both are named, so that a check that
#          stopped matching cannot pass for clean sources.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
MAX_LINES=600

if [ $# -ge 2 ]; then
    dir="$2/render_layout_selftest"
    rm -rf "$dir"
    mkdir -p "$dir/view/render/capture"
    i=0
    while [ $i -le $MAX_LINES ]; do echo "/* $i */"; i=$((i + 1)); done >"$dir/view/render/long.c"
    printf '%s\n' '/* fine */' >"$dir/view/render/capture/capture_create.c"
    printf '%s\n' '/* a backend */' 'OIT_CAPTURE_OPS(x, OIT_CAPTURE_ARRAY, "x", int, NULL);' '' \
        'static int f(const oit_capture *c) { return c->ops->kind == OIT_CAPTURE_STENCIL; }' \
        >"$dir/view/render/capture/capture_x.c"
    if out=$(sh "$0" "$dir" 2>&1); then
        die "planted faults passed: $out"
    fi
    case $out in *"view/render/long.c: 601 lines"*) ;; *) die "long file not named: $out" ;; esac
    case $out in *"view/render/capture/capture_x.c:4:"*) ;; *) die "branch not named: $out" ;; esac
    case $out in *"capture_x.c:2:"*) die "a table was reported: $out" ;; esac
    rm -rf "$dir"
    echo "ok: the planted long file and branch are named"
fi

cd "$1"
[ -d view/render/capture ] || die "no folder view/render/capture: update this test"
for f in $(find view/render -name '*.[ch]' | sort); do
    n=$(wc -l <"$f")
    [ "$n" -le $MAX_LINES ] || fail "$f: $n lines, more than $MAX_LINES: split it by concern"
done
# capture_choice.c decides which fill to make; capture_create.c looks the
# table up.
for f in view/render/capture/*.c; do
    case $f in view/render/capture/capture_create.c | view/render/capture/capture_choice.c) continue ;; esac
    # comment lines and the tables (OIT_CAPTURE_OPS) are not branches
    hits=$(grep -nE 'OIT_CAPTURE_(ARRAY|STENCIL|COUNTED|FIRSTK|COMPUTE)|->kind|oit_capture_backend\(' "$f" |
        grep -vE '^[0-9]+:OIT_CAPTURE_OPS\(|^[0-9]+:/?[[:space:]]*\*') || true
    [ -z "$hits" ] ||
        fail "$(printf '%s\n' "$hits" | sed "s|^|$f:|")
  names a capture kind: reach the backend through its table (capture_backend.h)"
done
finish "render layout"
