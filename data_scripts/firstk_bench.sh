#!/bin/sh
# --pack first-k against --pack counted and DFB on the source mesh, warm
# frames (bench/firstk-llvmpipe.md).
# Usage: data_scripts/firstk_bench.sh BIN OUT ROUNDS NAME MESH FILE.oitp
#   4 orbit views of FILE.oitp, each rendered twice in a row (--walk), at
#   1024x1024; per round the methods run interleaved. Prints, per method,
#   the warm frames' ms per view (median over rounds), their mean, and the
#   first round's second_pass_pixels / second_pass_packs per view.
set -u
[ $# -eq 6 ] || { echo "usage: $0 BIN OUT ROUNDS NAME MESH FILE.oitp" >&2; exit 2; }
B=$1/oitstream O=$2 R=$3 N=$4 SRC=$5 P=$6
mkdir -p "$O" || exit 1
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
"$B" "$P" --size 64x64 --orbit 4 --stats "$O/${N}_views.json" --quiet || exit 1
sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$O/${N}_views.json" | awk '{print; print}' > "$O/${N}_walk.txt"
run() { # TAG ARGS...
    tag=$1; shift
    nice -n 10 "$B" "$@" --size 1024x1024 --walk "$O/${N}_walk.txt" --quiet \
        --stats "$O/${N}_${tag}_$r.json" --out "$O/${N}_${tag}_$r/" || echo "$N $tag: exited $?" >&2
}
for r in $(seq 1 "$R"); do
    run firstk "$P" --pack first-k
    run counted "$P" --pack counted
    run dfb "$SRC" --method dfb
    run firstk128 "$P" --pack first-k --slot-budget 128M
done
for tag in counted firstk firstk128 dfb; do
    for r in $(seq 1 "$R"); do
        grep -o '"ms": [0-9.]*' "$O/${N}_${tag}_$r.json" | sed 's/.*: //' | awk 'NR % 2 == 0' |
            tr '\n' ' '; echo
    done | awk -v t="$tag" -v n="$N" '
        {for (v = 1; v <= NF; v++) ms[v, NR] = $v; views = NF; rounds = NR}
        END {printf "%s %-9s", n, t; s = 0
             for (v = 1; v <= views; v++) {
                 k = 0; for (i = 1; i <= rounds; i++) a[++k] = ms[v, i]
                 for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (a[j] < a[i]) {x = a[i]; a[i] = a[j]; a[j] = x}
                 m = k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
                 printf " %7.1f", m; s += m}
             printf "  mean %7.1f ms\n", s / views}'
    for k in second_pass_pixels second_pass_packs; do
        printf '    %s:' $k
        grep -o "\"$k\": [0-9]*" "$O/${N}_${tag}_1.json" | sed 's/.*: //' | awk 'NR % 2 == 0' | tr '\n' ' '
        echo
    done
done
