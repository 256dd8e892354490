#!/bin/sh
# Issue 39's figures: the compute capture (oitstream --method compute in
# core, --capture compute streamed) against DFB on the source mesh, on the
# same views: exactness on every frame and the warm frames' time.
#
# Per model: an orbit of V views, each drawn twice (cold, then warm); DFB,
# the compute capture in core and the stream with --capture compute each
# render the walk. Every frame is compared with DFB's: the share of pixels
# with a channel off by more than 1/255, over the whole frame and outside
# the edge mask (the Embree reference's --ambiguity mask: pixels whose hit
# set changes within 1/64 pixel of the centre, where two fill rules may
# legitimately disagree; models of at most COMPUTE_MASK_MAX triangles). A
# frame passes at <= 0.01% outside the mask (over the whole frame where no
# mask was made). Time: the medians of the warm frames, gpu_ms (GL
# timestamps) where the driver has them, else the frame's wall ms; the
# compute capture's phases (binning, coverage, sort, composite, ...) as
# --stats reports them.
#
# Models: every `oitgen hard` case, the demo, the fetched meshes present,
# the 1M plant, and on a GPU the 12M plant. The issue's bars (an NVIDIA GPU):
# 12M plant at 1024x1024 <= 0.25x DFB (beyond: <= 6.4 ms), the 600-layer
# stack (hard case "stack", its default view, head on) <= 0.1x DFB; the
# stream out of core at 1/4 of the model against DFB in core is measured by
# ooc_curve.sh (gpu_check.sh step 6 runs it with --capture compute).
#
# Usage: data_scripts/compute_vs_dfb.sh [BINDIR] [OUT.md] [WxH]
#   defaults: build/bin, bench/compute-vs-dfb-RENDERER.md, 1024x1024
# Knobs (environment):
#   COMPUTE_MODELS="stack demo plant1M"  these models only (hard case names,
#                         demo, plantN[M|K], or files in data_scripts/cache)
#   COMPUTE_12M=0|1       the 12M plant (default: 1 off llvmpipe)
#   COMPUTE_VIEWS=N       views of the orbit (default 3; the stack: 1)
#   COMPUTE_MASK_MAX=T    edge masks for models up to T triangles (default
#                         2000000; the reference is a CPU ray caster)
#   COMPUTE_STREAM=0      leave out the streamed rows
# Exits 1 when a frame fails or a render fails, 2 when a tool is missing.
set -u
bin=${1:-build/bin} out=${2:-} size=${3:-1024x1024}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/models.sh"
. "$here/sweep_lib.sh"
views=${COMPUTE_VIEWS:-3}
mask_max=${COMPUTE_MASK_MAX:-2000000}
cmdline="$0 $*"

die() { echo "compute_vs_dfb: $*" >&2; exit 2; }
need_bins "$bin" oitgen oitprep oitstream
command -v python3 >/dev/null || die "python3: missing (reads the --stats files)"
bin=$(cd "$bin" && pwd)
make_work compute_vs_dfb

probe_renderer --method compute ||
    die "oitstream --method compute cannot run here: $(head -c 300 "$work/err.txt")"
out=${out:-bench/compute-vs-dfb-$tag.md}
mkdir -p "$(dirname "$out")" || die "$(dirname "$out"): cannot create"

hard="coplanar coplanar_tiny coplanar_far decal touching rings sticks moebius degenerate nearflat far tiny thin nonmanifold stack dense mixed"
models=${COMPUTE_MODELS:-$hard $(check_models "$cache" "${COMPUTE_12M:-$def12}")}
failures=0
: >"$work/rows.txt"

# render NAME TAG FILE [options]: the walk into $work/NAME/TAG/, stats beside.
render() {
    _n=$1 _t=$2 _f=$3 && shift 3
    mkdir -p "$work/$_n/$_t"
    "$bin/oitstream" "$_f" --walk "$work/walk.txt" --size "$size" --out "$work/$_n/$_t/" \
        --stats "$work/$_n/$_t.json" --quiet "$@" 2>"$work/err.txt"
}

for model in $models; do
    name=${model%.*}
    is_hard=0
    case " $hard " in *" $model "*) is_hard=1 ;; esac
    if [ $is_hard = 1 ]; then
        mesh=$work/$model.ply
        "$bin/oitgen" hard --case "$model" -o "$mesh" >/dev/null || die "$model: oitgen failed"
    else
        model_mesh "$model"
    fi
    echo "compute_vs_dfb: $name" >&2
    nv=$views
    [ "$model" != stack ] || nv=1
    if [ "$nv" = 1 ]; then
        "$bin/oitstream" "$mesh" --method unsorted --size 16x16 --out "$work/v.png" \
            --stats "$work/v.json" --quiet || die "$model: framing the view failed"
    else
        "$bin/oitstream" "$mesh" --method unsorted --orbit "$nv" --size 16x16 --out "$work/v/" \
            --stats "$work/v.json" --quiet || die "$model: framing the views failed"
    fi
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | awk '{ print; print }' >"$work/walk.txt"
    tris=$(sed -n 's/.*"triangles": *\([0-9]*\).*/\1/p' "$work/v.json" | head -n 1)
    render "$name" dfb "$mesh" --method dfb ||
        { echo "$name dfb FAIL $(head -c 200 "$work/err.txt" | tr '\n|' '  ')" >>"$work/rows.txt"
          failures=$((failures + 1)); continue; }
    mask=""
    if [ "${tris:-0}" -le "$mask_max" ]; then
        mkdir -p "$work/$name/mask"
        "$bin/oitstream" "$mesh" --method reference --walk "$work/walk.txt" --size "$size" \
            --out "$work/$name/ref/" --ambiguity "$work/$name/mask/" --quiet 2>/dev/null &&
            mask="$work/$name/mask"
    fi
    runs="compute"
    if [ "${COMPUTE_STREAM:-1}" != 0 ]; then
        if "$bin/oitprep" "$mesh" -o "$work/$name.oitp" >"$work/prep.log" 2>&1; then
            runs="$runs stream"
        else
            echo "$name stream FAIL oitprep: $(tail -n 1 "$work/prep.log" | tr '|' ' ')" >>"$work/rows.txt"
            failures=$((failures + 1))
        fi
    fi
    for r in $runs; do
        if [ "$r" = compute ]; then
            render "$name" "$r" "$mesh" --method compute
        else
            render "$name" "$r" "$work/$name.oitp" --method stream --capture compute
        fi
        if [ $? != 0 ]; then
            echo "$name $r FAIL $(head -c 200 "$work/err.txt" | tr '\n|' '  ')" >>"$work/rows.txt"
            failures=$((failures + 1))
            continue
        fi
        # per frame: index, % over 1/255, % outside the mask (or -1)
        cmpf=$work/$name/$r.cmp
        : >"$cmpf"
        for img in "$work/$name/dfb"/frame_*.png; do
            fr=$(basename "$img")
            j=$("$bin/oitstream" --compare "$work/$name/$r/$fr" "$img" --json \
                ${mask:+--mask "$mask/$fr"} 2>/dev/null) || { echo "$fr -1 -1 missing" >>"$cmpf"; continue; }
            p=$(echo "$j" | sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
            q=$(echo "$j" | sed -n 's/.*"pct_over_1_255_outside_mask": *\([-0-9.e+]*\).*/\1/p')
            echo "$fr ${p:--1} ${q:--1} ok" >>"$cmpf"
        done
        echo "$name $r OK $tris $work/$name/$r.json $work/$name/dfb.json $cmpf" >>"$work/rows.txt"
    done
    rm -rf "$work/$name/dfb" "$work/$name/compute" "$work/$name/stream" "$work/$name/ref" \
        "$work/$name/mask" "$work/$name.oitp"
    case $mesh in "$work"/*) rm -f "$mesh" ;; esac
done

python3 - "$work/rows.txt" "$out" "$renderer" "$size" "$cmdline" "$here" <<'PY' || failures=$((failures + 1))
import json, os, statistics, subprocess, sys, time
rows, out, renderer, size, cmdline, here = sys.argv[1:7]
def warm(frames, key):
    v = [f[key] for i, f in enumerate(frames) if i % 2 == 1 and f.get(key, -1) >= 0]
    return statistics.median(v) if v else -1.0
def phases(frames):
    acc = {}
    for i, f in enumerate(frames):
        if i % 2 == 1:
            for k, v in (f.get("gpu_phase_ms") or {}).items():
                acc.setdefault(k, []).append(v)
    return ", ".join("%s %.2f" % (k, statistics.median(v)) for k, v in acc.items()
                     if statistics.median(v) >= 0.005)
fmt = lambda x, d=2: "-" if x is None or x < 0 else "%.*f" % (d, x)
lines, bad = [], 0
for line in open(rows):
    f = line.split()
    name, run, ok = f[0], f[1], f[2]
    if ok != "OK":
        lines.append("| %s | %s | - | - | - | - | - | - | - | **FAIL**: %s |" % (name, run, " ".join(f[3:])))
        bad += 1
        continue
    tris, mine, dfb, cmp = f[3], json.load(open(f[4])), json.load(open(f[5])), f[6]
    worst, worst_out, masked, failed = 0.0, -1.0, True, []
    for c in open(cmp):
        fr, p, q, st = c.split()
        p, q = float(p), float(q)
        if st != "ok":
            failed.append(fr + " missing")
            continue
        worst = max(worst, p)
        if q < 0: masked = False
        worst_out = max(worst_out, q)
        if (q if q >= 0 else p) > 0.01:
            failed.append(fr)
    key = "gpu_ms" if warm(dfb["frames"], "gpu_ms") > 0 and warm(mine["frames"], "gpu_ms") > 0 else "ms"
    d, m = warm(dfb["frames"], key), warm(mine["frames"], key)
    verdict = "pass" if not failed else "**FAIL** " + " ".join(failed)
    bad += bool(failed)
    lines.append("| %s | %s | %s | %d | %s | %s | %s %s | %s | %s | %s | %s |" % (
        name, "in core" if run == "compute" else "stream --capture compute", tris,
        len(mine["frames"]), fmt(worst, 4), fmt(worst_out, 4) if masked else "no mask",
        fmt(d), key, fmt(m), fmt(m / d if d > 0 and m >= 0 else -1), phases(mine["frames"]) or "-",
        verdict))
try:
    commit = subprocess.run(["git", "-C", here, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "?"
except OSError:
    commit = "?"
head = "`%s` at %s, %s, %d cores, %s." % (cmdline, commit, time.strftime("%Y-%m-%d", time.gmtime()),
                                           os.cpu_count(), size)
doc = ["# The compute capture against DFB on %s" % renderer, "",
       head + " Each view of an orbit drawn cold then warm; times are the warm frames' medians.", "",
       "A frame passes at <= 0.01% of its pixels over 1/255 against DFB on the source mesh, "
       "outside the edge mask (the reference's --ambiguity mask) where one was made. "
       "\"time\" is gpu_ms where both runs report it, else wall ms.", "",
       "| model | compute capture | triangles | frames | worst % over 1/255 | worst % outside mask | "
       "DFB time | compute time | compute / DFB | compute phases (warm medians, ms) | verdict |",
       "|---|---|---|---|---|---|---|---|---|---|---|"] + lines + ["",
       "Bars on an NVIDIA GPU (issue 39): plant12M in core <= 0.25x DFB (beyond: <= 6.4 ms); "
       "stack <= 0.1x DFB; the stream out of core at 1/4 of the model <= 0.5x DFB in core "
       "(ooc_curve.sh with OOC_STREAM_ARGS=\"--capture compute\")."]
open(out, "w").write("\n".join(doc) + "\n")
print("compute_vs_dfb: wrote %s (%d failing row(s))" % (out, bad))
sys.exit(1 if bad else 0)
PY
[ "$failures" = 0 ]
