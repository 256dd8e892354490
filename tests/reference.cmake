# tests for reference (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
oit_add_test_exe(test_shade SOURCES test_shade.c LIBS oit_image)
oit_add_test(NAME shade COMMAND test_shade LABELS unit TIMEOUT 20)

oit_add_test_exe(test_image SOURCES test_image.c LIBS oit_image_png)
oit_add_test(NAME image COMMAND test_image LABELS unit TIMEOUT 20)

oit_add_test_exe(test_reference SOURCES test_reference.c LIBS oit_reference)
oit_add_test(NAME reference COMMAND test_reference LABELS unit TIMEOUT 30)

# oitstream end to end (tests/test_oitstream.sh says what each part checks).
foreach(part cli scene meshes)
  oit_add_test(NAME oitstream_${part} LABELS integration TIMEOUT 120
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_oitstream.sh ${part})
endforeach()

# The image readers behind --compare: the corpus files start with one byte
# that selects the format (odd: PNG, even: PFM).
oit_add_fuzzer(fuzz_image fuzz_image.c LIBS oit_image_png
               CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/image)
