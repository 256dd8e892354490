# tests for scenes (see CMakeLists.txt for oit_add_test / oit_add_test_exe / oit_add_fuzzer)
oit_add_test_exe(test_ply_writer SOURCES test_ply_writer.c LIBS oit_formats)
oit_add_test(NAME scenes_ply_writer COMMAND test_ply_writer LABELS unit TIMEOUT 60)

oit_add_test_exe(test_scene_shapes SOURCES test_scene_shapes.c LIBS oit_scenes)
oit_add_test(NAME scenes_shapes COMMAND test_scene_shapes LABELS unit TIMEOUT 60)

oit_add_test_exe(test_oitgen SOURCES test_oitgen.c LIBS oit_formats)
add_dependencies(test_oitgen oitgen)
oit_add_test(NAME scenes_oitgen COMMAND test_oitgen LABELS unit TIMEOUT 120)
