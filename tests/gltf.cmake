# tests for gltf (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)

oit_add_test_exe(test_gltf SOURCES test_gltf.c LIBS oit_formats)
oit_add_test(NAME gltf COMMAND test_gltf ${CMAKE_CURRENT_SOURCE_DIR}/corpus/gltf LABELS unit TIMEOUT 60)

oit_add_test_exe(test_real_meshes SOURCES test_real_meshes.c LIBS oit_formats)
oit_add_test(NAME real_meshes COMMAND test_real_meshes LABELS integration TIMEOUT 120)

oit_add_fuzzer(fuzz_gltf fuzz_gltf.c LIBS oit_formats
               CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/gltf)
