# tests for the part-file streamer: order, packing, upload, oitstream --method stream
oit_add_test_exe(test_order SOURCES test_order.c LIBS oit_partfile_write oit_image)
oit_add_test(NAME stream_order COMMAND $<TARGET_FILE:test_order> LABELS unit TIMEOUT 60)
oit_add_test_exe(test_streamer SOURCES test_streamer.c LIBS oit_partfile_write)
add_dependencies(test_streamer oitstream)
# Under ASan on 2 cores these take 100-250 s; the timeouts leave room for a
# slower CI machine or a busy one (at 120/300 s a busy run timed out).
oit_add_test(NAME stream_parts_grid LABELS integration TIMEOUT 400
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_streamer.sh grid $<TARGET_FILE:test_streamer>)
add_dependencies(test_streamer oitgen oitprep)
oit_add_test(NAME stream_parts_demo LABELS integration TIMEOUT 600
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_streamer.sh demo)
oit_add_test(NAME stream_parts_bunny LABELS integration TIMEOUT 600
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_streamer.sh bunny)
oit_add_test_exe(test_schedule SOURCES test_schedule.c LIBS oit_stream)
oit_add_test(NAME stream_schedule COMMAND $<TARGET_FILE:test_schedule> LABELS unit TIMEOUT 60)
# the residency cache's bookkeeping (no GL)
oit_add_test_exe(test_residency SOURCES test_residency.c LIBS oit_stream)
oit_add_test(NAME stream_residency COMMAND $<TARGET_FILE:test_residency> LABELS unit TIMEOUT 60)
# the upload pipeline through the streamer API: residency, identical images
# across ring, cache and thread settings, a corrupt part, clean teardown
oit_add_test_exe(test_upload SOURCES test_upload.c LIBS oit_stream)
set(upload_grid ${CMAKE_BINARY_DIR}/test-tmp/upload_grid.oitp)
oit_add_test(NAME stream_upload LABELS integration TIMEOUT 60
  COMMAND sh -c "$<TARGET_FILE:test_streamer> ${upload_grid} && $<TARGET_FILE:test_upload> ${upload_grid}")
# the first-K capture (--pack first-k): pixels far over its slots exact, the
# second pass reported, none without overflow, early termination
oit_add_test(NAME stream_firstk LABELS integration TIMEOUT 300
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_firstk.sh $<TARGET_FILE:test_streamer>)

# The stream's prim is the source triangle index: exact ties between
# duplicated boxes decided as on the source mesh (tests/test_source_prims.sh).
oit_add_test(NAME stream_source_prims LABELS integration TIMEOUT 120
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_source_prims.sh $<TARGET_FILE:test_sources>)

# GPU memory sized to the scene: a 256x256 frame of a small model within
# 16 MB (gpu_bytes_peak) in every pack mode, its image DFB's
# (tests/test_memory.sh, bench/memory-llvmpipe.md).
oit_add_test(NAME stream_memory LABELS integration TIMEOUT 300
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_memory.sh)
