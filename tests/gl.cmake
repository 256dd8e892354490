# tests for gl (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
# They run on whatever EGL offers: llvmpipe in CI, a GPU where there is one.
oit_add_test_exe(test_gl_context SOURCES test_gl_context.c LIBS oit_render)
oit_add_test(NAME gl_context COMMAND test_gl_context LABELS unit TIMEOUT 30)

oit_add_test_exe(test_dfb SOURCES test_dfb.c LIBS oit_render)
oit_add_test(NAME dfb COMMAND test_dfb LABELS unit TIMEOUT 60)

oit_add_test_exe(test_capture SOURCES test_capture.c LIBS oit_render)
oit_add_test(NAME capture COMMAND test_capture LABELS unit TIMEOUT 60)
