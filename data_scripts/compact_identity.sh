#!/bin/sh
# Part file version 4 against version 5 (encoded, vertex-cache-ordered
# parts): each model converted by both builds' oitprep, rendered by each
# build's oitstream (exact stream, default method) from the same views into
# float PFMs, and the PFMs compared byte for byte (cmp). Any difference
# fails the script.
#
# Usage: data_scripts/compact_identity.sh BIN_V4 BIN_V5 [SCHEME] [MODEL|hard:CASE|demo]...
# SCHEME: fast (oitprep's default) or guaranteed.
set -eu
a=$(cd "$1" && pwd) b=$(cd "$2" && pwd) scheme=$3
shift 3
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
export EGL_PLATFORM=surfaceless
views="0,20 135,20 250,-30"
status=0
for m in "$@"; do
    name=$(basename "$m" | tr ':.' '__')
    case "$m" in
    demo) "$b/oitgen" demo -o "$work/$name.ply" >/dev/null; src="$work/$name.ply" ;;
    hard:*) "$b/oitgen" hard --case "${m#hard:}" -o "$work/$name.ply" >/dev/null
        src="$work/$name.ply" ;;
    *) src="$here/data_scripts/cache/$m" ;;
    esac
    for v in 4 5; do
        bin=$a; [ $v = 5 ] && bin=$b
        "$bin/oitprep" "$src" -o "$work/$name.v$v.oitp" --scheme "$scheme" >/dev/null 2>&1
    done
    for view in $views; do
        az=${view%,*} el=${view#*,}
        for v in 4 5; do
            bin=$a; [ $v = 5 ] && bin=$b
            "$bin/oitstream" "$work/$name.v$v.oitp" --size 256x256 --azimuth "$az" \
                --elevation "$el" --out "$work/$name.$az.v$v.pfm" --quiet \
                2>"$work/$name.$az.v$v.err" || echo "exit $?" >>"$work/$name.$az.v$v.err"
        done
        if [ -s "$work/$name.$az.v4.err" ] || [ -s "$work/$name.$az.v5.err" ]; then
            r="not rendered (v4: $(tail -n 1 "$work/$name.$az.v4.err" | sed 's/.*: //'); v5: $(tail -n 1 "$work/$name.$az.v5.err" | sed 's/.*: //'))"
            status=1
        elif cmp -s "$work/$name.$az.v4.pfm" "$work/$name.$az.v5.pfm"; then r=identical; else
            r=DIFFERENT; status=1; fi
        echo "$scheme $m azimuth $az elevation $el: v4 $(stat -c %s "$work/$name.v4.oitp") bytes, v5 $(stat -c %s "$work/$name.v5.oitp") bytes: PFMs $r"
    done
done
exit $status
