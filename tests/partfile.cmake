# Part file reader/writer (docs/part-file.md) and `oitprep info`.
oit_add_test_exe(test_partfile SOURCES test_partfile.c LIBS oit_partfile_write)
add_dependencies(test_partfile oitprep)
oit_add_test(NAME partfile
  COMMAND test_partfile ${CMAKE_CURRENT_SOURCE_DIR}/corpus/partfile
  LABELS unit TIMEOUT 60)
oit_add_fuzzer(fuzz_partfile fuzz_partfile.c LIBS oit_partfile
  CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/partfile)
