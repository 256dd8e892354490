# The bad-input battery (tests/test_bad_input.sh says what it runs and checks).
oit_add_test(NAME bad_input LABELS integration TIMEOUT 600
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_bad_input.sh)
