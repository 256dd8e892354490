#!/bin/sh
# What a one-image run costs, start-up included: the stream on a part file
# (oitstream FILE.oitp) against DFB on the source mesh (oitstream MESH
# --method dfb), whole-process wall clock and CPU time (user + system,
# /usr/bin/time), on the demo scene (oitgen demo, as demo.sh makes it) and
# a CAD part. Methods interleaved within each round (their order swapped
# every round), medians over ROUNDS rounds, llvmpipe's default threads.
#   cold: every run with an empty program cache (--program-cache, a fresh
#         folder) and an empty Mesa shader cache (MESA_SHADER_CACHE_DIR,
#         a fresh folder): a first run on a machine;
#   warm: both caches kept across runs (warmed by one run of each first).
# Usage: startup.sh BINDIR OUT.md   (env: ROUNDS, default 5; SIZE, default
#        1024x1024; CAD, default data_scripts/cache/turbine.off, 18,460
#        triangles, from fetch_meshes.sh)
set -eu
bin=$1 out=$2
rounds=${ROUNDS:-5} size=${SIZE:-1024x1024}
here=$(cd "$(dirname "$0")" && pwd)
cad=${CAD:-$here/cache/turbine.off}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
[ -f "$cad" ] || { echo "startup: no CAD part $cad (run fetch_meshes.sh or set CAD)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "startup: needs /usr/bin/time" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/t"
"$bin/oitgen" demo -o "$work/demo.ply" > /dev/null
"$bin/oitprep" "$work/demo.ply" -o "$work/demo.oitp" > /dev/null
cadname=$(basename "$cad")
"$bin/oitprep" "$cad" -o "$work/cad.oitp" > /dev/null
OIT_PROGRAM_CACHE=off "$bin/oitstream" "$work/cad.oitp" --size 64x64 --out "$work/r.png" \
    --stats "$work/r.json" --quiet
# A build before --program-cache runs without it (for a before/after).
has_pc=$("$bin/oitstream" --help 2>&1 | grep -c -- --program-cache || true)
renderer=$(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/r.json" | head -1)

# run SCENE METHOD CACHE: one process; appends "wall_ms cpu_ms" to
# $work/t/SCENE.METHOD.CACHE.
run() {
    scene=$1 method=$2 cache=$3
    case $scene in demo) mesh=$work/demo.ply ;; *) mesh=$cad ;; esac
    if [ "$cache" = cold ]; then
        rm -rf "$work/pc-cold" "$work/mesa-cold"
        pc=$work/pc-cold mesa=$work/mesa-cold
    else
        pc=$work/pc-warm mesa=$work/mesa-warm
    fi
    if [ "$method" = stream ]; then
        set -- "$work/$scene.oitp"
    else
        set -- "$mesh" --method dfb
    fi
    [ "$has_pc" = 0 ] || set -- "$@" --program-cache "$pc"
    t0=$(date +%s%N)
    MESA_SHADER_CACHE_DIR=$mesa /usr/bin/time -f "%U %S" -o "$work/time" \
        "$bin/oitstream" "$@" --size "$size" \
        --out "$work/$scene.$method.png" --quiet
    t1=$(date +%s%N)
    cpu=$(awk '{printf "%.0f", ($1 + $2) * 1000}' "$work/time")
    echo "$(( (t1 - t0) / 1000000 )) $cpu" >> "$work/t/$scene.$method.$cache"
}

for scene in demo cad; do
    for method in stream dfb; do run $scene $method warm; done
    rm -f "$work/t/$scene".*.warm
done
i=0
while [ $i -lt "$rounds" ]; do
    for scene in demo cad; do
        for cache in cold warm; do
            if [ $((i % 2)) -eq 0 ]; then
                run $scene stream $cache; run $scene dfb $cache
            else
                run $scene dfb $cache; run $scene stream $cache
            fi
        done
    done
    i=$((i + 1))
done

# median FILE COLUMN
median() {
    cut -d' ' -f"$2" "$1" | sort -n | awk '{v[NR] = $1} END {
        if (NR % 2) print v[(NR + 1) / 2]; else printf "%.0f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

{
    echo "# One-image runs: stream vs DFB, start-up included"
    echo
    echo "\`data_scripts/startup.sh $bin OUT.md\` (ROUNDS=$rounds, SIZE=$size) on" \
        "$(date -u +%Y-%m-%d), $(nproc) cores, load average at the end:" \
        "$(cut -d' ' -f1-3 /proc/loadavg)."
    echo "Renderer: $renderer."
    echo "Stream: \`oitstream FILE.oitp --size $size\`; DFB: \`oitstream MESH --method dfb\`;"
    if [ "$has_pc" = 0 ]; then
        echo "this build has no \`--program-cache\`; cold: an empty Mesa shader cache, warm: kept."
    else
        echo "both with \`--program-cache\` (cold: empty, with an empty Mesa shader cache;"
        echo "warm: kept)."
    fi
    echo "Wall and CPU (user + system) of the whole process, medians of $rounds."
    echo
    echo "| scene | caches | stream wall ms | DFB wall ms | wall ratio | stream CPU ms | DFB CPU ms | CPU ratio |"
    echo "|---|---|---|---|---|---|---|---|"
    for scene in demo cad; do
        name=$([ $scene = demo ] && echo "demo (oitgen demo)" || echo "$cadname")
        for cache in cold warm; do
            t=$work/t/$scene
            sw=$(median "$t.stream.$cache" 1) dw=$(median "$t.dfb.$cache" 1)
            sc=$(median "$t.stream.$cache" 2) dc=$(median "$t.dfb.$cache" 2)
            echo "| $name | $cache | $sw | $dw | $(ratio "$sw" "$dw") | $sc | $dc | $(ratio "$sc" "$dc") |"
        done
    done
    echo
    echo "Every run (wall ms, CPU ms), in order:"
    echo
    for f in "$work"/t/*; do
        echo "- $(basename "$f"): $(tr '\n' ';' < "$f" | sed 's/;$//; s/;/; /g')"
    done
} > "$out"
cat "$out"
