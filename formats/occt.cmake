# STEP and IGES through Open CASCADE (libocct-*-dev, setup/debian-packages.txt):
# the adapter step_adapter.cpp, linked into oit_formats_linked for the tools,
# and the plugin liboit-occt.so that liboit loads with dlopen
# (step_plugin.c), as glTF's (formats/CMakeLists.txt).
find_package(OpenCASCADE REQUIRED CONFIG)
# The toolkits the adapter calls: XDE readers for STEP and IGES, XCAF
# documents and their presentation styles, BRepMesh.
# One target carries them, with the headers, for the adapter and the tests
# that count with Open CASCADE (tests/formats/test_step.cpp).
add_library(oit_occt INTERFACE)
target_link_libraries(oit_occt INTERFACE TKXDESTEP TKXDEIGES TKSTEP TKIGES TKXSBase TKXCAF
                      TKRWMesh TKLCAF TKCAF TKMesh TKBRep TKMath TKernel TKTopAlgo TKG3d
                      TKGeomBase TKV3d TKService)
target_include_directories(oit_occt SYSTEM INTERFACE ${OpenCASCADE_INCLUDE_DIR})
set(OIT_OCCT_LIBS oit_occt)

add_library(oit_occt_adapter OBJECT step_adapter.cpp)
target_link_libraries(oit_occt_adapter PRIVATE oit_occt)
set_target_properties(oit_occt_adapter PROPERTIES POSITION_INDEPENDENT_CODE ON)

oit_add_reader_plugin(oit_occt_plugin oit-occt oit_occt_adapter step_plugin.map ${OIT_OCCT_LIBS})
