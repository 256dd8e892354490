/* oitbench's output files from one measurement (bench_run.h):
 * DIR/results.csv  one row per method per view, then one summary row per
 *                  method (column "row": view | summary);
 * DIR/results.json the same figures nested, for data_scripts/plot_bench.py;
 * DIR/report.md    a table per method, the machine and the command line.
 * Non-finite figures (psnr of identical images, a method that never ran)
 * are empty in CSV, null in JSON, "-" or "inf" in the report. */
#ifndef OIT_STREAM_BENCH_REPORT_H
#define OIT_STREAM_BENCH_REPORT_H

#include "stream/bench_run.h"

typedef struct oit_bench_context {
    const char *model;
    const char *command_line;
    int width, height, frames, warmup;
    long cpus;
} oit_bench_context;

/* Creates dir when missing. */
oit_status oit_bench_write_reports(const char *dir, const oit_bench_context *ctx,
                                   const oit_bench_result *r, oit_error *err);

#endif
