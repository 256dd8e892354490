# tests for formats (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
oit_add_test_exe(test_readers SOURCES test_readers.c LIBS oit_formats)
oit_add_test(NAME readers COMMAND test_readers LABELS unit TIMEOUT 60)


foreach(fmt ply obj off stl)
  oit_add_fuzzer(fuzz_${fmt} fuzz_reader.c LIBS oit_formats
                 CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/${fmt})
  if(TARGET fuzz_${fmt})
    target_compile_definitions(fuzz_${fmt} PRIVATE OIT_FUZZ_FORMAT=${fmt})
  endif()
endforeach()
