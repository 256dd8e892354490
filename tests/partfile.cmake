# Part file reader/writer (docs/part-file.md) and `oitprep info`.
oit_add_test_exe(test_partfile SOURCES test_partfile.c LIBS oit_partfile_write)
add_dependencies(test_partfile oitprep)
oit_add_test(NAME partfile
  COMMAND test_partfile ${CMAKE_CURRENT_SOURCE_DIR}/corpus/partfile
  LABELS unit TIMEOUT 60)
oit_add_fuzzer(fuzz_partfile fuzz_partfile.c LIBS oit_partfile
  CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/partfile)
# Our meshopt decoders against libmeshoptimizer's (the oracle: its encoder
# writes the streams), and a differential fuzzer of the two.
oit_add_test_exe(test_meshopt_decode SOURCES test_meshopt_decode.c
  LIBS oit_partfile ${MESHOPT_LIBRARY} m)
oit_add_test(NAME meshopt_decode COMMAND test_meshopt_decode LABELS unit TIMEOUT 60)
oit_add_fuzzer(fuzz_meshopt_decode fuzz_meshopt_decode.c LIBS oit_partfile ${MESHOPT_LIBRARY}
  CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/meshopt)
