# Sourced after tests/lib.sh by the tests that drive oitstream --window
# through real X events (xdotool under xvfb-run): skips without a display
# or xdotool, and the helpers they share. start and quit read S (the
# oitstream binary), W and H (the window's size) from the caller; the
# viewer's stdout goes to log.txt and its --stats to st.json in the
# current folder.
[ -n "${DISPLAY:-}" ] || skip "no DISPLAY (run under xvfb-run)"
command -v xdotool >/dev/null 2>&1 ||
    skip "xdotool not installed (setup/debian-packages.txt lists it; run setup/install-deps.sh)"

stat_of() { json_num "$1" <st.json; }
# wait_for SECONDS CONDITION...: polls the condition every 0.1 s
wait_for() {
    n=$(($1 * 10)); shift
    while [ "$n" -gt 0 ]; do
        "$@" && return 0
        sleep 0.1
        n=$((n - 1))
    done
    return 1
}
stat_at_least() { [ -f st.json ] && [ "$(stat_of "$1")" -ge "$2" ] 2>/dev/null; }
# start ARGS...: the viewer in the background, its window id in WIN
start() {
    rm -f st.json
    "$S" "$@" --window --no-overlay --size ${W}x$H --stats st.json >log.txt 2>&1 &
    PID=$!
    wait_for 120 stat_at_least exact_frames 1 || { cat log.txt; fail "$1: no first frame"; return 1; }
    WIN=$(timeout 20 xdotool search --sync --pid "$PID" 2>/dev/null | head -n 1)
    [ -n "$WIN" ] || { fail "$1: xdotool finds no window of pid $PID"; return 1; }
}
# quit NAME: Q, exit status 0 and the frame counters on stdout
quit() {
    xdotool key --window "$WIN" q 2>/dev/null # the key release may find the window gone
    wait "$PID"; rc=$?
    cat log.txt
    [ "$rc" -eq 0 ] || fail "$1: the viewer exited with $rc after Q"
    grep -q "^viewer: [0-9]* frames rendered ([0-9]* exact, [0-9]* preview)" log.txt ||
        fail "$1: no frame counters on exit"
}
