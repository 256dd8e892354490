# --help against behaviour for every numeric option (tests/test_help_ranges.sh).
oit_add_test(NAME help_ranges LABELS integration TIMEOUT 600
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_help_ranges.sh)
