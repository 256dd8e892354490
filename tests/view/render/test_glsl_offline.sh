#!/bin/sh
# A second compiler's verdict on every shader, without a GPU: glslang
# (Debian's glslang-tools) compiles every program the renderer can build,
# as GL would get it (tests/view/render/glsl_variants.c lists them through each
# module's oit_*_glsl_variants), so that a shader that llvmpipe accepts but
# the GLSL 4.50 spec does not fails here and not on a user's GPU.
#
# usage: test_glsl_offline.sh VARIANTS_EXE TMP_DIR
#          compiles every variant; fails naming each program glslang refuses
#        test_glsl_offline.sh --built VARIANTS_EXE TMP_DIR LOG
#          every program the suite built (LOG, OIT_GLSL_LOG's lines, one a
#          program built) is one of the variants: fails naming each that is
#          not, so a variant a module forgot to list cannot pass unchecked
#        test_glsl_offline.sh --self-test VARIANTS_EXE TMP_DIR
#          plants a program glslang must refuse and one the list lacks and
#          checks that both are caught
set -eu
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
command -v glslangValidator >/dev/null 2>&1 ||
    die "glslangValidator not found: install glslang-tools (setup/debian-packages.txt)"

# variants EXE DIR: the programs' stage files and index.txt into DIR.
variants() {
    rm -rf "$2" && mkdir -p "$2"
    "$1" "$2" >/dev/null || die "$1 $2 failed"
}

# compile DIR: a line per stage file glslang refuses, with the program's
# name and glslang's first errors.
compile() {
    for f in "$1"/*.vert "$1"/*.frag "$1"/*.comp; do
        [ -e "$f" ] || continue
        n=$(basename "$f" | cut -d. -f1)
        if ! out=$(glslangValidator "$f" 2>&1); then
            what=$(awk -v n="$n" '$1 == n { $1 = ""; $2 = ""; sub(/^  /, ""); print }' "$1/index.txt")
            echo "glslang refused $what ($f): $(printf '%s\n' "$out" | grep -m3 'ERROR' | tr '\n' ' ')"
        fi
    done
}

# unlisted DIR LOG: a line per hash in LOG that DIR's index lacks.
unlisted() {
    awk 'NR == FNR { known[$2] = 1; next } !($1 in known) && !seen[$1]++ {
        $0 = $0; h = $1; $1 = ""; print "built but in no oit_*_glsl_variants list:" $0 " (" h ")" }' \
        "$1/index.txt" "$2"
}

case ${1:-} in
--self-test)
    dir="$3/glsl_offline_selftest"
    variants "$2" "$dir"
    n=$(wc -l <"$dir/index.txt")
    [ "$n" -gt 0 ] || die "no variants listed"
    # a stage with an undeclared name, as a module's typo would be; the
    # stages but it and one sound one removed, so that this stays quick
    first=$(ls "$dir"/*.comp | head -n 1)
    sound=$(ls "$dir"/*.frag | head -n 1)
    for f in "$dir"/*.vert "$dir"/*.frag "$dir"/*.comp; do
        [ "$f" = "$first" ] || [ "$f" = "$sound" ] || rm -f "$f"
    done
    printf 'void oit_planted() { undeclared_name = 1; }\n' >>"$first"
    out=$(compile "$dir")
    case $out in *"glslang refused"*"$(basename "$first")"*) ;; *) die "planted error not caught: $out" ;; esac
    case $out in *"$(basename "$sound")"*) die "a sound stage was refused: $out" ;; esac
    # a program built that no list names
    printf '0123456789abcdef planted program\n' >"$dir/log"
    awk '{ print $2, "listed" }' "$dir/index.txt" >>"$dir/log"
    out=$(unlisted "$dir" "$dir/log")
    [ "$(printf '%s\n' "$out" | grep -c 'in no oit_')" = 1 ] || die "unlisted program: $out"
    case $out in *"planted program"*) ;; *) die "unlisted program not named: $out" ;; esac
    rm -rf "$dir"
    echo "ok: a refused stage and an unlisted program are both caught"
    ;;
--built)
    dir="$3/glsl_offline_built"
    variants "$2" "$dir"
    [ -s "$4" ] || die "$4: no program was logged (OIT_GLSL_LOG)"
    out=$(unlisted "$dir" "$4")
    [ -z "$out" ] || fail "$out"
    echo "ok: the $(sort -u "$4" | wc -l) programs the suite built are all listed"
    finish "glsl built"
    ;;
*)
    dir="$2/glsl_offline"
    variants "$1" "$dir"
    out=$(compile "$dir")
    [ -z "$out" ] || fail "$out"
    echo "ok: glslang compiled all $(wc -l <"$dir/index.txt") programs"
    finish "glsl offline"
    ;;
esac
