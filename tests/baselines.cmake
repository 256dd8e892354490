# tests for the baseline methods (unsorted, WBOIT, PLL, paged PLL, B3D, depth
# peeling, dual depth peeling, guarded OIT, F2B) against DFB
oit_add_test_exe(test_baselines SOURCES test_baselines.c LIBS oit_baselines oit_reference)
oit_add_test(NAME baselines COMMAND test_baselines LABELS unit TIMEOUT 60)

# The baselines through oitstream --method (and oitbench), against --method dfb.
oit_add_test(NAME baselines_cli LABELS integration TIMEOUT 180
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_baselines_cli.sh)
