#!/bin/sh
# GL state that the GL 4.5 tables give as 64-bit (GL_MAX_SHADER_STORAGE_BLOCK_SIZE,
# GL_MAX_ELEMENT_INDEX, GL_MAX_SERVER_WAIT_TIMEOUT, buffer sizes and offsets,
# ...) is read with a 64-bit getter (glGetInteger64v, glGetInteger64i_v,
# glGetNamedBufferParameteri64v): through a 32-bit one a driver that allows
# more than 2^31 bytes clamps, or truncates, the value (a wrong draw window,
# bindings cut short). Fails naming each file:line that reads one through
# glGetIntegerv, glGetIntegeri_v or glGet*BufferParameteriv.
# usage: test_gl_limits64.sh SOURCE_DIR [FOLDER...]
#          FOLDERs under SOURCE_DIR; default: view/render view/stream liboit tools
#        test_gl_limits64.sh --self-test TMP_DIR
#          plants one 32-bit read of each kind under TMP_DIR and checks that
#          every one is named, so that a pattern that stopped matching cannot
#          pass for clean sources.
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"

NAMES='GL_MAX_SHADER_STORAGE_BLOCK_SIZE|GL_MAX_UNIFORM_BLOCK_SIZE|GL_MAX_ELEMENT_INDEX'
NAMES="$NAMES|GL_MAX_SERVER_WAIT_TIMEOUT|GL_TIMESTAMP|GL_BUFFER_SIZE|GL_BUFFER_MAP_LENGTH"
NAMES="$NAMES|GL_BUFFER_MAP_OFFSET|GL_SHADER_STORAGE_BUFFER_SIZE|GL_SHADER_STORAGE_BUFFER_START"
NAMES="$NAMES|GL_UNIFORM_BUFFER_SIZE|GL_UNIFORM_BUFFER_START|GL_VERTEX_BINDING_OFFSET"
GETTERS='glGetIntegerv|glGetIntegeri_v|glGetBufferParameteriv|glGetNamedBufferParameteriv'

if [ "$1" = --self-test ]; then
    dir="$2/gl_limits64_selftest"
    rm -rf "$dir"
    mkdir -p "$dir/view/render"
    cat >"$dir/view/render/planted.c" <<'EOF'
void f(void)
{
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_SIZE, 8, &size);
    glGetNamedBufferParameteriv(buf, GL_BUFFER_SIZE, &bytes);
    glGetIntegerv( GL_MAX_ELEMENT_INDEX , &max_index);
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block); /* 64-bit: fine */
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align); /* 32-bit: fine */
}
EOF
    if out=$(sh "$0" "$dir" view/render 2>&1); then
        die "planted 32-bit reads passed: $out"
    fi
    for line in 3 4 5 6; do
        case $out in
        *"view/render/planted.c:$line:"*) ;;
        *) die "planted 32-bit read at view/render/planted.c:$line not named: $out" ;;
        esac
    done
    case $out in
    *"view/render/planted.c:7:"* | *"view/render/planted.c:8:"*) die "a fine read was reported: $out" ;;
    esac
    rm -rf "$dir"
    echo "ok: every planted 32-bit read is named"
    exit 0
fi

cd "$1"
shift
[ $# -gt 0 ] || set -- view/render view/stream liboit tools
for d in "$@"; do
    [ -d "$d" ] || die "no folder $d" # a moved folder must move here too
done

# One line at a time: a call that breaks before its pname is not seen.
hits=$(grep -rnE --include='*.c' --include='*.h' \
    -e "($GETTERS)[[:space:]]*\([^;]*($NAMES)([^A-Z_]|\$)" "$@" || true)
if [ -n "$hits" ]; then
    printf '%s\n' "$hits" |
        sed -e 's/^\([^:]*:[0-9]*\):[[:space:]]*\(.*\)/FAIL: \1: 64-bit GL state, 32-bit getter: \2/' \
            -e 's/$/ (use glGetInteger64v)/' >&2
    exit 1
fi
echo "ok: every 64-bit limit in $* is read as 64 bits"
