#!/bin/sh
# liboit.so exports exactly its public API: the dynamic symbols it defines are
# exactly the functions include/oit/ marks OIT_API (oit/export.h), and every
# function those installed headers declare is marked so (or static inline): a
# declaration liboit does not export is a link error for its caller. And
# it links only libc, pthreads, libm, libdl and the GL/EGL loaders (a viewer
# carries liboit with the system's GL alone): every NEEDED entry is on the
# allow list below; PNG, GLFW, zlib, meshoptimizer and the glTF plugin's C++
# stay out (docs/architecture.md). The headers spell colour one way and cite
# no file of the source tree (a user has the installed headers and
# part-file.md, not the tree).
# usage: test_liboit_exports.sh LIBOIT_SO INCLUDE_OIT_DIR [sanitize]
# sanitize: the build is instrumented; its sanitizer runtimes are allowed too.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
lib=$1
inc=$2
sanitize=${3:-}
temp_scratch liboit_exports
tmp=$T

declared() { # the oit_ function names declared OIT_API in the given headers
    grep -h '^OIT_API [a-z].*\boit_[a-z0-9_]*(' "$@" |
        sed 's/^[^(]*\b\(oit_[a-z0-9_]*\)(.*/\1/' | sort -u
}
declared "$inc"/*.h > "$tmp/public"
declared "$inc/liboit.h" "$inc/offscreen.h" > "$tmp/embedding"
# A line that starts a declaration of an oit_ function without OIT_API
# (static inline definitions and typedefs aside).
unmarked=$(grep -n '^[a-z].*\boit_[a-z0-9_]*(' "$inc"/*.h | grep -v -E ':(static|typedef) ' || true)
[ -z "$unmarked" ] ||
    die "functions declared in the installed headers without OIT_API (liboit does not export them: declare them in an internal header): $(echo "$unmarked" | cut -c1-600)"
[ -s "$tmp/embedding" ] || die "no function found in $inc/liboit.h and offscreen.h"
# One spelling across the public API: colour (the project's, and most of
# the headers'), never color, in any name (GL's own GL_*_COLOR* aside).
spelt=$(grep -n -E '[A-Za-z_]*(color|COLOR)[A-Za-z0-9_]*' "$inc"/*.h | grep -v -E 'GL_[A-Z0-9_]*COLOR' || true)
[ -z "$spelt" ] || die "the public API spells colour as color: $spelt"
# Source-tree paths in comments ("view/render/dfb.h", "docs/design.md"): say it in
# words or cite a public header (oit/*.h) or the installed part-file.md.
cited=$(grep -noE '[A-Za-z0-9_.-]*/[A-Za-z0-9_.-]+\.(c|h|cpp|md|map|sh|txt|py)\b|\b[A-Za-z0-9_-]+\.md\b' "$inc"/*.h |
    grep -v -E ':(oit/[a-z_]+\.h|part-file\.md)$' || true)
[ -z "$cited" ] || die "the installed headers cite files of the source tree: $(echo $cited | cut -c1-600)"
nm -D --defined-only "$lib" | awk '{print $NF}' | sed 's/@.*//' | sort -u > "$tmp/exported"
[ -s "$tmp/exported" ] || die "$lib exports nothing"

extra=$(comm -23 "$tmp/exported" "$tmp/public")
[ -z "$extra" ] || die "$lib exports $(echo "$extra" | wc -l) symbols not declared in $inc: $(echo $extra | cut -c1-400)"
missing=$(comm -23 "$tmp/embedding" "$tmp/exported")
[ -z "$missing" ] || die "$lib does not export these functions of liboit.h/offscreen.h: $missing"
unlinked=$(comm -23 "$tmp/public" "$tmp/exported")
[ -z "$unlinked" ] || die "$lib lacks these OIT_API functions (a caller would get a link error): $unlinked"

allowed() { # $1: a NEEDED name (libEGL.so.1)
    case $1 in
    libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | ld-linux*.so.*) return 0 ;;
    libEGL.so.* | libGL.so.* | libOpenGL.so.* | libGLdispatch.so.*) return 0 ;;
    libasan.so.* | libubsan.so.* | libclang_rt.asan*.so | libclang_rt.ubsan*.so)
        [ "$sanitize" = sanitize ] ;;
    *) return 1 ;;
    esac
}
readelf -d "$lib" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' > "$tmp/needed"
[ -s "$tmp/needed" ] || die "readelf -d $lib shows no NEEDED entry (not a shared library?)"
outside=""
while read -r so; do
    allowed "$so" || outside="$outside $so"
done < "$tmp/needed"
[ -z "$outside" ] || die "$lib links libraries outside the allow list (libc, libm, pthreads, \
libdl, the GL/EGL loaders):$outside; load them at run time (dlopen) or keep them in the tools"
echo "ok: $lib needs only $(tr "\n" " " < "$tmp/needed")"
echo "ok: $lib exports $(wc -l < "$tmp/exported") functions, all declared in $inc"
