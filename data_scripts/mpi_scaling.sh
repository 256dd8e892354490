#!/bin/sh
# Sort-last scaling of oitstream-mpi (issue 38): plants converted by oitprep,
# rendered with 1, 2, 4 (RANKS) ranks on this machine, each rank's share
# (triangles), its render ms, IceT's compositing ms and bytes exchanged,
# averaged over the orbit's frames after the first (cold) one; peak host
# and GPU memory per rank (the largest over ranks and frames of the stats'
# host_peak_bytes, getrusage's maximum RSS, and gpu_peak_bytes).
# Writes a Markdown table to OUT (default bench/tmp/mpi-scaling.md).
#
# Usage: data_scripts/mpi_scaling.sh [BINDIR] [OUT]
# Knobs: MPI_MODELS="1000000 12000000 50000000" (plant triangles; 50M only
#        when the machine has 64 GB: MPI_50M=1 forces it), RANKS="1 2 4",
#        MPI_SIZE=1024x1024, MPI_VIEWS=4, LP_NUM_THREADS (llvmpipe threads a
#        rank; stated in the table), MPI_WORK (where the plants are kept).
# Heavy: the 12M plant converts in minutes and renders seconds a frame on
# llvmpipe; do not run it on a shared machine.
set -eu
bin=${1:-build/bin} out=${2:-bench/tmp/mpi-scaling.md}
here=$(cd "$(dirname "$0")" && pwd)
size=${MPI_SIZE:-1024x1024} views=${MPI_VIEWS:-4} ranks=${RANKS:-1 2 4}
work=${MPI_WORK:-/tmp/mpi_scaling}
mem_gb=$(awk '/MemTotal/ { print int($2 / 1048576) }' /proc/meminfo)
models=${MPI_MODELS:-1000000 12000000}
if [ -z "${MPI_MODELS:-}" ] && { [ "$mem_gb" -ge 64 ] || [ "${MPI_50M:-0}" = 1 ]; }; then
    models="$models 50000000"
fi
[ -x "$bin/oitstream-mpi" ] || { echo "mpi_scaling: $bin/oitstream-mpi not built" >&2; exit 2; }
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
export OMPI_MCA_btl=self,vader OMPI_MCA_hwloc_base_binding_policy=none
root=""
[ "$(id -u)" -eq 0 ] && root=--allow-run-as-root
mkdir -p "$work" "$(dirname "$out")"
{
    echo "| plant | ranks | LP_NUM_THREADS | frame ms | composite ms | MiB exchanged | shares (triangles) | rank ms | peak host MiB a rank | peak GPU MiB a rank |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
} >"$out"
for n in $models; do
    pf="$work/plant$n.oitp"
    if [ ! -f "$pf" ]; then
        "$bin/oitgen" plant --triangles "$n" -o "$work/plant$n.ply" >/dev/null
        "$bin/oitprep" "$work/plant$n.ply" -o "$pf" >/dev/null
        rm -f "$work/plant$n.ply"
    fi
    for np in $ranks; do
        js="$work/plant$n-$np.json"
        # shellcheck disable=SC2086
        mpirun $root --oversubscribe -np "$np" \
            "$bin/oitstream-mpi" "$pf" --size "$size" --orbit "$views" --stats "$js" --quiet
        python3 - "$js" "$n" "$np" "${LP_NUM_THREADS:-default}" >>"$out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
fr = d["frames"][1:] or d["frames"]
avg = lambda xs: sum(xs) / len(xs)
ranks = d["ranks"]
shares = " / ".join(str(r["triangles"]) for r in fr[0]["ranks"])
rank_ms = " / ".join("%.0f" % avg([f["ranks"][k]["ms"] for f in fr]) for k in range(ranks))
peak = lambda key: max(k[key] for f in d["frames"] for k in f["ranks"]) / 2**20
print("| %s | %d | %s | %.0f | %.1f | %.1f | %s | %s | %.0f | %.0f |" % (
    sys.argv[2], ranks, sys.argv[4], avg([f["ms"] for f in fr]),
    avg([f["composite_ms"] for f in fr]), avg([f["bytes_exchanged"] for f in fr]) / 2**20,
    shares, rank_ms, peak("host_peak_bytes"), peak("gpu_peak_bytes")))
PY
    done
done
echo "mpi_scaling: $out"
