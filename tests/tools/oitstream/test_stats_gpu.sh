#!/bin/sh
# oitstream --stats: GPU time per frame and phase, the warm medians, and the
# stream's chosen memory. On a part file of 24 quads (several parts) and its
# mesh: every frame of stream and dfb has gpu_ms > 0 whose phases add up to
# it, pass1 and resolve > 0 (the geometry and its compositing are timed),
# the summary's medians are those of the frames after the first; the
# stream's budget names its source (llvmpipe: no driver figure, no total),
# and --gpu-budget is the total it reports. GPU bytes count all a method
# holds: DFB's gpu_bytes_peak holds its mesh (gpu_mesh_bytes, at least the
# triangles' vertex bytes, 3 x 16 a triangle, worked out here) and its
# per-pixel output; the stream's holds its upload ring (the budget's) and
# its per-pixel state (20 bytes a pixel, transparent), with no mesh: on a
# plant of 20000 triangles at 16x16, whose parts (resident: a ring of the
# file's size, at least the bytes frame 0 uploaded) outweigh the capture,
# a figure without the ring falls short.
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
gen_plant 20000 "$T/p.ply"
"$OIT_BIN/oitprep" "$T/p.ply" -o "$T/p.oitp" >/dev/null || die "oitprep plant"
"$OIT_BIN/oitstream" "$T/p.oitp" --method stream --orbit 2 --size 16x16 --quiet \
    --stats "$T/p.json" >/dev/null || fail "stream plant --stats"
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
d = json.load(open("%s/d.json" % t))
px = d["width"] * d["height"]
vertex = 3 * 4 + 4  # position floats + RGBA8
for i, f in enumerate(d["frames"]):
    check(f["gpu_mesh_bytes"] >= d["triangles"] * 3 * vertex,
          "dfb frame %d: gpu_mesh_bytes %d for %d triangles" % (i, f["gpu_mesh_bytes"], d["triangles"]))
    check(f["gpu_bytes_peak"] >= f["gpu_mesh_bytes"] + 16 * px,
          "dfb frame %d: gpu_bytes_peak %d below its mesh %d and output %d" %
          (i, f["gpu_bytes_peak"], f["gpu_mesh_bytes"], 16 * px))
s = json.load(open("%s/s.json" % t))
for i, f in enumerate(s["frames"]):
    check(f["gpu_mesh_bytes"] == 0, "stream frame %d: gpu_mesh_bytes %d" % (i, f["gpu_mesh_bytes"]))
    check(f["gpu_bytes_peak"] >= s["budget"]["ring"] + 20 * px,
          "stream frame %d: gpu_bytes_peak %d below its ring %d and state %d" %
          (i, f["gpu_bytes_peak"], s["budget"]["ring"], 20 * px))
p = json.load(open("%s/p.json" % t))
ring, up = p["budget"]["ring"], p["frames"][0]["bytes_uploaded"]
check(p["budget"]["resident"] == 1 and ring >= up > 16 * 16 * 1000,
      "plant: resident %r, ring %d, frame 0 uploaded %d" % (p["budget"]["resident"], ring, up))
for i, f in enumerate(p["frames"]):
    check(f["gpu_mesh_bytes"] == 0 and f["gpu_bytes_peak"] >= ring + 20 * 16 * 16,
          "plant frame %d: gpu_bytes_peak %d below its ring %d and state %d" %
          (i, f["gpu_bytes_peak"], ring, 20 * 16 * 16))
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
