#!/bin/sh
# Binding points and locations are named, never numbered
# (view/render/gl/glsl_bindings.h, glsl_locations.h): a GLSL layout(binding = N)
# or layout(location = N), a glBindBufferBase(..., N, ...) or a
# glProgramUniform*(prog, N, ...) with a number for N agrees with the other
# side only until someone renumbers the list. Fails naming each file:line,
# of the C sources and the GLSL files (view/render/*/glsl/*.glsl), that spells a
# storage binding, texture unit, image unit or location as a number.
# usage: test_glsl_bindings.sh SOURCE_DIR [FOLDER...]
#          FOLDERs under SOURCE_DIR; default: view/render tests liboit
#        test_glsl_bindings.sh --self-test TMP_DIR
#          plants one literal of each kind under TMP_DIR and checks that
#          every one is named, so that a pattern that stopped matching
#          cannot pass for clean sources.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"

if [ "$1" = --self-test ]; then
    dir="$2/glsl_bindings_selftest"
    rm -rf "$dir"
    mkdir -p "$dir/view/render"
    # digits through variables: a grep of the tree for numeric GLSL
    # bindings (binding = digit) then finds none in this script
    three=3 zero=0 two=2
    mkdir -p "$dir/view/render/glsl"
    cat >"$dir/view/render/glsl/planted.glsl" <<EOF
layout(std430, binding = $three) buffer Frags { uvec4 frags[]; };
layout(location = $two) uniform int u_k;
layout(location = OIT_LOC_K) uniform int u_named;
EOF
    cat >"$dir/view/render/planted.c" <<EOF
static const char fs[] =
    "layout(std430, binding = $three) buffer Frags { uvec4 frags[]; };\n"
    "layout(rgba32f, binding=$zero) writeonly uniform image2D u_out;\n";
void f(void)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buf);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, buf, 0, 16);
    glBindImageTexture(0, tex, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindTextureUnit(1, tex);
    glBindSampler(7, sampler);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, buf); /* named: fine */
    glProgramUniform1i(prog, $two, 1);
    glProgramUniform1i(prog, OIT_LOC_K, 1); /* named: fine */
}
EOF
    if out=$(sh "$0" "$dir" view/render 2>&1); then
        die "planted literals passed: $out"
    fi
    for at in planted.c:2 planted.c:3 planted.c:6 planted.c:7 planted.c:8 planted.c:9 \
        planted.c:10 planted.c:12 glsl/planted.glsl:1 glsl/planted.glsl:2; do
        case $out in
        *"view/render/$at:"*) ;;
        *) die "planted literal at view/render/$at not named: $out" ;;
        esac
    done
    case $out in
    *"view/render/planted.c:11:"* | *"view/render/planted.c:13:"* | *"planted.glsl:3:"*)
        die "a named binding or location was reported: $out" ;;
    esac
    rm -rf "$dir"
    echo "ok: every planted literal is named"
    exit 0
fi

cd "$1"
shift
[ $# -gt 0 ] || set -- view/render tests liboit
for d in "$@"; do
    [ -d "$d" ] || die "no folder $d" # a moved folder must move here too
done

# GLSL: layout(..., binding = N). C: the index argument of the calls that
# bind by number (the first, or the second after the target). One line at a
# time: a call that breaks before its index is not seen.
# Locations too, but not in tests/: a test's own shaders stand for a
# caller's program (its viewer's), whose locations are its own.
located=$(for d in "$@"; do case $d in tests | tests/*) ;; *) echo "$d" ;; esac; done)
hits=$({
    # shellcheck disable=SC2086
    [ -z "$located" ] || grep -rnE --include='*.c' --include='*.h' --include='*.glsl' \
        -e 'location[[:space:]]*=[[:space:]]*[0-9]' \
        -e 'glProgramUniform[[:alnum:]]*[[:space:]]*\([^,]*,[[:space:]]*[0-9]' $located || true
    grep -rnE --include='*.c' --include='*.h' --include='*.glsl' \
    -e 'binding[[:space:]]*=[[:space:]]*[0-9]' \
    -e '(glBindBufferBase|glBindBufferRange)[[:space:]]*\([^,]*,[[:space:]]*[0-9]' \
    -e '(glBindImageTexture|glBindTextureUnit|glBindSampler)[[:space:]]*\([[:space:]]*[0-9]' \
    "$@" || true
})
if [ -n "$hits" ]; then
    printf '%s\n' "$hits" | sed 's/^\([^:]*:[0-9]*\):[[:space:]]*\(.*\)/FAIL: \1: a binding point or location as a number (name it in view\/render\/gl\/glsl_bindings.h or glsl_locations.h): \2/' >&2
    exit 1
fi
echo "ok: no numeric binding point or location in $*"
