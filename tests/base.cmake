# tests for base/ (see CMakeLists.txt for oit_add_test / oit_add_test_exe):
# the strict number parsers and the JSON writer.
oit_add_test_exe(test_base SOURCES test_base.c LIBS oit_base)
oit_add_test(NAME base COMMAND test_base LABELS unit TIMEOUT 30)
