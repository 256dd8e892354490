#!/bin/sh
# Long libFuzzer runs of every parser (make test runs 10 s of each).
# Usage: data_scripts/fuzz_long.sh [SECONDS_EACH] [BUILD_DIR]
# BUILD_DIR must be configured with -DOIT_FUZZ=ON (clang), as `make test`'s
# build-test is. Crashes are written to BUILD_DIR/fuzz/crash-*; a non-zero
# exit names the target that failed.
set -eu
secs=${1:-600} build=${2:-build-test}
cd "$build/fuzz"
status=0
for t in fuzz_ply fuzz_obj fuzz_off fuzz_stl fuzz_gltf fuzz_partfile; do
    [ -x "$t" ] || { echo "fuzz_long: $build/fuzz/$t missing (configure with -DOIT_FUZZ=ON)" >&2; exit 1; }
    mkdir -p "$t-corpus-long"
    src=$(ls -d ../../tests/corpus/"${t#fuzz_}" 2>/dev/null || true)
    echo "fuzz_long: $t for ${secs}s" >&2
    if ! ./"$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
            -artifact_prefix="crash-$t-" "$t-corpus-long" $src; then
        echo "fuzz_long: $t FAILED (see $build/fuzz/crash-$t-*)" >&2
        status=1
    fi
done
exit $status
