#!/bin/sh
# Mutation run: plants each bug of a list (data_scripts/mutations.txt) one at
# a time in a scratch clone of HEAD, rebuilds (Release), runs the tests the
# entry names and says whether they caught it; prints a table, the kill rate
# and the survivors. The clone's tests must all pass before anything is
# planted, and an entry whose text no longer occurs exactly once is reported
# as stale (the run fails), so the list cannot quietly fall behind the code.
#
# usage: data_scripts/mutate.sh [--list FILE] [--only ID,ID...] [--whole-suite]
#                               [--jobs N] [--keep] [--scratch DIR]
#   --whole-suite  also run the whole suite for each survivor (a survivor
#                  the suite kills counts as killed, marked "suite")
#   --keep         keep the scratch clone (default: removed at the end)
# Needs git, cmake, perl and what `make build` needs. Uncommitted changes are
# not in the clone: commit first. Exit 0 when nothing is stale and the kill
# rate is at least 90%, 1 otherwise, 2 on a usage error.
set -u
ROOT=$(git -C "$(dirname "$0")" rev-parse --show-toplevel) || exit 1
LIST="$ROOT/data_scripts/mutations.txt"
ONLY="" WHOLE=0 JOBS=$(nproc) KEEP=0 SCRATCH=""
while [ $# -gt 0 ]; do
    case "$1" in
    --list) LIST=$2; shift ;;
    --only) ONLY=",$2," ; shift ;;
    --whole-suite) WHOLE=1 ;;
    --jobs) JOBS=$2; shift ;;
    --keep) KEEP=1 ;;
    --scratch) SCRATCH=$2; shift ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "mutate.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
[ -f "$LIST" ] || { echo "mutate.sh: $LIST: no such list" >&2; exit 2; }
command -v perl >/dev/null || { echo "mutate.sh: needs perl" >&2; exit 1; }
[ -z "$SCRATCH" ] && SCRATCH=$(mktemp -d /tmp/oit-mutate.XXXXXX)
[ -n "$(git -C "$ROOT" status --porcelain --untracked-files=no)" ] &&
    echo "mutate.sh: note: uncommitted changes in $ROOT are not in the clone" >&2

SRC="$SCRATCH/src" B="$SCRATCH/src/build" E="$SCRATCH/entries"
cleanup() { [ "$KEEP" -eq 1 ] || rm -rf "$SCRATCH"; }
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
rm -rf "$SRC" "$E" && mkdir -p "$E" || exit 1
git clone -q --no-hardlinks "$ROOT" "$SRC" || { echo "mutate.sh: cannot clone $ROOT" >&2; exit 1; }

# Splits the list into $E/N.{id,file,tests,old,new}, one set an entry.
perl -e '
    my ($list, $dir) = @ARGV; open(my $in, "<", $list) or die "$list: $!\n";
    my $n = 0; my %e;
    sub flush { return unless %e; $n++;
        for my $k (qw(id file tests old new)) {
            open(my $o, ">", "$dir/$n.$k") or die "$dir: $!\n";
            my $v = $e{$k} // ""; $v =~ s/\n\z// if $k eq "old" || $k eq "new";
            print $o $v; close $o }
        %e = () }
    while (<$in>) { chomp;
        if (/^@\s*(\S+)\s*\|\s*(\S+)\s*\|\s*(\S+)\s*$/) { flush(); %e = (id => $1, file => $2, tests => $3) }
        elsif (/^- (.*)$/s && %e) { $e{old} .= "$1\n" }
        elsif (/^\+ (.*)$/s && %e) { $e{new} .= "$1\n" }
        elsif (/^\s*(#.*)?$/) { }
        else { die "$list:$.: not an entry line: $_\n" } }
    flush();
' "$LIST" "$E" || exit 2

# occurrences FILE OLD: how many times OLD's text occurs in FILE.
occurrences() {
    perl -e 'local $/; open(my $f, "<", $ARGV[0]) or die; my $s = <$f>;
             open(my $o, "<", $ARGV[1]) or die; my $t = <$o>;
             my $n = 0; my $p = 0; while (($p = index($s, $t, $p)) >= 0) { $n++; $p++ } print $n' "$1" "$2"
}
# plant FILE OLD NEW: replaces the one occurrence.
plant() {
    perl -e 'local $/; open(my $f, "<", $ARGV[0]) or die; my $s = <$f>; close $f;
             open(my $o, "<", $ARGV[1]) or die; my $t = <$o>;
             open(my $w, "<", $ARGV[2]) or die; my $r = <$w>;
             my $p = index($s, $t); substr($s, $p, length $t) = $r;
             open($f, ">", $ARGV[0]) or die; print $f $s' "$1" "$2" "$3"
}

echo "mutate: configuring and building a Release clone of $(git -C "$SRC" rev-parse --short HEAD) in $SRC" >&2
cmake -S "$SRC" -B "$B" -DCMAKE_BUILD_TYPE=Release -DOIT_MESH_CACHE="$ROOT/data_scripts/cache" \
    >"$SCRATCH/configure.log" 2>&1 && cmake --build "$B" -j "$JOBS" >"$SCRATCH/build.log" 2>&1 ||
    { echo "mutate.sh: the clean clone does not build (see $SCRATCH/build.log)" >&2; KEEP=1; exit 1; }

ids="" stale=0 union=""
count=$(ls "$E" | grep -c '\.id$')
for i in $(seq 1 "$count"); do
    n="$E/$i" id=$(cat "$E/$i.id")
    [ -n "$ONLY" ] && case "$ONLY" in *",$id,"*) ;; *) continue ;; esac
    c=$(occurrences "$SRC/$(cat "$n.file")" "$n.old" 2>/dev/null || echo 0)
    if [ "$c" != 1 ]; then
        echo "mutate: STALE $id: its text occurs $c times in $(cat "$n.file")" >&2
        stale=$((stale + 1)); continue
    fi
    t=$(ctest --test-dir "$B" -N -R "^($(cat "$n.tests"))\$" | sed -n 's/^Total Tests: //p')
    if [ "${t:-0}" -eq 0 ]; then
        echo "mutate: STALE $id: no test matches '$(cat "$n.tests")'" >&2
        stale=$((stale + 1)); continue
    fi
    ids="$ids ${n##*/}"
    union="${union:+$union|}$(cat "$n.tests")"
done
[ -n "$ids" ] || { echo "mutate.sh: no entry to run" >&2; exit 1; }

echo "mutate: baseline: the named tests on the clean clone" >&2
ctest --test-dir "$B" -j "$JOBS" -R "^($union)\$" >"$SCRATCH/baseline.log" 2>&1 ||
    { echo "mutate.sh: tests fail before any bug is planted (see $SCRATCH/baseline.log)" >&2
      KEEP=1; exit 1; }

killed=0 survived=0 broken=0 total=0 survivors=""
printf '%-30s %-28s %-9s %s\n' "bug" "file" "result" "failing tests"
for n in $ids; do
    id=$(cat "$E/$n.id") file=$(cat "$E/$n.file") tests=$(cat "$E/$n.tests")
    plant "$SRC/$file" "$E/$n.old" "$E/$n.new"
    log="$SCRATCH/$id.log"
    if ! cmake --build "$B" -j "$JOBS" >"$log" 2>&1; then
        result=nobuild failing="(does not compile: fix the entry)"; broken=$((broken + 1))
    else
        total=$((total + 1))
        ctest --test-dir "$B" -j "$JOBS" -R "^($tests)\$" >>"$log" 2>&1
        failing=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) (.*/\1/p' "$log" | tr '\n' ' ')
        if [ -n "$failing" ]; then
            result=killed; killed=$((killed + 1))
        elif [ "$WHOLE" -eq 1 ] && ! ctest --test-dir "$B" -j "$JOBS" >"$log.suite" 2>&1; then
            failing=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) (.*/\1/p' "$log.suite" | tr '\n' ' ')
            result=suite; killed=$((killed + 1))
        else
            result=SURVIVED failing="(none of: $tests)"; survived=$((survived + 1))
            survivors="$survivors $id"
        fi
    fi
    printf '%-30s %-28s %-9s %s\n' "$id" "$file" "$result" "$failing"
    git -C "$SRC" checkout -q -- "$file"
done
# A kept clone is left built from clean sources; a removed one needs no rebuild.
[ "$KEEP" -eq 1 ] && cmake --build "$B" -j "$JOBS" >/dev/null 2>&1

rate=$(awk -v k=$killed -v t=$total 'BEGIN{printf "%.1f", t ? 100 * k / t : 0}')
echo "mutate: $killed of $total planted bugs killed ($rate%), $survived survived," \
     "$broken did not compile, $stale stale"
[ -n "$survivors" ] && echo "mutate: survivors:$survivors"
[ "$stale" -eq 0 ] && [ "$broken" -eq 0 ] && awk -v r="$rate" 'BEGIN{exit !(r >= 90)}'
