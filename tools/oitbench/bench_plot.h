/* oitbench's charts (PNG, drawn with chart.h), from the rows of results.csv
 * (bench_csv.h), so that a chart shows exactly what the file says:
 *
 *   speed_vs_error     one run: median ms per frame against mean rmse versus
 *                      the Embree reference (log), one marker and name per
 *                      entry, the Pareto front as a dashed line, rmse 0 drawn
 *                      at a labelled floor, entries that did not run listed
 *                      with their reason;
 *   memory_vs_depth    one or more runs: GPU MiB at peak against the view's
 *                      depth complexity (view_max_layers), a series per
 *                      method, a point per view of every run;
 *   time_vs_triangles  several runs: median ms against the model's
 *                      triangles, log-log, a series per method, a point per
 *                      run.
 *
 * A chart with nothing to show is still written, saying so on it. */
#ifndef OIT_OITBENCH_BENCH_PLOT_H
#define OIT_OITBENCH_BENCH_PLOT_H

#include "tools/oitbench/bench_csv.h"

/* Sets on_front[i] to 1 for the points no other point dominates (another j
 * with x[j] <= x[i] and y[j] <= y[i], better in one: faster and at least as
 * exact, or as fast and more exact), 0 for the rest and for points with a
 * non-finite coordinate. Equal points are both on the front. Returns how
 * many are on it. */
int oit_bench_pareto_front(const double *x, const double *y, int n, unsigned char *on_front);

/* The y value the speed chart draws rmse 0 at: a decade below the least
 * positive rmse of the summary rows that ran (1e-6 when there is none). */
double oit_bench_rmse_floor(const oit_bench_table *t);

/* title: the chart's first line (the model, say); subtitle may be NULL. */
oit_status oit_bench_plot_speed_error(const oit_bench_table *t, const char *title,
                                      const char *subtitle, const char *path, oit_error *err);

/* runs[0..n) are tables of one run each. */
oit_status oit_bench_plot_memory_depth(const oit_bench_table *runs, int n, const char *title,
                                       const char *subtitle, const char *path, oit_error *err);
oit_status oit_bench_plot_time_triangles(const oit_bench_table *runs, int n, const char *title,
                                         const char *subtitle, const char *path,
                                         oit_error *err);

#endif
