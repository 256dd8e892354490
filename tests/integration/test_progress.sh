#!/bin/sh
# Progress where nobody watches a terminal: oitprep and oitgen, with stderr
# piped, print whole lines ("progress: STAGE  43%  6.2 s", "oitgen: ...%"),
# never the in-place bar's carriage returns, every OIT_PROGRESS_PERIOD
# seconds (forced tiny here, so a small scene prints them); with the default
# period (5 s) a conversion of a second prints none; on a terminal (script(1)
# gives one) the bar is drawn in place as before.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
need_every_tool
scratch progress
cd "$T" || exit 1
CR=$(printf '\r')

OIT_PROGRESS_PERIOD=0.000001 "$G" plant --triangles 20000 -o plant.ply >/dev/null 2>gen.txt ||
    die "oitgen plant: $(cat gen.txt)"
cat gen.txt
grep -q "^oitgen: 100.0%  [0-9]* triangles  [0-9.]* s$" gen.txt ||
    fail "oitgen with stderr piped printed no progress line"
grep -q "$CR" gen.txt && fail "oitgen with stderr piped drew the bar (carriage returns)"

OIT_PROGRESS_PERIOD=0.000001 "$P" plant.ply -o plant.oitp --part-triangles 2000 >/dev/null 2>prep.txt ||
    die "oitprep: $(cat prep.txt)"
cat prep.txt
for stage in bounds grid bin partition; do
    grep -q "^progress: $stage *100%  [0-9.]* s$" prep.txt ||
        fail "oitprep with stderr piped printed no 100% line for the $stage stage"
done
grep -q "$CR" prep.txt && fail "oitprep with stderr piped drew the bar (carriage returns)"
# The period holds: by default a short conversion prints no progress line.
"$P" plant.ply -o default.oitp --part-triangles 2000 >/dev/null 2>quiet.txt || die "oitprep: $(cat quiet.txt)"
grep -q "^progress:" quiet.txt && fail "a conversion shorter than the 5 s period printed progress lines"
# A malformed period is said and ignored.
OIT_PROGRESS_PERIOD=soon "$G" quads --count 4 -o q.ply >/dev/null 2>bad.txt || die "oitgen quads"
grep -q "OIT_PROGRESS_PERIOD=soon is not a number of seconds" bad.txt ||
    fail "a malformed OIT_PROGRESS_PERIOD was not reported"

# On a terminal: the bar, redrawn in place.
if command -v script >/dev/null 2>&1; then
    script -qec "'$P' plant.ply -o tty.oitp --part-triangles 2000" /dev/null >tty.txt 2>&1 ||
        fail "oitprep under script(1) failed"
    grep -q "partition  \[#*\] 100%" tty.txt && grep -q "$CR" tty.txt ||
        fail "oitprep on a terminal did not draw its bar"
    grep -q "^progress:" tty.txt && fail "oitprep on a terminal printed progress lines"
else
    echo "note: no script(1): the terminal's bar is not checked"
fi
finish --clean progress
