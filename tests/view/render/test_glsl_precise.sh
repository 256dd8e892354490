#!/bin/sh
# The tie rule's key must round on the GPU as it does on the CPU (shade.c,
# reference.c): a GPU compiler may fuse a multiply and an add into one
# rounding, or reassociate, unless the result is `precise` (GLSL 4.50
# 4.7.1); llvmpipe happens not to, so only the source can show it. Checks
# that the GLSL key function (view/render/gl/glsl/fragment_key.glsl,
# oit_depth_key) and the plane's rotation (tie_plane.glsl, oit_tie_plane) use no built-in whose operation order is the
# driver's (normalize, dot, length, a matrix product) and spell their
# arithmetic as precise.
# usage: test_glsl_precise.sh SOURCE_DIR | --self-test TMP_DIR
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"

# body FILE START: the GLSL lines of the function whose header contains
# START, up to its closing brace line.
body() {
    awk -v start="$2" 'index($0, start) { on = 1 } on { print } on && /^}/ { exit }' "$1"
}

# check KEY_FILE PLANE_FILE: prints one line per offence.
check() {
    key=$(body "$1" 'uint oit_depth_key(float t_interp)')
    plane=$(body "$2" 'vec4 oit_tie_plane(')
    [ -n "$key" ] || echo "oit_depth_key: not found"
    [ -n "$plane" ] || echo "oit_tie_plane: not found"
    echo "$key" | grep -n 'normalize(\|dot(\|length(\|distance(\|fma(' |
        sed 's/^/oit_depth_key: a built-in of the driver'"'"'s order: /'
    echo "$plane" | grep -n 'mat3(u_view) \*\|dot(v\|normalize(' |
        sed 's/^/oit_tie_plane: a built-in of the driver'"'"'s order: /'
    # Every float line with * or / in the key is precise (declared or
    # assigned to a precise variable: dir).
    echo "$key" | grep -n '[*/] ' | grep -v 'precise\|dir = dir \*\|//' |
        sed 's/^/oit_depth_key: arithmetic outside precise: /'
    [ "$(echo "$key" | grep -c 'precise')" -ge 4 ] ||
        echo "oit_depth_key: fewer than 4 precise declarations"
    echo "$plane" | grep -q '^    precise vec3' || echo "oit_tie_plane: no precise rotation"
}

if [ "${1:-}" = --self-test ]; then
    dir="$2/glsl_precise_selftest"
    mkdir -p "$dir"
    src=$(dirname "$0")/../../../view/render/gl/glsl
    # The key as it was before precise: dot and normalize, fused freely.
    sed 's/^    precise float nd = n.x \* dir.x + n.y \* dir.y + n.z \* dir.z;/    float nd = dot(n, dir);/' \
        "$src/fragment_key.glsl" >"$dir/planted.glsl"
    cmp -s "$src/fragment_key.glsl" "$dir/planted.glsl" && fail "the planted edit did not apply"
    out=$(check "$dir/planted.glsl" "$src/tie_plane.glsl")
    [ -n "$out" ] || fail "a key with dot() passed"
    echo "$out" | grep -q 'dot(' || fail "planted dot() not named: $out"
    sed 's/^    precise vec3 r;/    vec3 r;/' "$src/tie_plane.glsl" >"$dir/planted2.glsl"
    check "$src/fragment_key.glsl" "$dir/planted2.glsl" | grep -q 'oit_tie_plane: no precise' ||
        fail "a rotation without precise passed"
    finish "glsl precise self-test"
fi

out=$(check "$1/view/render/gl/glsl/fragment_key.glsl" "$1/view/render/gl/glsl/tie_plane.glsl")
[ -z "$out" ] || fail "$out"
finish "glsl precise"
