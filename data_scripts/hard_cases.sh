#!/bin/sh
# Every `oitgen hard` case through tests/integration/test_hard.sh (oitprep, verify, every
# exact method, several views), its printed figures gathered into one
# markdown report: what the hard-case suite measured on this machine.
#
# Usage: data_scripts/hard_cases.sh [BINDIR] [OUT.md] [WxH]
set -eu
bin=$(cd "${1:-build/bin}" && pwd) out=${2:-bench/hard-cases-$(hostname).md} size=${3:-256x256}
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
cases="coplanar rings sticks moebius degenerate nearflat far tiny thin nonmanifold stack dense"
mkdir -p "$(dirname "$out")"
{
    echo "# Numerical hard cases"
    echo
    EGL_PLATFORM=surfaceless "$bin/oitstream" "$here/tests/corpus/partfile/small.oitp" \
        --method dfb --size 8x8 --out "$work/x.png" --stats "$work/x.json" --quiet
    echo "Machine: $(uname -m), $(nproc) cores; GL: $(sed -n 's/.*"renderer": *"\([^"]*\)".*/\1/p' "$work/x.json" | head -n 1)."
    echo "Image size $size. Command: \`data_scripts/hard_cases.sh $bin $out $size\`."
    echo
    echo "Each case: oitprep's conversion, oitprep verify, then per view every exact"
    echo "method against DFB (stream and PLL on the part file, depth peeling and DFB"
    echo "on the source mesh, the Embree reference outside its ambiguous pixels)."
    echo "\"over 1/255\" is the share of pixels with a channel off by more than 1/255;"
    echo "every check's limit is 0.1% (0.5% part file vs mesh), as in tests/integration/test_hard.sh."
    echo
} > "$out"
status=0
for c in $cases; do
    echo "hard_cases: $c" >&2
    echo "## $c" >> "$out"
    echo '```' >> "$out"
    OIT_BIN="$bin" OIT_TEST_TMP="$work" OIT_HARD_SIZE="$size" sh "$here/tests/integration/test_hard.sh" "$c" \
        >> "$out" 2>&1 || status=1
    echo '```' >> "$out"
done
echo "hard_cases: wrote $out" >&2
exit $status
