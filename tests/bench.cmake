# oitbench: methods side by side against the reference, its files and exit codes;
# the in-core methods on the mesh and the stream on its part file (converted,
# given with --parts, or the input, with and without its source).
oit_add_test(NAME oitbench LABELS integration TIMEOUT 240
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_oitbench.sh)

# The chart module, the Pareto front, results.csv round trip and malformed
# files, a speed chart as PNG (no GL).
oit_add_test_exe(test_bench_plot SOURCES test_bench_plot.c LIBS oit_bench_files)
oit_add_test(NAME bench_plot COMMAND test_bench_plot LABELS unit TIMEOUT 60)

# oitbench's PNG charts, --epsilon sweep and `oitbench plot` end to end
# (png_figures tells a drawn chart from a blank one).
oit_add_test_exe(png_figures SOURCES png_figures.c LIBS oit_render oit_image_png)
oit_add_test(NAME oitbench_plots LABELS integration TIMEOUT 120
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_oitbench_plots.sh $<TARGET_FILE:png_figures>)

# results.csv reader under libFuzzer (only with -DOIT_FUZZ=ON)
oit_add_fuzzer(fuzz_bench_csv fuzz_bench_csv.c LIBS oit_bench_files
               CORPUS ${CMAKE_CURRENT_SOURCE_DIR}/corpus/bench_csv)
