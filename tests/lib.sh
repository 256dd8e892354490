# Shell helpers the tests share (POSIX sh: the scripts run under dash).
# A test script in tests/FOLDER/ loads them with
#     . "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
# (two folders down, ../../lib.sh): ctest sets OIT_TEST_LIB
# (tests/CMakeLists.txt); the fallback serves a script run by hand, as
# data_scripts/hard_cases.sh runs test_hard.sh. Tool variables are the
# scripts' own (S, P, G, ... mean different things in different scripts),
# but for need_every_tool, which the suites that run every tool share.

# Headless GL wherever the script is run from (ctest sets it too).
export EGL_PLATFORM="${EGL_PLATFORM:-surfaceless}"

FAILS=0

# fail MESSAGE...: one failed check, said on stderr and counted; the script
# goes on, so that one run names every broken figure. FAIL_PREFIX, where a
# script sets it, names its case in every message ("coplanar (fast): ").
fail() {
    echo "FAIL: ${FAIL_PREFIX:-}$*" >&2
    FAILS=$((FAILS + 1))
}

# die MESSAGE...: a failure after which nothing else can be checked (an
# input the rest needs was not made): said, and exit 1.
die() {
    echo "FAIL: ${FAIL_PREFIX:-}$*" >&2
    exit 1
}

# skip REASON...: exit 77, which ctest reports as skipped.
skip() {
    echo "skip: $*"
    exit 77
}

# need_tools PATH...: skips unless each is an executable (a tool this
# configuration did not build).
need_tools() {
    for _tool in "$@"; do
        [ -x "$_tool" ] || skip "$_tool not built"
    done
}

# need_every_tool: P, G, S and BN, the paths of oitprep, oitgen, oitstream
# and oitbench, each built or the test skipped.
need_every_tool() {
    : "${OIT_BIN:?OIT_BIN must name the tools folder}"
    P="$OIT_BIN/oitprep"
    G="$OIT_BIN/oitgen"
    S="$OIT_BIN/oitstream"
    BN="$OIT_BIN/oitbench"
    need_tools "$P" "$G" "$S" "$BN"
}

# have_mesh NAME: MESH, the path of the fetched mesh NAME
# (data_scripts/fetch_meshes.sh fills $OIT_MESH_CACHE); returns 1, saying so,
# when it is not there, for a test that then checks less.
have_mesh() {
    MESH="${OIT_MESH_CACHE:-}/$1"
    [ -f "$MESH" ] && return 0
    echo "note: $MESH missing (run data_scripts/fetch_meshes.sh)"
    return 1
}

# need_mesh NAME: MESH as have_mesh sets it, or skip: the test is about it.
need_mesh() {
    MESH="${OIT_MESH_CACHE:-}/$1"
    [ -f "$MESH" ] || skip "$MESH missing (run data_scripts/fetch_meshes.sh)"
}

# scratch NAME: T, this test's folder $OIT_TEST_TMP/NAME, made empty. It is
# kept after the run, so that a failure's files are there to look at
# (finish --clean removes it after a pass). Fails early, naming the variable,
# when the script runs outside ctest without OIT_BIN or OIT_TEST_TMP.
scratch() {
    : "${OIT_BIN:?OIT_BIN must name the tools folder}"
    : "${OIT_TEST_TMP:?OIT_TEST_TMP must name a scratch folder}"
    T="$OIT_TEST_TMP/$1"
    rm -rf "$T" && mkdir -p "$T" || exit 1
}

# temp_scratch NAME: T, a new folder (under $OIT_TEST_TMP, else the system's
# temporary folder) removed when the script exits, whatever the verdict: for
# tests whose files say nothing once the run has printed its findings.
temp_scratch() {
    T=$(mktemp -d "${OIT_TEST_TMP:-${TMPDIR:-/tmp}}/$1.XXXXXX") || exit 1
    trap 'rm -rf "$T"' EXIT
}

# finish [--clean] [WHAT]: the verdict, last in a script. With failures:
# "WHAT: N failure(s)" on stderr and exit 1; else "WHAT: ok" and exit 0,
# removing $T first with --clean.
finish() {
    _clean=
    if [ "${1:-}" = --clean ]; then
        _clean=1
        shift
    fi
    _what=${1:+$1: }
    if [ "$FAILS" -ne 0 ]; then
        echo "$_what$FAILS failure(s)" >&2
        exit 1
    fi
    [ -z "$_clean" ] || rm -rf "$T"
    echo "${_what}ok"
    exit 0
}

# expect_rc WANT CMD...: runs CMD (stdout to $T/out.txt, stderr to
# $T/err.txt, the status in rc) and checks that it exits WANT.
expect_rc() {
    _want=$1
    shift
    _ran="$*"
    "$@" >"$T/out.txt" 2>"$T/err.txt"
    rc=$?
    [ "$rc" -eq "$_want" ] || fail "'$*' exited $rc, want $_want: $(tail -n 2 "$T/err.txt")"
}

# expect_err PATTERN [WHAT]: the stderr of expect_rc's command matches
# PATTERN (grep's), the message a refusal must give; WHAT names the check in
# the failure, the command otherwise.
expect_err() {
    grep -q -- "$1" "$T/err.txt" ||
        fail "${2:-"'$_ran'"}: stderr lacks '$1': $(head -c 300 "$T/err.txt")"
}

# The tools write flat JSON (stats, --compare --json, info --json): one
# value is found by its key with sed, without a JSON parser on the machine.
# Each reads FILE, or stdin without one.
# json_num KEY [FILE]: the number after "KEY": on the first line that has
# one (the last on that line); empty when there is none.
json_num() {
    sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" ${2:+"$2"} | head -n 1
}
# json_str KEY [FILE]: the string after "KEY":, as json_num finds it.
json_str() {
    sed -n "s/.*\"$1\": *\"\([^\"]*\)\".*/\1/p" ${2:+"$2"} | head -n 1
}
# json_all KEY [FILE]: every number after "KEY":, one a line (in stats
# files, one a frame).
json_all() {
    grep -o "\"$1\": *[-0-9.e+]*" ${2:+"$2"} | sed 's/.*: *//'
}
# json_sum KEY [FILE], json_min KEY [FILE]: of every value json_all finds.
json_sum() {
    json_all "$@" | awk '{s += $1} END {print s + 0}'
}
json_min() {
    json_all "$@" | awk 'NR == 1 || $1 < m {m = $1} END {print m + 0}'
}

# at_most A B: true when A <= B, numbers of any form awk reads.
at_most() {
    awk "BEGIN{exit !($1 <= $2)}"
}

# compare NAME A B [MASK] LIMIT: oitstream --compare of images A and B
# (outside MASK's pixels when given), printed (after INDENT, where a script
# nests its lines) and checked: at most LIMIT% of the pixels may differ by
# more than 1/255, the DESIGN.md tolerance at LIMIT 0.1. Leaves the
# figures in PCT and MAX_ABS, and the JSON in $T/cmp.json.
compare() {
    if [ $# -eq 5 ]; then
        "$OIT_BIN/oitstream" --compare "$2" "$3" --mask "$4" --json >"$T/cmp.json" ||
            { fail "$1: compare"; PCT=100; return; }
        PCT=$(json_num pct_over_1_255_outside_mask "$T/cmp.json") _limit=$5
    else
        "$OIT_BIN/oitstream" --compare "$2" "$3" --json >"$T/cmp.json" ||
            { fail "$1: compare"; PCT=100; return; }
        PCT=$(json_num pct_over_1_255 "$T/cmp.json") _limit=$4
    fi
    MAX_ABS=$(json_num max_abs "$T/cmp.json")
    echo "${INDENT:-}$1: max_abs $MAX_ABS, over 1/255 $PCT% (limit $_limit%)"
    at_most "$PCT" "$_limit" || fail "$1: $PCT% of pixels off by more than 1/255"
}

# image_diff NAME A B: oitstream --compare of images A and B, printed; the
# figures stay in MAX_ABS, RMSE and OVER (pixels more than 1/255 apart).
image_diff() {
    "$OIT_BIN/oitstream" --compare "$2" "$3" --json >"$T/cmp.json" ||
        { fail "$1: cannot compare $2 $3"; MAX_ABS=9 RMSE=9 OVER=0; return 1; }
    MAX_ABS=$(json_num max_abs "$T/cmp.json")
    RMSE=$(json_num rmse "$T/cmp.json")
    OVER=$(json_num pixels_over "$T/cmp.json")
    echo "${INDENT:-}$1: max_abs $MAX_ABS, rmse $RMSE, $OVER pixels over 1/255"
}

# expect_equal NAME A B: no value of A more than EQUAL from B's (max_abs);
# EQUAL is 0, bit for bit in 8 bits, unless the script sets it.
expect_equal() {
    image_diff "$@"
    at_most "$MAX_ABS" "${EQUAL:-0}" || fail "$1: $2 differs from $3 (max_abs $MAX_ABS)"
}

# expect_differ NAME A B MIN: at least MIN pixels of A more than 1/255 from
# B's (a change that must show).
expect_differ() {
    image_diff "$1" "$2" "$3"
    [ "$OVER" -ge "$4" ] || fail "$1: $2 too close to $3 ($OVER pixels over, want >= $4)"
}

# gen_hard CASE OUT: the numerical hard case's mesh (oitgen hard --case
# CASE) in OUT, or die.
gen_hard() {
    "$OIT_BIN/oitgen" hard --case "$1" -o "$2" >/dev/null || die "oitgen hard --case $1"
}

# gen_plant TRIANGLES OUT: oitgen's plant of about TRIANGLES triangles in
# OUT, or die.
gen_plant() {
    "$OIT_BIN/oitgen" plant --triangles "$1" -o "$2" >/dev/null || die "oitgen plant"
}

# prep_or_die IN OUT [OPTION...]: oitprep IN -o OUT OPTION..., what it says
# in $T/prep.txt; dies with its last line when it fails.
prep_or_die() {
    _in=$1 _out=$2
    shift 2
    "$OIT_BIN/oitprep" "$_in" -o "$_out" "$@" >"$T/prep.txt" 2>&1 ||
        die "oitprep $(basename "$_in") $*: $(tail -n 1 "$T/prep.txt")"
}
