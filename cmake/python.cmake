# The Python package python/oit (ctypes over liboit.so, numpy): installed
# with liboit so that `import oit` finds the library beside it, and tested
# by python/tests (tests/python/CMakeLists.txt).
set(OIT_PYTHON /usr/bin/python3 CACHE FILEPATH
    "the Python 3 that runs python/tests (Debian's, with python3-numpy and python3-pytest)")
set(OIT_PYTHON_INSTALL_DIR "lib/python3/dist-packages" CACHE STRING
    "where cmake --install puts the package oit, relative to the prefix; Debian's python3 \
reads PREFIX/lib/python3/dist-packages for PREFIX /usr (for /usr/local: lib/python3.11/dist-packages)")
if(IS_ABSOLUTE "${OIT_PYTHON_INSTALL_DIR}")
  message(FATAL_ERROR "OIT_PYTHON_INSTALL_DIR must be relative to the install prefix, "
                      "so that the package finds liboit.so beside it: ${OIT_PYTHON_INSTALL_DIR}")
endif()
# The installed package finds liboit.so and oitprep relative to itself.
file(RELATIVE_PATH OIT_PY_LIBDIR /p/${OIT_PYTHON_INSTALL_DIR}/oit /p/lib)
file(RELATIVE_PATH OIT_PY_BINDIR /p/${OIT_PYTHON_INSTALL_DIR}/oit /p/bin)
file(WRITE ${CMAKE_BINARY_DIR}/python/_install_paths.py
  "# Written by cmake --install: liboit.so and oitprep relative to this folder.\n"
  "LIBDIR = \"${OIT_PY_LIBDIR}\"\nBINDIR = \"${OIT_PY_BINDIR}\"\n")
install(FILES ${CMAKE_SOURCE_DIR}/python/oit/__init__.py ${CMAKE_SOURCE_DIR}/python/oit/_lib.py
              ${CMAKE_SOURCE_DIR}/python/oit/_png.py ${CMAKE_BINARY_DIR}/python/_install_paths.py
        DESTINATION ${OIT_PYTHON_INSTALL_DIR}/oit)
