# Install rules of liboit: the public headers, the shared library and its
# glTF plugin, a CMake package exporting oit::oit and a pkg-config file, the
# tools (oitprep among them, which the Python package's oit.prep runs) and
# the Python package, all relocatable (nothing records the configure-time prefix), so
# `cmake --install B --prefix P` works for any P.
include(CMakePackageConfigHelpers)

install(TARGETS oit EXPORT oitTargets
        LIBRARY DESTINATION lib
        ARCHIVE DESTINATION lib
        RUNTIME DESTINATION bin)
# The glTF plugin, beside liboit.so: liboit loads it from its own folder
# when a .gltf/.glb is opened (formats/gltf_plugin.c). Nothing links it, so
# it is not part of the exported targets.
install(TARGETS oit_gltf_plugin LIBRARY DESTINATION lib)
# The assimp plugin likewise, for every other mesh format (formats/assimp_plugin.c).
install(TARGETS oit_assimp_plugin LIBRARY DESTINATION lib)
install(TARGETS oit_occt_plugin LIBRARY DESTINATION lib) # STEP/IGES, formats/step_plugin.c
# The Embree reference likewise, which liboit loads to offer the reference
# method (view/render/reference/reference_plugin.h).
install(TARGETS oit_reference_plugin LIBRARY DESTINATION lib)
install(FILES
        ${CMAKE_SOURCE_DIR}/include/oit/oit.h
        ${CMAKE_SOURCE_DIR}/include/oit/status.h
        ${CMAKE_SOURCE_DIR}/include/oit/export.h
        ${CMAKE_SOURCE_DIR}/include/oit/mesh.h
        ${CMAKE_SOURCE_DIR}/include/oit/partfile.h
        ${CMAKE_SOURCE_DIR}/include/oit/liboit.h
        ${CMAKE_SOURCE_DIR}/include/oit/render_modes.h
        ${CMAKE_SOURCE_DIR}/include/oit/draw_stats.h
        ${CMAKE_SOURCE_DIR}/include/oit/pick.h
        ${CMAKE_SOURCE_DIR}/include/oit/frame.h
        ${CMAKE_SOURCE_DIR}/include/oit/offscreen.h
        DESTINATION include/oit)
# The part-file format, which oit/partfile.h cites: the one document a
# reader of that header needs and would otherwise find only in the sources.
install(FILES ${CMAKE_SOURCE_DIR}/docs/part-file.md DESTINATION share/doc/oit)
install(EXPORT oitTargets NAMESPACE oit:: DESTINATION lib/cmake/oit)

configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/oitConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/oitConfig.cmake INSTALL_DESTINATION lib/cmake/oit)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/oitConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/oitConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/oitConfigVersion.cmake
        DESTINATION lib/cmake/oit)

configure_file(${CMAKE_SOURCE_DIR}/cmake/oit.pc.in ${CMAKE_BINARY_DIR}/cmake/oit.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/cmake/oit.pc DESTINATION lib/pkgconfig)

# Every tool (README, Tools). They link our libraries statically and only
# system libraries dynamically, but for oitstream and oitbench, whose stream
# method is liboit.so's public API (tools/common/method_stream.h): they find
# it beside the installed tree.
set_target_properties(oitstream oitbench PROPERTIES INSTALL_RPATH "$ORIGIN/../lib")
install(TARGETS oitgen oitprep oitstream oitbench oit_meshinfo RUNTIME DESTINATION bin)
include(${CMAKE_SOURCE_DIR}/cmake/python.cmake)
