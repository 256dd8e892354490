#!/bin/sh
# Long libFuzzer runs of every fuzz target built (make test runs 10 s of each).
# Usage: data_scripts/fuzz_long.sh [SECONDS_EACH] [BUILD_DIR]
# BUILD_DIR must be configured with -DOIT_FUZZ=ON (clang), as `make test`'s
# build-test is. Crashes are written to BUILD_DIR/fuzz/crash-*; a non-zero
# exit names the target that failed.
set -eu
secs=${1:-600} build=${2:-build-test}
cd "$build/fuzz"
status=0
found=0
for t in fuzz_*; do
    [ -f "$t" ] && [ -x "$t" ] || continue
    found=1
    # the seeds ctest gives it (tests/*/CMakeLists.txt, oit_add_fuzzer CORPUS)
    case ${t#fuzz_} in
        assimp_*) seeds=assimp ;;
        meshopt_decode) seeds=meshopt ;;
        *) seeds=${t#fuzz_} ;;
    esac
    src=$(ls -d ../../tests/corpus/"$seeds" 2>/dev/null || true)
    mkdir -p "$t-corpus-long"
    echo "fuzz_long: $t for ${secs}s" >&2
    # no -rss_limit_mb: see oit_add_fuzzer in tests/CMakeLists.txt (its
    # thread and the readers' forked child deadlock under clang 14's ASan)
    if ! ./"$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=0 -malloc_limit_mb=2048 \
            -artifact_prefix="crash-$t-" "$t-corpus-long" $src; then
        echo "fuzz_long: $t FAILED (see $build/fuzz/crash-$t-*)" >&2
        status=1
    fi
done
[ $found = 1 ] || { echo "fuzz_long: no fuzz_* targets in $build/fuzz (configure with -DOIT_FUZZ=ON)" >&2; exit 1; }
exit $status
