/* oitbench's output files from one measurement (bench_run.h):
 * DIR/results.csv          one row per entry per view, then one summary row
 *                          per entry (bench_csv.h has the columns);
 * DIR/results.json         the same figures nested, with the run's settings;
 * DIR/speed_vs_error.png   and DIR/memory_vs_depth.png, drawn from
 *                          results.csv as written (bench_plot.h);
 * DIR/report.md            what each entry drew (source mesh or part file,
 *                          triangles), the conversion, a summary table, a
 *                          table per entry, the machine, the command line
 *                          and the two charts.
 * Non-finite figures (psnr of identical images, a method that never ran)
 * are empty in CSV, null in JSON, "-" or "inf" in the report. */
#ifndef OIT_OITBENCH_BENCH_REPORT_H
#define OIT_OITBENCH_BENCH_REPORT_H

#include "tools/oitbench/bench_models.h"
#include "tools/oitbench/bench_run.h"

typedef struct oit_bench_context {
    const char *model;
    const char *command_line;
    int width, height, frames, warmup;
    long cpus;
    unsigned long long triangles;   /* of the source model */
    const char *shading;            /* "transparent" or "translucent" */
    /* the source mesh, part file, conversion and notes; NULL: none said */
    const oit_bench_models *models;
} oit_bench_context;

/* One line per entry: name, geometry, triangles drawn, median and p95 ms,
 * mean rmse and worst %% of pixels off against the reference, GPU MiB; the
 * table oitbench prints on stdout and report.md starts with. */
void oit_bench_print_summary(FILE *f, const oit_bench_result *r, int markdown);

/* Creates dir when missing. */
oit_status oit_bench_write_reports(const char *dir, const oit_bench_context *ctx,
                                   const oit_bench_result *r, oit_error *err);

#endif
