# python/tests: the Python package (python/oit) over this build's liboit.so
# and oitprep, checking real pixels (`python3 -m pytest python`).
set(oit_python_env
  OIT_LIBRARY=$<TARGET_FILE:oit> OIT_PREP=$<TARGET_FILE:oitprep>
  PYTHONPATH=${CMAKE_SOURCE_DIR}/python PYTHONDONTWRITEBYTECODE=1)
# An instrumented liboit.so needs the sanitizer runtime in the process that
# loads it: python3 gets the shared one preloaded. Leak checking is off for
# it (the interpreter's own allocations read as leaks; the C tests check
# liboit's under LSan).
set(OIT_PYTHON_PRELOAD "")
if(OIT_SANITIZE)
  if(CMAKE_C_COMPILER_ID STREQUAL "Clang")
    execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libclang_rt.asan-${CMAKE_SYSTEM_PROCESSOR}.so
                    OUTPUT_VARIABLE OIT_PYTHON_PRELOAD OUTPUT_STRIP_TRAILING_WHITESPACE)
  else()
    execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libasan.so
                    OUTPUT_VARIABLE OIT_PYTHON_PRELOAD OUTPUT_STRIP_TRAILING_WHITESPACE)
  endif()
  # oitprep, which oit.prep runs, has the static runtime: not the preload.
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/tests/oitprep-unpreloaded
       CONTENT "#!/bin/sh\nunset LD_PRELOAD\nexec '$<TARGET_FILE:oitprep>' \"$@\"\n"
       FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                        WORLD_READ WORLD_EXECUTE)
  list(TRANSFORM oit_python_env REPLACE "^OIT_PREP=.*" "OIT_PREP=${CMAKE_BINARY_DIR}/tests/oitprep-unpreloaded")
  list(APPEND oit_python_env LD_PRELOAD=${OIT_PYTHON_PRELOAD} ASAN_OPTIONS=detect_leaks=0)
endif()
oit_add_test(NAME python_oit LABELS integration TIMEOUT 300
  COMMAND ${CMAKE_COMMAND} -E env ${oit_python_env}
          ${OIT_PYTHON} -m pytest -q -p no:cacheprovider ${CMAKE_SOURCE_DIR}/python)
