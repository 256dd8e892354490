# partition/ kernels and oitprep end to end (tests/test_prep.sh says what it checks).
oit_add_test_exe(test_partition SOURCES test_partition.c LIBS oit_partition)
oit_add_test(NAME partition COMMAND test_partition LABELS unit TIMEOUT 30)
oit_add_test_exe(test_grid_phase SOURCES test_grid_phase.c LIBS oit_preprocess)
oit_add_test(NAME grid_phase COMMAND test_grid_phase LABELS unit TIMEOUT 30)

oit_add_test(NAME prep LABELS integration TIMEOUT 120
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_prep.sh)

# oitprep verify's slab-side check on a hand-written file, good and bad.
oit_add_test(NAME verify_slab LABELS integration TIMEOUT 60
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_verify_slab.sh $<TARGET_FILE:test_streamer>)

# Pinned piece and part counts (and the file's hash) on CAD-like fetched meshes.
oit_add_test(NAME prep_pinned LABELS integration TIMEOUT 60
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_prep_pinned.sh)

# Every part triangle carries its source triangle's index: both schemes,
# clipping, spilling and threads, checked by area against the source mesh.
oit_add_test_exe(test_sources SOURCES test_sources.c LIBS oit_partfile_write oit_partition)
oit_add_test(NAME prep_sources LABELS integration TIMEOUT 300
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_sources.sh $<TARGET_FILE:test_sources>)
