# oitbench: methods side by side against the reference, its files and exit codes.
oit_add_test(NAME oitbench LABELS integration TIMEOUT 60
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_oitbench.sh)
