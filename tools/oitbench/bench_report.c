/* oitbench's output files (bench_report.h). */
#include "tools/oitbench/bench_report.h"

#include "tools/oitbench/bench_csv.h"
#include "tools/oitbench/bench_plot.h"
#include "base/json.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* ---- output files ---- */

static oit_status open_out(const char *dir, const char *name, FILE **f, char *path, size_t cap,
                           oit_error *err)
{
    snprintf(path, cap, "%s/%s", dir, name);
    *f = fopen(path, "w");
    if (!*f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    return OIT_OK;
}

static oit_status close_out(FILE *f, const char *path, oit_error *err)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed", path);
    return OIT_OK;
}

/* ---- results.json ---- */

/* One view of one method: its figures, null where it did not run. */
static void json_cell(oit_json *w, int v, const oit_bench_cell *c)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_int(w, "view", v);
    oit_json_bool(w, "ok", c->ok);
    oit_json_fixed(w, "ms_median", c->ok ? c->ms_median : NAN, 4);
    oit_json_fixed(w, "ms_p95", c->ok ? c->ms_p95 : NAN, 4);
    oit_json_fixed(w, "gpu_ms_median", c->ok ? c->gpu_ms_median : NAN, 4);
    oit_json_uint(w, "gpu_bytes_peak", c->gpu_bytes_peak);
    oit_json_uint(w, "gpu_mesh_bytes", c->gpu_mesh_bytes);
    oit_json_uint(w, "max_layers", c->max_layers);
    oit_json_uint(w, "host_waits_max", c->host_waits_max);
    oit_json_uint(w, "fragments", c->fragments);
    oit_json_general(w, "rmse", c->ok ? c->diff.rmse : NAN, 9);
    oit_json_general(w, "max_abs", c->ok ? c->diff.max_abs : NAN, 9);
    oit_json_fixed(w, "pct_over_1_255", c->ok ? c->diff.pct_over_1_255 : NAN, 6);
    oit_json_fixed(w, "pct_over_1_255_outside_ambiguity",
                   c->ok ? c->pct_over_outside_ambiguity : NAN, 6);
    oit_json_fixed(w, "psnr", c->ok ? c->diff.psnr : NAN, 4);
    oit_json_end(w);
}

/* A method's summary, then its views, each on a line of its own. */
static void json_method(oit_json *w, const oit_bench_method *m, int views)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_string(w, "name", m->name);
    oit_json_string(w, "method", m->method->name);
    oit_json_general(w, "epsilon", m->epsilon >= 0.0f ? m->epsilon : NAN, 6);
    oit_json_string(w, "geometry",
                    m->geometry == OIT_BENCH_GEOMETRY_PART_FILE ? "part_file" : "source_mesh");
    oit_json_uint(w, "triangles", m->triangles);
    oit_json_bool(w, "runnable", m->runnable);
    oit_json_string(w, "reason", m->reason);
    oit_json_uint(w, "timed_frames", m->ms_count);
    oit_json_fixed(w, "ms_median", m->ms_median, 4);
    oit_json_fixed(w, "ms_p95", m->ms_p95, 4);
    oit_json_fixed(w, "gpu_ms_median", m->runnable ? m->gpu_ms_median : NAN, 4);
    oit_json_uint(w, "gpu_bytes_peak", m->gpu_bytes_peak);
    oit_json_uint(w, "gpu_mesh_bytes", m->gpu_mesh_bytes);
    oit_json_uint(w, "max_layers", m->max_layers);
    oit_json_uint(w, "host_waits_max", m->host_waits_max);
    oit_json_general(w, "rmse_mean", m->runnable ? m->rmse_mean : NAN, 9);
    oit_json_general(w, "max_abs_worst", m->runnable ? m->max_abs_worst : NAN, 9);
    oit_json_fixed(w, "pct_over_1_255_worst", m->runnable ? m->pct_over_worst : NAN, 6);
    oit_json_fixed(w, "pct_over_1_255_outside_ambiguity_worst",
                   m->runnable ? m->pct_over_outside_ambiguity_worst : NAN, 6);
    oit_json_fixed(w, "psnr_min", m->runnable ? m->psnr_min : NAN, 4);
    oit_json_break(w, 5);
    oit_json_begin_array(w, "views", OIT_JSON_INLINE);
    for (int v = 0; v < views; v++) {
        if (v)
            oit_json_break(w, 7);
        json_cell(w, v, &m->cells[v]);
    }
    oit_json_end(w);
    oit_json_end(w);
}

/* The source mesh, the part file and the conversion, as JSON members. */
static void json_models(oit_json *w, const oit_bench_models *m)
{
    oit_json_break(w, 2);
    oit_json_string(w, "source_mesh", m->have_source ? m->source_path : NULL);
    oit_json_uint(w, "source_triangles", m->source_triangles);
    oit_json_break(w, 2);
    oit_json_string(w, "part_file", m->conv.done && !m->conv.kept ? "(temporary, removed)"
                                    : m->parts_path[0]            ? m->parts_path
                                                                  : NULL);
    oit_json_uint(w, "part_file_triangles", m->part_triangles);
    if (m->conv.done) {
        oit_json_break(w, 2);
        oit_json_begin_object(w, "conversion", OIT_JSON_INLINE);
        oit_json_string(w, "scheme", m->conv.scheme);
        oit_json_uint(w, "part_triangles", m->conv.part_triangles);
        oit_json_fixed(w, "seconds", m->conv.seconds, 3);
        oit_json_uint(w, "triangles_in", m->conv.triangles_in);
        oit_json_uint(w, "triangles_out", m->conv.triangles_out);
        oit_json_uint(w, "parts", m->conv.parts);
        oit_json_end(w);
    }
    oit_json_break(w, 2);
    oit_json_string(w, "reference_geometry", m->have_source ? "source_mesh" : "part_file");
    oit_json_break(w, 2);
    oit_json_begin_array(w, "notes", OIT_JSON_INLINE);
    for (int i = 0; i < m->note_count; i++)
        oit_json_string(w, NULL, m->notes[i]);
    oit_json_end(w);
}

/* The run's settings on a few lines, then one line per method and view. */
static void write_json(oit_json *w, const oit_bench_context *ctx, const oit_bench_result *r)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_break(w, 2);
    oit_json_string(w, "model", ctx->model);
    if (ctx->models)
        json_models(w, ctx->models);
    oit_json_break(w, 2);
    oit_json_string(w, "command", ctx->command_line);
    oit_json_break(w, 2);
    oit_json_string(w, "renderer", r->renderer);
    /* the run's sizes, all counts (>= 0) */
    const oit_json_uint_member sizes[] = {
        {"width", (unsigned)ctx->width}, {"height", (unsigned)ctx->height},
        {"views", (unsigned)r->views}, {"frames", (unsigned)ctx->frames},
        {"warmup", (unsigned)ctx->warmup}};
    oit_json_break(w, 2);
    oit_json_int(w, "cpus", ctx->cpus);
    oit_json_uint(w, "triangles", ctx->triangles);
    oit_json_string(w, "shading", ctx->shading);
    OIT_JSON_UINTS(w, sizes);
    oit_json_break(w, 2);
    oit_json_begin_array(w, "reference_ms", OIT_JSON_INLINE);
    for (int v = 0; v < r->views; v++)
        oit_json_fixed(w, NULL, r->ref_ms[v], 4);
    oit_json_end(w);
    oit_json_break(w, 2);
    oit_json_begin_array(w, "reference_max_layers", OIT_JSON_INLINE);
    for (int v = 0; v < r->views; v++)
        oit_json_uint(w, NULL, r->ref_layers[v]);
    oit_json_end(w);
    oit_json_break(w, 2);
    oit_json_begin_array(w, "reference_ambiguous_pct", OIT_JSON_INLINE);
    for (int v = 0; v < r->views; v++)
        oit_json_fixed(w, NULL, r->ref_ambiguous_pct[v], 6);
    oit_json_end(w);
    oit_json_break(w, 2);
    oit_json_begin_array(w, "methods", OIT_JSON_BLOCK);
    for (int i = 0; i < r->method_count; i++)
        json_method(w, &r->methods[i], r->views);
    oit_json_end(w);
    oit_json_break(w, 0);
    oit_json_end(w);
}

/* ---- report.md ---- */

static void md_method(FILE *f, const oit_bench_method *m, const oit_bench_result *r)
{
    int views = r->views;
    char b[9][40];
    fprintf(f, "## %s\n\nDrew the %s: %llu triangles.\n\n", m->name,
            oit_bench_geometry_label(m->geometry, m->triangles, m->source_triangles),
            (unsigned long long)m->triangles);
    if (!m->runnable && m->ms_count == 0) {
        fprintf(f, "Not runnable: %s\n\n", m->reason);
        return;
    }
    if (!m->runnable)
        fprintf(f, "Stopped: %s (figures below are over the views it rendered)\n\n", m->reason);
    fprintf(f, "| view | depth | ms median | ms p95 | GPU MiB peak | max layers | rmse | "
               "max_abs | %% over 1/255 | %% over 1/255 outside ambiguity | PSNR dB |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int v = 0; v < views; v++) {
        const oit_bench_cell *c = &m->cells[v];
        if (!c->ok) {
            fprintf(f, "| %d | %u | - | - | - | - | - | - | - | - | - |\n", v, r->ref_layers[v]);
            continue;
        }
        fprintf(f, "| %d | %u | %.3f | %.3f | %.2f | %u | %.3g | %.3g | %.4f | %.4f | %s |\n", v,
                r->ref_layers[v], c->ms_median, c->ms_p95, (double)c->gpu_bytes_peak / 1048576.0,
                c->max_layers,
                c->diff.rmse, c->diff.max_abs, c->diff.pct_over_1_255,
                c->pct_over_outside_ambiguity,
                oit_bench_number(b[0], 40, c->diff.psnr, "%.2f", "inf"));
    }
    fprintf(f, "| **all** | | **%s** | **%s** | %.2f | %u | %s (mean) | %s (worst) | %s (worst) | "
               "%s (worst) | %s (min) |\n\n",
            oit_bench_number(b[1], 40, m->ms_median, "%.3f", "-"), oit_bench_number(b[2], 40, m->ms_p95, "%.3f", "-"),
            (double)m->gpu_bytes_peak / 1048576.0, m->max_layers,
            oit_bench_number(b[3], 40, m->rmse_mean, "%.3g", "-"), oit_bench_number(b[4], 40, m->max_abs_worst, "%.3g", "-"),
            oit_bench_number(b[5], 40, m->pct_over_worst, "%.4f", "-"),
            oit_bench_number(b[7], 40, m->pct_over_outside_ambiguity_worst, "%.4f", "-"),
            oit_bench_number(b[6], 40, m->psnr_min, "%.2f", "inf"));
}

/* What the methods drew: the source mesh, the part file, the conversion. */
static void md_models(FILE *f, const oit_bench_models *m)
{
    if (m->have_source)
        fprintf(f, "- source mesh: %s, %llu triangles; the in-core methods and the reference "
                   "draw it\n", m->source_path, (unsigned long long)m->source.count);
    else
        fprintf(f, "- source mesh: not at hand; the in-core methods and the reference draw "
                   "the part file's clipped triangles (the source had %llu)\n",
                (unsigned long long)m->source_triangles);
    if (m->conv.done)
        fprintf(f, "- part file: converted in this run (%s%s), scheme %s, %.2f s, %llu "
                   "triangles in, %llu out, %llu parts\n",
                m->conv.kept ? "kept as " : "temporary, removed",
                m->conv.kept ? m->parts_path : "", m->conv.scheme, m->conv.seconds,
                (unsigned long long)m->conv.triangles_in,
                (unsigned long long)m->conv.triangles_out, (unsigned long long)m->conv.parts);
    else if (m->parts_path[0])
        fprintf(f, "- part file: %s, %llu triangles (clipped at part boundaries)\n",
                m->parts_path, (unsigned long long)m->part_triangles);
    for (int i = 0; i < m->note_count; i++)
        fprintf(f, "- **note**: %s\n", m->notes[i]);
}

/* What the two error columns mean, under the summary table. */
/* What the two error columns mean, under the summary table. */
static void print_error_legend(FILE *f, int markdown)
{
    if (!markdown) {
        fprintf(f, "  %% >1/255: pixels off the reference by > 1/255; %% unamb.: the same outside "
                   "the reference's\n  ambiguity mask (edge pixels where raster and ray may "
                   "disagree): ~0 for exact methods\n");
        return;
    }
    fprintf(f, "Errors: *worst %% over 1/255* (`pct_over_1_255` in results.csv) is the %% of "
               "all pixels with a channel off the reference by more than 1/255; *worst %% over "
               "1/255 outside ambiguity* (`pct_over_1_255_outside_ambiguity`) is the same over "
               "the pixels outside the reference's ambiguity mask, leaving out the edge pixels "
               "where rasterization and the reference's ray may disagree (a pixel centre within "
               "the ambiguity radius of an edge). An exact method shows ~0 there, while its raw "
               "figure counts those edge pixels too; both are the worst view's.\n\n");
}

void oit_bench_print_summary(FILE *f, const oit_bench_result *r, int markdown)
{
    char b[6][40];
    if (markdown)
        fprintf(f, "| entry | drew | triangles | ms median | ms p95 | rmse mean | "
                   "worst %% over 1/255 | worst %% over 1/255 outside ambiguity | GPU MiB |\n"
                   "|---|---|---|---|---|---|---|---|---|\n");
    else
        fprintf(f, "%-14s  %-19s  %10s  %9s  %9s  %10s  %9s  %9s  %8s\n", "entry", "drew",
                "triangles", "ms median", "ms p95", "rmse mean", "% >1/255", "% unamb.",
                "GPU MiB");
    for (int i = 0; i < r->method_count; i++) {
        const oit_bench_method *m = &r->methods[i];
        int ran = m->ms_count > 0;
        fprintf(f, markdown ? "| %s | %s | %llu | %s | %s | %s | %s | %s | %s |\n"
                            : "%-14s  %-19s  %10llu  %9s  %9s  %10s  %9s  %9s  %8s\n",
                m->name, oit_bench_geometry_label(m->geometry, m->triangles, m->source_triangles),
                (unsigned long long)m->triangles,
                oit_bench_number(b[0], 40, m->ms_median, "%.2f", "not run"),
                oit_bench_number(b[1], 40, m->ms_p95, "%.2f", "-"),
                oit_bench_number(b[2], 40, ran ? m->rmse_mean : NAN, "%.3g", "-"),
                oit_bench_number(b[3], 40, ran ? m->pct_over_worst : NAN, "%.4f", "-"),
                oit_bench_number(b[5], 40, ran ? m->pct_over_outside_ambiguity_worst : NAN,
                                 "%.4f", "-"),
                oit_bench_number(b[4], 40, ran ? (double)m->gpu_bytes_peak / 1048576.0 : NAN,
                                 "%.1f", "-"));
    }
    if (markdown)
        fprintf(f, "\n");
    print_error_legend(f, markdown);
}

static void write_md(FILE *f, const oit_bench_context *ctx, const oit_bench_result *r)
{
    fprintf(f, "# oitbench: %s\n\n", ctx->model);
    fprintf(f, "- GL renderer: %s\n- CPUs: %ld\n- command: `%s`\n", r->renderer, ctx->cpus,
            ctx->command_line);
    fprintf(f, "- model: %llu triangles, %s shading\n", (unsigned long long)ctx->triangles,
            ctx->shading);
    if (ctx->models)
        md_models(f, ctx->models);
    fprintf(f, "- %d views (orbit, elevation 20 deg), %dx%d, %d warm-up + %d timed frames per "
               "method per view, methods interleaved round-robin\n",
            r->views, ctx->width, ctx->height, ctx->warmup, ctx->frames);
    fprintf(f, "- errors are against the Embree reference of the same view; a view's depth is "
               "the most surfaces the reference ray met at one pixel\n");
    fprintf(f, "- NAME@E: the method with threshold E (stream: early termination at "
               "transmittance E; guarded: contribution threshold; f2b: alpha threshold); "
               "NAME alone: its default\n\n");
    fprintf(f, "Absolute times are only meaningful from a GPU (a software renderer such as "
               "llvmpipe says nothing about GPU speed); ratios between methods were measured "
               "side by side in one run.\n\n");
    fprintf(f, "## Summary\n\n");
    oit_bench_print_summary(f, r, 1);
    fprintf(f, "GPU MiB: every GPU buffer and texture the entry held at its peak: an in-core "
               "method's working memory and the mesh it uploaded (`gpu_mesh_bytes` in "
               "results.csv and results.json), the stream's upload ring, residency cache, "
               "capture and per-pixel state.\n\n");
    fprintf(f, "## Plots\n\n![speed against error](speed_vs_error.png)\n\n"
               "![memory against depth](memory_vs_depth.png)\n\n");
    for (int i = 0; i < r->method_count; i++)
        md_method(f, &r->methods[i], r);
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* The charts are drawn from results.csv as written, read back. */
static oit_status write_plots(const char *dir, const oit_bench_context *ctx,
                              const oit_bench_result *r, oit_error *err)
{
    char path[4096], title[256], sub[512];
    oit_bench_table t;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    oit_status s = oit_bench_csv_load(path, &t, err);
    if (s != OIT_OK)
        return s;
    snprintf(title, sizeof title, "%s: %llu triangles, %s", base_name(ctx->model),
             (unsigned long long)ctx->triangles, ctx->shading);
    snprintf(sub, sizeof sub, "%dx%d, %d views, %s", ctx->width, ctx->height, r->views,
             r->renderer);
    snprintf(path, sizeof path, "%s/speed_vs_error.png", dir);
    s = oit_bench_plot_speed_error(&t, title, sub, path, err);
    snprintf(path, sizeof path, "%s/memory_vs_depth.png", dir);
    if (s == OIT_OK)
        s = oit_bench_plot_memory_depth(&t, 1, title, sub, path, err);
    oit_bench_table_free(&t);
    return s;
}

oit_status oit_bench_write_reports(const char *dir, const oit_bench_context *ctx,
                                   const oit_bench_result *r, oit_error *err)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create folder: %s", dir, strerror(errno));
    char path[4096];
    FILE *f;
    oit_status s = open_out(dir, "results.csv", &f, path, sizeof path, err);
    if (s == OIT_OK) {
        oit_bench_csv_write(f, r, ctx->triangles);
        s = close_out(f, path, err);
    }
    if (s == OIT_OK && (s = open_out(dir, "results.json", &f, path, sizeof path, err)) == OIT_OK) {
        oit_json w;
        oit_json_init(&w, f, path);
        write_json(&w, ctx, r);
        s = oit_json_close(&w, err);
    }
    if (s == OIT_OK)
        s = write_plots(dir, ctx, r, err);
    if (s == OIT_OK && (s = open_out(dir, "report.md", &f, path, sizeof path, err)) == OIT_OK) {
        write_md(f, ctx, r);
        s = close_out(f, path, err);
    }
    return s;
}
