# tests for gl (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
# They run on whatever EGL offers: llvmpipe in CI, a GPU where there is one.
oit_add_test_exe(test_gl_context SOURCES test_gl_context.c LIBS oit_window)
oit_add_test(NAME gl_context COMMAND test_gl_context LABELS unit TIMEOUT 30)

oit_add_test_exe(test_dfb SOURCES test_dfb.c LIBS oit_render)
oit_add_test(NAME dfb COMMAND test_dfb LABELS unit TIMEOUT 60)

oit_add_test_exe(test_capture SOURCES test_capture.c LIBS oit_render)
oit_add_test(NAME capture COMMAND test_capture LABELS unit TIMEOUT 60)

# multi-draw grouping against drawing mesh by mesh (gpu_mesh.h)
oit_add_test_exe(test_gpu_draws SOURCES test_gpu_draws.c LIBS oit_render)
oit_add_test(NAME gpu_draws COMMAND test_gpu_draws LABELS unit TIMEOUT 60)

# The GLFW window path, under a virtual X display (xvfb-run from the xvfb
# package, installed by setup/install-deps.sh). Skipped when xvfb-run is absent.
oit_add_test_exe(test_gl_window SOURCES test_gl_window.c LIBS oit_window oit_image_png)
find_program(OIT_XVFB_RUN xvfb-run)
if(OIT_XVFB_RUN)
  # Leak checking is off here only: the X11 client libraries that Mesa loads
  # and unloads leave allocations whose module LSan can no longer name, so no
  # suppression can match them. Our code's leaks are checked by the headless
  # tests, which run the same DFB path.
  oit_add_test(NAME gl_window LABELS unit TIMEOUT 60
    COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0 ${OIT_XVFB_RUN} -a -s "-screen 0 320x240x24" $<TARGET_FILE:test_gl_window>)
else()
  oit_add_test(NAME gl_window LABELS unit COMMAND sh -c "echo 'SKIP: xvfb-run not installed'; exit 77")
endif()

# Binding points come from render/glsl_bindings.h on both sides: no GLSL
# layout(binding = N) or glBind*(N) with a number in its place; the
# self-test checks that the patterns still catch a planted literal.
oit_add_test(NAME glsl_bindings LABELS unit TIMEOUT 30
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_glsl_bindings.sh ${CMAKE_SOURCE_DIR})
oit_add_test(NAME glsl_bindings_selftest LABELS unit TIMEOUT 30
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_glsl_bindings.sh --self-test ${CMAKE_BINARY_DIR}/test-tmp)
