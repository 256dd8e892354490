/* results.csv, the file oitbench writes for every run, in both directions:
 * written from a measurement (bench_run.h) and read back, strictly, by
 * `oitbench plot` and by the run's own charts, so that a chart always shows
 * what the file says.
 *
 * One header line (OIT_BENCH_CSV_HEADER), then one row per entry per view
 * (row = view) and one summary row per entry (row = summary, view empty).
 * Figures a row does not have are empty: every figure of an entry that did
 * not run; ms of a view it failed on; psnr of identical images is "inf".
 * reason is the only quoted field ("" inside stands for "); it is empty
 * unless status is not_runnable. triangles (the source model's, the one
 * count of the file) is on every row; view_max_layers is the depth
 * complexity of the view (the most hits the reference met at one pixel), on
 * a summary row the most over the views. geometry says which triangles the
 * entry drew (source_mesh, or part_file: the part file's, clipped at part
 * boundaries) and drawn_triangles how many, on not_runnable rows too (what
 * it would have drawn).
 *
 * gpu_ms_median is the median GPU time of the timed frames (GL timestamp
 * queries, view/render/gl/gpu_timer.h), empty where the method was not timed on
 * the GPU (no GL, no timestamps, or not run).
 *
 * gpu_bytes_peak is every GPU buffer and texture the entry held at its
 * peak: an in-core method's working memory and the mesh it uploaded, the
 * stream's ring, cache, capture and per-pixel state; gpu_mesh_bytes is the
 * mesh's part of it (0 for the stream and the reference), both empty
 * where the entry did not run.
 *
 * pct_over_1_255 is the % of all pixels with a channel off the reference by
 * more than 1/255; pct_over_1_255_outside_ambiguity the same % over the
 * pixels outside the reference's ambiguity mask (a pixel centre within the
 * ambiguity radius of an edge, where rasterization and the ray may
 * disagree: oit_pixels_desc.ambiguous), ~0 for an exact method, whose
 * pct_over_1_255 counts those edge pixels too; a summary row has the worst
 * view's of both.
 *
 * The reader also takes the file of the oitbench before geometry
 * (OIT_BENCH_CSV_HEADER_15, 15 fields); its rows read with geometry -1 and
 * drawn_triangles = triangles; the one before gpu_ms_median
 * (OIT_BENCH_CSV_HEADER_17), read with gpu_ms_median -1; and the one
 * before gpu_mesh_bytes (OIT_BENCH_CSV_HEADER_18), whose in-core methods'
 * gpu_bytes_peak left their mesh out: read with mesh_counted 0; and the
 * one before pct_over_1_255_outside_ambiguity (OIT_BENCH_CSV_HEADER_19),
 * read with it NAN. The new column is the last, so that a reader of the
 * older file that picks columns by position still finds the others. */
#ifndef OIT_OITBENCH_BENCH_CSV_H
#define OIT_OITBENCH_BENCH_CSV_H

#include <stdint.h>
#include <stdio.h>

#include "tools/oitbench/bench_run.h"

#define OIT_BENCH_CSV_HEADER_15                                                          \
    "row,method,view,status,ms_median,ms_p95,gpu_bytes_peak,max_layers,rmse,max_abs,"    \
    "pct_over_1_255,psnr,reason,triangles,view_max_layers"
#define OIT_BENCH_CSV_HEADER_17 OIT_BENCH_CSV_HEADER_15 ",geometry,drawn_triangles"
#define OIT_BENCH_CSV_HEADER_18 OIT_BENCH_CSV_HEADER_17 ",gpu_ms_median"
#define OIT_BENCH_CSV_HEADER_19 OIT_BENCH_CSV_HEADER_18 ",gpu_mesh_bytes"
#define OIT_BENCH_CSV_HEADER OIT_BENCH_CSV_HEADER_19 ",pct_over_1_255_outside_ambiguity"

#define OIT_BENCH_CSV_REASON_MAX 512

/* One line of the file; figures it leaves empty are NAN (for ms, rmse,
 * max_abs, pct, psnr) or 0 with has_gpu = 0 (gpu bytes and max_layers,
 * which the writer leaves empty together). */
typedef struct oit_bench_row {
    int summary;                    /* 0: a view row */
    char method[OIT_BENCH_NAME_MAX];
    int view;                       /* -1 on a summary row */
    int ok;                         /* status ok; else not_runnable */
    double ms_median, ms_p95;
    int has_gpu;
    uint64_t gpu_bytes_peak;
    uint32_t max_layers;
    double rmse, max_abs, pct_over_1_255, psnr;
    char reason[OIT_BENCH_CSV_REASON_MAX];
    uint64_t triangles;
    uint32_t view_max_layers;
    int geometry;                   /* oit_bench_geometry; -1: an older file */
    uint64_t drawn_triangles;
    double gpu_ms_median;           /* -1: empty */
    /* 1: gpu_bytes_peak counts the in-core mesh, gpu_mesh_bytes of it; 0:
     * a file older than the column, whose in-core figures leave it out. */
    int mesh_counted;
    uint64_t gpu_mesh_bytes;
    /* pct_over_1_255 outside the reference's ambiguity mask; NAN where
     * empty or the file is older than the column */
    double pct_over_outside_ambiguity;
} oit_bench_row;

typedef struct oit_bench_table {
    oit_bench_row *rows;
    size_t count;
} oit_bench_table;

/* Writes the whole file for r; triangles is the source model's count. */
void oit_bench_csv_write(FILE *f, const oit_bench_result *r, uint64_t triangles);
/* x printed with fmt into buf, or nonfinite when x is not finite (CSV and
 * JSON spell a missing figure differently). Returns buf. */
const char *oit_bench_number(char *buf, size_t cap, double x, const char *fmt,
                             const char *nonfinite);

/* Reads a file as oit_bench_csv_write writes it, and nothing else: the
 * exact header, 20 fields a row (19, 18, 17 or 15 after the older headers), every field checked (row kind, method
 * name, view number, status, numbers finite and >= 0, figures present
 * exactly where the status says, reason quoted, one triangle count in the
 * whole file). A failure is OIT_ERR_FORMAT (OIT_ERR_IO when reading fails)
 * with a message "NAME: line L: ..."; t is then empty. name is used in
 * messages only. */
oit_status oit_bench_csv_read(FILE *f, const char *name, oit_bench_table *t, oit_error *err);
/* The same from a path (OIT_ERR_IO when it cannot be opened). */
oit_status oit_bench_csv_load(const char *path, oit_bench_table *t, oit_error *err);
void oit_bench_table_free(oit_bench_table *t);

#endif
