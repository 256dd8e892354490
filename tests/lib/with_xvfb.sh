#!/bin/sh
# with_xvfb.sh SCREEN XVFB_RUN CMD...: runs CMD under a virtual X display of
# SCREEN (WxHxD) through XVFB_RUN, with LSan off (tests/CMakeLists.txt,
# oit_add_x11_test, says why). Checked when the test runs, not only when it
# was configured: a build carried to a machine without Xvfb (the GPU recipe)
# skips, saying so.
screen=$1 xvfb=$2
shift 2
[ -x "$xvfb" ] || { echo "SKIP: $xvfb not installed here"; exit 77; }
ASAN_OPTIONS=detect_leaks=0 exec "$xvfb" -a -s "-screen 0 $screen" "$@"
