#!/bin/sh
# liboit.so exports exactly its public API: the dynamic symbols it defines are
# exactly the functions include/oit/ marks OIT_API (oit/export.h), and every
# function of liboit.h and offscreen.h (the embedding API) is among them.
# usage: test_liboit_exports.sh LIBOIT_SO INCLUDE_OIT_DIR
set -eu
lib=$1
inc=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

declared() { # the oit_ function names declared OIT_API in the given headers
    grep -h '^OIT_API [a-z].*\boit_[a-z0-9_]*(' "$@" |
        sed 's/^[^(]*\b\(oit_[a-z0-9_]*\)(.*/\1/' | sort -u
}
declared "$inc"/*.h > "$tmp/public"
declared "$inc/liboit.h" "$inc/offscreen.h" > "$tmp/embedding"
[ "$(grep -c '^[a-z].*\boit_[a-z0-9_]*(' "$inc/liboit.h" "$inc/offscreen.h" | awk -F: '{n += $2} END {print n}')" = 0 ] ||
    fail "a function of liboit.h/offscreen.h is not marked OIT_API"
[ -s "$tmp/embedding" ] || fail "no function found in $inc/liboit.h and offscreen.h"
nm -D --defined-only "$lib" | awk '{print $NF}' | sed 's/@.*//' | sort -u > "$tmp/exported"
[ -s "$tmp/exported" ] || fail "$lib exports nothing"

extra=$(comm -23 "$tmp/exported" "$tmp/public")
[ -z "$extra" ] || fail "$lib exports $(echo "$extra" | wc -l) symbols not declared in $inc: $(echo $extra | cut -c1-400)"
missing=$(comm -23 "$tmp/embedding" "$tmp/exported")
[ -z "$missing" ] || fail "$lib does not export these functions of liboit.h/offscreen.h: $missing"
unlinked=$(comm -23 "$tmp/public" "$tmp/exported")
[ -z "$unlinked" ] || fail "$lib lacks these OIT_API functions (a caller would get a link error): $unlinked"
echo "ok: $lib exports $(wc -l < "$tmp/exported") functions, all declared in $inc"
