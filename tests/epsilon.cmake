# tests for early termination of the part-file streamer (oitstream --epsilon)
oit_add_test(NAME stream_epsilon LABELS integration TIMEOUT 120
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_epsilon.sh $<TARGET_FILE:test_streamer>)
