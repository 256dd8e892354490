#!/bin/sh
# oitstream --stats: GPU time per frame and phase, the warm medians, and the
# stream's chosen memory. On a part file of 24 quads (several parts) and its
# mesh: every frame of stream and dfb has gpu_ms > 0 whose phases add up to
# it, pass1 and resolve > 0 (the geometry and its compositing are timed),
# the summary's medians are those of the frames after the first; the
# stream's budget names its source (llvmpipe: no driver figure, no total),
# and --gpu-budget is the total it reports.
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
scratch oitstream_stats_gpu
"$OIT_BIN/oitgen" quads --count 24 -o "$T/q.ply" >/dev/null || die "oitgen quads"
"$OIT_BIN/oitprep" "$T/q.ply" -o "$T/q.oitp" --scheme guaranteed >/dev/null || die "oitprep"
"$OIT_BIN/oitstream" "$T/q.oitp" --method stream --orbit 3 --size 64x64 --quiet \
    --stats "$T/s.json" >/dev/null || fail "stream --stats"
"$OIT_BIN/oitstream" "$T/q.ply" --method dfb --orbit 3 --size 64x64 --quiet \
    --stats "$T/d.json" >/dev/null || fail "dfb --stats"
"$OIT_BIN/oitstream" "$T/q.oitp" --method stream --orbit 2 --size 64x64 --quiet \
    --gpu-budget 8M --stats "$T/b.json" >/dev/null || fail "stream --gpu-budget 8M"
python3 - "$T" <<'PY' || fail "--stats GPU figures wrong"
import json, statistics, sys
t = sys.argv[1]
ok = True
def check(c, what):
    global ok
    if not c:
        print("FAIL:", what); ok = False
for name in ("s", "d"):
    d = json.load(open("%s/%s.json" % (t, name)))
    check(d["gpu_timer"] == "GL timestamp queries", "%s: gpu_timer %r" % (name, d["gpu_timer"]))
    fr = d["frames"]
    for i, f in enumerate(fr):
        ph = f.get("gpu_phase_ms", {})
        check(f["gpu_ms"] > 0, "%s frame %d: gpu_ms %r" % (name, i, f["gpu_ms"]))
        check(set(ph) == {"other", "upload", "pass1", "pass2", "resolve", "readback",
                          "binning", "sweep"},
              "%s frame %d: phases %r" % (name, i, sorted(ph)))
        check(abs(sum(ph.values()) - f["gpu_ms"]) <= 0.01 + 1e-3 * f["gpu_ms"],
              "%s frame %d: phases add to %.3f, gpu_ms %.3f" % (name, i, sum(ph.values()), f["gpu_ms"]))
        check(ph.get("pass1", 0) > 0 and ph.get("resolve", 0) > 0,
              "%s frame %d: pass1 %r resolve %r" % (name, i, ph.get("pass1"), ph.get("resolve")))
    med = statistics.median(f["gpu_ms"] for f in fr[1:])
    check(abs(d["summary"]["gpu_ms_median"] - med) <= 0.002,
          "%s: summary gpu_ms_median %r, frames' %r" % (name, d["summary"]["gpu_ms_median"], med))
    check(d["summary"]["warm_frames"] == len(fr) - 1, "%s: warm_frames" % name)
s, b = (json.load(open("%s/%s.json" % (t, n))) for n in ("s", "b"))
sb, bb = s["budget"], b["budget"]
check(sb["source"] != "" and (sb["gpu_budget"] == 0) == (sb["driver_free"] == 0),
      "default budget %r" % sb)
check(bb["gpu_budget"] == 8 << 20 and bb["source"] == "--gpu-budget" and
      bb["ring"] + bb["capture"] + (0 if bb["resident"] else bb["cache"]) <= 8 << 20,
      "--gpu-budget 8M: %r" % bb)
check(max(f["gpu_bytes_peak"] for f in b["frames"]) <= 8 << 20, "--gpu-budget 8M: peak over it")
sys.exit(0 if ok else 1)
PY
finish --clean test_stats_gpu
