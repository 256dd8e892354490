#!/bin/sh
# oitbench bus: one JSON object with the host-to-device rates, both ways,
# on the wall (> 0) and on the GPU (> 0, or -1 with the reason where the
# driver has no timer queries); a bad option is a usage error (exit 2).
. "${OIT_TEST_LIB:-$(dirname "$0")/../../lib.sh}"
scratch oitbench_bus
"$OIT_BIN/oitbench" bus --bytes 4M --repeat 2 > "$T/bus.json" || fail "oitbench bus exited $?"
cat "$T/bus.json"
python3 - "$T/bus.json" <<'PY' || fail "bus.json: wrong figures"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["bytes"] == 4 << 20 and d["repeat"] == 2, d
for k in ("subdata", "mapped_copy"):
    assert d[k + "_wall_gbps"] > 0, (k, d)
    timed = d["timer"] == "GL_TIME_ELAPSED"
    assert (d[k + "_gpu_gbps"] > 0) if timed else (d[k + "_gpu_gbps"] == -1), (k, d)
assert d["renderer"], d
PY
"$OIT_BIN/oitbench" bus --bytes 12 2> "$T/err.txt"
rc=$?
[ "$rc" -eq 2 ] || fail "oitbench bus --bytes 12 exited $rc, expected 2"
grep -q -- "--bytes" "$T/err.txt" || fail "the usage error does not name --bytes"
finish --clean test_oitbench_bus
