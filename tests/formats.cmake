# tests for formats (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
