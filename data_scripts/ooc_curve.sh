#!/bin/sh
# Issue 35's out-of-core curve: one part file streamed with its geometry
# held to 1/1, 1/2, 1/4 and 1/8 of its decoded size, against DFB in core on
# the same views, beside the host-to-device rate measured in the same run.
#
# Per budget fraction f (D: the file's decoded part bytes, what the stream
# would keep resident; S: the capture's slot budget, 64M; ST: its fragment
# store budget, 256M (both their defaults); P: the frame's per-pixel
# buffers, W*H*80 bytes):
#   f = 1:  --upload-budget D --cache-budget D (resident: read once)
#   f < 1:  --upload-budget R --cache-budget f*D - R, R = min(64M, f*D/4),
#           at least the largest part the fast scheme makes (128K triangles);
#           where that leaves no cache: the ring alone, geometry = R
#   always: --slot-budget S --store-budget ST --gpu-budget f*D + S + ST + P
#   (the total bounds all)
# Columns: frame ms and gpu_ms (medians of the warm frames: each view of
# the walk is drawn twice, cold then warm, as stream_vs_dfb.sh does), the
# stream against DFB (ms and gpu_ms), MB uploaded a warm frame, upload GB/s
# (bytes uploaded over the warm frames' wall ms), GPU MB at peak (the
# streamer's own count) against the --gpu-budget, and whether the peak stayed
# inside it. Beside them, `oitbench bus`: glNamedBufferSubData and the
# streamer's mapped-buffer copy, GB/s on the GPU clock and on the wall.
#
# Usage: data_scripts/ooc_curve.sh [BINDIR] [OUT.md] [WxH] [MODEL]
#   defaults: build/bin, bench/ooc-curve-RENDERER.md, 1024x1024, 12000000
#   MODEL: a plant's triangle count (`oitgen plant --triangles N`, converted
#   with oitprep's defaults, both kept in OOC_CACHE so later runs skip them),
#   or a part file FILE.oitp with its source mesh beside it as FILE.ply (DFB
#   draws the mesh).
# Knobs (environment):
#   OOC_CACHE=DIR        where plants and their part files are kept
#                        (default data_scripts/cache/ooc)
#   OOC_VIEWS=N          views of the orbit (default 3)
#   OOC_FRACTIONS="1 2 4 8"  the budgets, as denominators of D
#   OOC_BUS_BYTES=B      bytes of the bus measurement (default 256M)
#   OOC_STREAM_ARGS="--capture compute"  more oitstream options for the
#                        stream's runs (not DFB's), named in the report
# The 12M plant: ~0.6 GB decoded; its conversion takes minutes and 1.3 GB of
# disk; on llvmpipe a frame takes tens of seconds: try `... 512x512 1000000`.
set -eu
bin=${1:-build/bin} size=${3:-1024x1024} model=${4:-12000000}
here=$(cd "$(dirname "$0")" && pwd)
ooc=${OOC_CACHE:-$here/cache/ooc}
views=${OOC_VIEWS:-3}
fractions=${OOC_FRACTIONS:-1 2 4 8}
bus_bytes=${OOC_BUS_BYTES:-256M}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
cmdline="$0 $*"

die() { echo "ooc_curve: $*" >&2; exit 1; }
case $size in *x*) ;; *) die "size '$size': expected WxH" ;; esac
w=${size%x*} h=${size#*x}
for t in oitgen oitprep oitstream oitbench; do
    [ -x "$bin/$t" ] || die "$bin/$t: missing (build with: make build)"
done
command -v python3 >/dev/null || die "python3: missing (reads the --stats files)"
work=$(mktemp -d /tmp/ooc_curve.XXXXXX) || die "mktemp failed"
trap 'rm -rf "$work"' EXIT

# ---- the model -----------------------------------------------------------
case $model in
*.oitp)
    parts=$model mesh=${model%.oitp}.ply
    [ -f "$parts" ] || die "$parts: missing"
    [ -f "$mesh" ] || die "$mesh: the source mesh DFB draws is missing (FILE.ply beside FILE.oitp)"
    name=$(basename "$parts" .oitp) ;;
*[!0-9]*|'') die "model '$model': a triangle count or a FILE.oitp" ;;
*)
    name=plant$model
    mkdir -p "$ooc" || die "$ooc: cannot create"
    mesh=$ooc/$name.ply parts=$ooc/$name.oitp
    if [ ! -s "$mesh" ]; then
        echo "ooc_curve: oitgen plant --triangles $model" >&2
        "$bin/oitgen" plant --triangles "$model" -o "$mesh.tmp" >/dev/null || die "oitgen failed"
        mv "$mesh.tmp" "$mesh"
    fi
    if [ ! -s "$parts" ]; then
        echo "ooc_curve: oitprep $mesh" >&2
        "$bin/oitprep" "$mesh" -o "$parts.tmp.oitp" >/dev/null || die "oitprep failed"
        mv "$parts.tmp.oitp" "$parts"
    fi ;;
esac

# ---- the views: an orbit of the mesh, each view twice (cold, warm) ---------
"$bin/oitstream" "$mesh" --method unsorted --orbit "$views" --size 16x16 --quiet \
    --stats "$work/v.json" >/dev/null || die "$mesh: the orbit's views"
sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | awk '{ print; print }' >"$work/walk.txt"
[ "$(wc -l <"$work/walk.txt")" = $((2 * views)) ] || die "the walk has not $((2 * views)) views"

# D: the bytes the stream keeps resident when everything fits (a budget far
# past the file, one small frame).
"$bin/oitstream" "$parts" --method stream --size 16x16 --orbit 2 --gpu-budget 512G --quiet \
    --stats "$work/d.json" >/dev/null || die "$parts: cannot stream"
D=$(python3 -c "import json,sys; b=json.load(open(sys.argv[1]))['budget']; \
assert b['resident'], b; print(b['ring'])" "$work/d.json") || die "$parts: decoded size"

"$bin/oitprep" info "$parts" --json >"$work/info.json" || die "$parts: oitprep info failed"

# ---- the bus, then DFB and the stream at each budget ---------------------
"$bin/oitbench" bus --bytes "$bus_bytes" >"$work/bus.json" || die "oitbench bus failed"
render() { # render FILE STATS [options]: the walk at the size, --stats STATS
    _f=$1 _s=$2 && shift 2
    "$bin/oitstream" "$_f" --walk "$work/walk.txt" --size "$size" --quiet --stats "$_s" "$@" \
        >/dev/null || die "$_f $*: render failed"
}
echo "ooc_curve: DFB in core on $name" >&2
render "$mesh" "$work/dfb.json" --method dfb
S=$((64 << 20)) ST=$((256 << 20)) P=$((w * h * 80))
# The ring holds a part whole: the largest oitprep's fast scheme makes
# (--part-triangles, default 128K) at the file's bytes a triangle.
tris=$(python3 -c "import json,sys; print(json.load(sys.stdin)['triangles'])" \
    <"$work/info.json") || die "$parts: oitprep info"
big=$((D / tris * 131072 + 65536))
big=$((big > D ? D : big))
for q in $fractions; do
    g=$((D / q))
    if [ "$q" = 1 ]; then
        r=$D c=$D
    else
        r=$((g / 4 < (64 << 20) ? g / 4 : (64 << 20)))
        r=$((r < big ? big : r)) c=$((g - r))
        # a budget no larger than a part: the ring alone, no cache
        [ "$c" -ge 65536 ] || c=off g=$r
    fi
    total=$((g + S + ST + P))
    [ "$c" != off ] || total=$((r + S + ST + P))
    echo "ooc_curve: stream at 1/$q of $D bytes (--gpu-budget $total)" >&2
    # shellcheck disable=SC2086 # OOC_STREAM_ARGS: words on purpose
    render "$parts" "$work/s$q.json" --method stream --slot-budget "$S" --store-budget "$ST" --upload-budget "$r" \
        --cache-budget "$c" --gpu-budget "$total" ${OOC_STREAM_ARGS:-}
    echo "$q $g $total" >>"$work/budgets.txt"
done

# ---- report ----------------------------------------------------------------
out=${2:-}
python3 - "$work" "$D" "$name" "$size" "$cmdline" "$out" "$here" "${OOC_STREAM_ARGS:-}" <<'PY'
import json, os, statistics, subprocess, sys, time
work, D, name, size, cmdline, out, here, extra = sys.argv[1:9]
D = int(D)
def load(p): return json.load(open(os.path.join(work, p)))
def warm(frames, key):
    v = [f[key] for i, f in enumerate(frames) if i % 2 == 1 and f.get(key, -1) >= 0]
    return statistics.median(v) if v else -1.0
dfb, bus = load("dfb.json"), load("bus.json")
renderer = dfb["renderer"]
tag = "".join(c if c.isalnum() else "-" for c in renderer.lower()).strip("-")
while "--" in tag: tag = tag.replace("--", "-")
out = out or os.path.join("bench", "ooc-curve-%s.md" % tag[:40])
d_ms, d_gpu = warm(dfb["frames"], "ms"), warm(dfb["frames"], "gpu_ms")
try:
    commit = subprocess.run(["git", "-C", here, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "?"
except OSError:
    commit = "?"
fmt = lambda x, d=1: "-" if x is None or x < 0 else "%.*f" % (d, x)
rows = []
for line in open(os.path.join(work, "budgets.txt")):
    q, g, total = map(int, line.split())
    s = load("s%d.json" % q)
    fr = s["frames"]
    w = [f for i, f in enumerate(fr) if i % 2 == 1]
    ms, gpu = warm(fr, "ms"), warm(fr, "gpu_ms")
    up = sum(f["bytes_uploaded"] for f in w)
    wall = sum(f["ms"] for f in w)
    peak = max(f["gpu_bytes_peak"] for f in fr)
    rows.append("| 1/%d | %.1f | %.1f | %s | %s | %s | %s | %.1f | %s | %.1f | %s |" % (
        q, g / 1e6, total / 1e6, fmt(ms), fmt(gpu), fmt(ms / d_ms if d_ms > 0 else -1, 2),
        fmt(gpu / d_gpu if gpu > 0 and d_gpu > 0 else -1, 2), up / len(w) / 1e6 if w else 0,
        fmt(up / (wall * 1e6) if wall > 0 else -1, 4), peak / 1e6,
        "yes" if peak <= total else "**no**"))
with open(out, "w") as f:
    p = lambda *a: print(*a, file=f)
    p("# Out-of-core curve on %s" % renderer)
    p()
    p("`%s` at %s, %s, %d cores; %s, %s, %d views of an orbit, each drawn cold then warm; "
      "medians of the warm frames." % (cmdline, commit, time.strftime("%Y-%m-%d", time.gmtime()),
                                      os.cpu_count(), name, size, len(dfb["frames"]) // 2))
    p()
    p("Decoded part bytes D = %.1f MB. GPU time: %s (gpu_ms spans the frame's first to last "
      "timestamp, readback included)." % (D / 1e6, dfb.get("gpu_timer", "?")))
    p()
    p("Host to device (`oitbench bus`, %d MB, median of %d): glNamedBufferSubData %s GB/s on the "
      "GPU clock, %s GB/s on the wall; mapped-buffer copy (the streamer's path) %s GPU, %s wall."
      % (bus["bytes"] / 1e6, bus["repeat"], fmt(bus["subdata_gpu_gbps"], 2),
         fmt(bus["subdata_wall_gbps"], 2), fmt(bus["mapped_copy_gpu_gbps"], 2),
         fmt(bus["mapped_copy_wall_gbps"], 2)))
    if bus["subdata_gpu_gbps"] > 100 * max(bus["subdata_wall_gbps"], 1e-9):
        p()
        p("The GPU clock did not see the copies (%s GB/s): this driver copies buffers in the "
          "calling thread, outside its timer (llvmpipe does); the wall figures are the rate."
          % fmt(bus["subdata_gpu_gbps"], 0))
    p()
    p("DFB in core on the source mesh: %s ms, gpu %s ms." % (fmt(d_ms), fmt(d_gpu)))
    if extra:
        p()
        p("The stream's runs add `%s` (OOC_STREAM_ARGS)." % extra)
    p()
    p("| budget | geometry MB | --gpu-budget MB | ms | gpu_ms | ms / DFB | gpu / DFB | "
      "MB uploaded a warm frame | upload GB/s (wall) | GPU MB at peak | peak inside |")
    p("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows: p(r)
print("ooc_curve: wrote", out)
PY
