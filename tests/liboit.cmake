# tests for liboit, the public embedding API: drawing into a caller's FBO
# against DFB, and installing then linking from an outside project.
oit_add_test_exe(test_liboit SOURCES test_liboit.c LIBS oit oit_stream)
add_dependencies(test_liboit test_streamer)
set(liboit_grid ${CMAKE_BINARY_DIR}/test-tmp/liboit_grid.oitp)
oit_add_test(NAME liboit LABELS unit TIMEOUT 60
  COMMAND sh -c "$<TARGET_FILE:test_streamer> ${liboit_grid} && $<TARGET_FILE:test_liboit> ${liboit_grid}")

# An instrumented liboit.so needs the sanitizer runtime in the executable
# that loads it, so the outside project links with the same flags.
set(liboit_consumer_flags "")
if(OIT_SANITIZE)
  # liboit.so is C, but the glTF plugin it loads for a .gltf/.glb
  # (liboit-gltf.so) holds C++: its UBSan checks (vptr) need the C++ part
  # of the runtime in the executable, or the plugin fails to load.
  set(liboit_consumer_flags "-fsanitize=address,undefined -fsanitize-link-c++-runtime -lstdc++")
endif()
oit_add_test(NAME liboit_install LABELS integration TIMEOUT 180
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_install.sh ${CMAKE_BINARY_DIR} "${CMAKE_C_COMPILER}"
          ${OIT_PYTHON} "${liboit_consumer_flags}" "${OIT_PYTHON_PRELOAD}")

# The example must keep working: it is the API's documentation. A part file
# and mesh files (in core) through the same program; liboit_install builds
# it again against the installed package alone. The .glb (Draco) goes
# through the glTF plugin beside liboit.so, the .off.gz through the zlib
# liboit loads: the example links liboit alone, so nothing else can read them.
set(liboit_example_grid ${CMAKE_BINARY_DIR}/test-tmp/liboit_example.oitp)
set(liboit_example_ply ${CMAKE_BINARY_DIR}/test-tmp/liboit_example.ply)
oit_add_test(NAME liboit_example LABELS integration TIMEOUT 60
  COMMAND sh -c "$<TARGET_FILE:test_streamer> ${liboit_example_grid} && $<TARGET_FILE:embed_liboit> ${liboit_example_grid} ${CMAKE_BINARY_DIR}/test-tmp/liboit_example.ppm 160 120 && $<TARGET_FILE:oitgen> quads --count 16 -o ${liboit_example_ply} && $<TARGET_FILE:embed_liboit> ${liboit_example_ply} ${CMAKE_BINARY_DIR}/test-tmp/liboit_example_mesh.ppm 160 120 && $<TARGET_FILE:embed_liboit> ${CMAKE_SOURCE_DIR}/tests/corpus/gltf/draco.glb ${CMAKE_BINARY_DIR}/test-tmp/liboit_example_glb.ppm 160 120 && $<TARGET_FILE:embed_liboit> ${CMAKE_SOURCE_DIR}/tests/corpus/off/color.off.gz ${CMAKE_BINARY_DIR}/test-tmp/liboit_example_gz.ppm 160 120")

# In-core scenes (a mesh file, caller arrays) against the part file the
# test converts with oitprep, and the offscreen API's pixels.
oit_add_test_exe(test_liboit_incore SOURCES test_liboit_incore.c LIBS oit oit_formats)
oit_add_test(NAME liboit_incore LABELS integration TIMEOUT 120
  COMMAND $<TARGET_FILE:test_liboit_incore> $<TARGET_FILE:oitprep> ${CMAKE_BINARY_DIR}/test-tmp)

# The caller's opaque depth (oit_frame.depth_texture): an occluder drawn
# with depth, then the part file (every packing) and the in-core scene,
# against DFB of the scene with the occluder as alpha-1 triangles.
oit_add_test_exe(test_liboit_depth SOURCES test_liboit_depth.c LIBS oit oit_stream)
add_dependencies(test_liboit_depth test_streamer)
set(liboit_depth_grid ${CMAKE_BINARY_DIR}/test-tmp/liboit_depth_grid.oitp)
oit_add_test(NAME liboit_depth LABELS unit TIMEOUT 120
  COMMAND sh -c "$<TARGET_FILE:test_streamer> ${liboit_depth_grid} && $<TARGET_FILE:test_liboit_depth> ${liboit_depth_grid}")

# The shared library's boundary: it exports include/oit/'s functions only,
# and links only libc, libm, pthreads, libdl and the GL/EGL loaders (with
# the sanitizer runtimes when the build is instrumented).
oit_add_test(NAME liboit_exports LABELS unit TIMEOUT 30
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_liboit_exports.sh $<TARGET_FILE:oit>
          ${CMAKE_SOURCE_DIR}/include/oit $<$<BOOL:${OIT_SANITIZE}>:sanitize>)
