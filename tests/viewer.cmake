# tests for the interactive viewer (oitstream --window), under a virtual X
# display like gl_window in gl.cmake, and with leak checking off for the same
# reason: Mesa's X11 client libraries leave allocations LSan cannot name.
# viewer_interactive drives the window with real X events (xdotool).
find_program(OIT_XVFB_RUN xvfb-run)
if(OIT_XVFB_RUN)
  oit_add_test(NAME viewer LABELS integration TIMEOUT 120
    COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0
      ${OIT_XVFB_RUN} -a -s "-screen 0 640x480x24" sh ${CMAKE_CURRENT_SOURCE_DIR}/test_viewer.sh)
  oit_add_test(NAME viewer_interactive LABELS integration TIMEOUT 240
    COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0
      ${OIT_XVFB_RUN} -a -s "-screen 0 640x480x24" sh ${CMAKE_CURRENT_SOURCE_DIR}/test_viewer_interactive.sh)
else()
  oit_add_test(NAME viewer LABELS integration COMMAND sh -c "echo 'SKIP: xvfb-run not installed'; exit 77")
  oit_add_test(NAME viewer_interactive LABELS integration COMMAND sh -c "echo 'SKIP: xvfb-run not installed'; exit 77")
endif()
