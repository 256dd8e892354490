/* oitbench's output files (bench_report.h). */
#include "tools/oitbench/bench_report.h"

#include "tools/oitbench/bench_csv.h"
#include "tools/oitbench/bench_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* ---- small formatting helpers ---- */


static void json_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

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

static void json_cell(FILE *f, int v, const oit_bench_cell *c)
{
    char b[6][40];
    fprintf(f, "{\"view\": %d, \"ok\": %s, \"ms_median\": %s, \"ms_p95\": %s, "
               "\"gpu_bytes_peak\": %llu, \"max_layers\": %u, \"fragments\": %llu, "
               "\"rmse\": %s, \"max_abs\": %s, \"pct_over_1_255\": %s, \"psnr\": %s}",
            v, c->ok ? "true" : "false", oit_bench_number(b[0], 40, c->ok ? c->ms_median : NAN, "%.4f", "null"),
            oit_bench_number(b[1], 40, c->ok ? c->ms_p95 : NAN, "%.4f", "null"),
            (unsigned long long)c->gpu_bytes_peak, c->max_layers,
            (unsigned long long)c->fragments,
            oit_bench_number(b[2], 40, c->ok ? c->diff.rmse : NAN, "%.9g", "null"),
            oit_bench_number(b[3], 40, c->ok ? c->diff.max_abs : NAN, "%.9g", "null"),
            oit_bench_number(b[4], 40, c->ok ? c->diff.pct_over_1_255 : NAN, "%.6f", "null"),
            oit_bench_number(b[5], 40, c->ok ? c->diff.psnr : NAN, "%.4f", "null"));
}

static void json_method(FILE *f, const oit_bench_method *m, int views)
{
    char b[6][40];
    fprintf(f, "    {\"name\": \"%s\", \"method\": \"%s\", \"epsilon\": %s, "
               "\"geometry\": \"%s\", \"triangles\": %llu, \"runnable\": %s, \"reason\": ",
            m->name, m->method->name, oit_bench_number(b[0], 40, m->epsilon >= 0.0f ? m->epsilon : NAN, "%g",
                                          "null"),
            m->geometry == OIT_BENCH_GEOMETRY_PART_FILE ? "part_file" : "source_mesh",
            (unsigned long long)m->triangles, m->runnable ? "true" : "false");
    json_text(f, m->reason);
    fprintf(f, ", \"timed_frames\": %zu, \"ms_median\": %s, \"ms_p95\": %s, "
               "\"gpu_bytes_peak\": %llu, \"max_layers\": %u, \"rmse_mean\": %s, "
               "\"max_abs_worst\": %s, \"pct_over_1_255_worst\": %s, \"psnr_min\": %s,\n"
               "     \"views\": [",
            m->ms_count, oit_bench_number(b[0], 40, m->ms_median, "%.4f", "null"),
            oit_bench_number(b[1], 40, m->ms_p95, "%.4f", "null"), (unsigned long long)m->gpu_bytes_peak,
            m->max_layers, oit_bench_number(b[2], 40, m->runnable ? m->rmse_mean : NAN, "%.9g", "null"),
            oit_bench_number(b[3], 40, m->runnable ? m->max_abs_worst : NAN, "%.9g", "null"),
            oit_bench_number(b[4], 40, m->runnable ? m->pct_over_worst : NAN, "%.6f", "null"),
            oit_bench_number(b[5], 40, m->runnable ? m->psnr_min : NAN, "%.4f", "null"));
    for (int v = 0; v < views; v++) {
        fprintf(f, "%s", v ? ",\n       " : "");
        json_cell(f, v, &m->cells[v]);
    }
    fprintf(f, "]}");
}

/* The source mesh, the part file and the conversion, as JSON members. */
static void json_models(FILE *f, const oit_bench_models *m)
{
    fprintf(f, ",\n  \"source_mesh\": ");
    if (m->have_source)
        json_text(f, m->source_path);
    else
        fprintf(f, "null");
    fprintf(f, ", \"source_triangles\": %llu,\n  \"part_file\": ",
            (unsigned long long)m->source_triangles);
    if (m->conv.done && !m->conv.kept)
        fprintf(f, "\"(temporary, removed)\"");
    else if (m->parts_path[0])
        json_text(f, m->parts_path);
    else
        fprintf(f, "null");
    fprintf(f, ", \"part_file_triangles\": %llu", (unsigned long long)m->part_triangles);
    if (m->conv.done)
        fprintf(f, ",\n  \"conversion\": {\"scheme\": \"%s\", \"part_triangles\": %u, "
                   "\"seconds\": %.3f, \"triangles_in\": %llu, \"triangles_out\": %llu, "
                   "\"parts\": %llu}", m->conv.scheme, m->conv.part_triangles, m->conv.seconds,
                (unsigned long long)m->conv.triangles_in,
                (unsigned long long)m->conv.triangles_out, (unsigned long long)m->conv.parts);
    fprintf(f, ",\n  \"reference_geometry\": \"%s\",\n  \"notes\": [",
            m->have_source ? "source_mesh" : "part_file");
    for (int i = 0; i < m->note_count; i++) {
        fprintf(f, "%s", i ? ", " : "");
        json_text(f, m->notes[i]);
    }
    fprintf(f, "]");
}

static void write_json(FILE *f, const oit_bench_context *ctx, const oit_bench_result *r)
{
    fprintf(f, "{\n  \"model\": ");
    json_text(f, ctx->model);
    if (ctx->models)
        json_models(f, ctx->models);
    fprintf(f, ",\n  \"command\": ");
    json_text(f, ctx->command_line);
    fprintf(f, ",\n  \"renderer\": ");
    json_text(f, r->renderer);
    fprintf(f, ",\n  \"cpus\": %ld, \"triangles\": %llu, \"shading\": \"%s\", "
               "\"width\": %d, \"height\": %d, \"views\": %d, \"frames\": %d, "
               "\"warmup\": %d,\n  \"reference_ms\": [",
            ctx->cpus, (unsigned long long)ctx->triangles, ctx->shading, ctx->width, ctx->height,
            r->views, ctx->frames, ctx->warmup);
    for (int v = 0; v < r->views; v++)
        fprintf(f, "%s%.4f", v ? ", " : "", r->ref_ms[v]);
    fprintf(f, "],\n  \"reference_max_layers\": [");
    for (int v = 0; v < r->views; v++)
        fprintf(f, "%s%u", v ? ", " : "", r->ref_layers[v]);
    fprintf(f, "],\n  \"methods\": [\n");
    for (int i = 0; i < r->method_count; i++) {
        json_method(f, &r->methods[i], r->views);
        fprintf(f, "%s\n", i + 1 < r->method_count ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
}

/* ---- report.md ---- */

static void md_method(FILE *f, const oit_bench_method *m, const oit_bench_result *r)
{
    int views = r->views;
    char b[8][40];
    fprintf(f, "## %s\n\nDrew the %s: %llu triangles.\n\n", m->name,
            oit_bench_geometry_label(m->geometry), (unsigned long long)m->triangles);
    if (!m->runnable && m->ms_count == 0) {
        fprintf(f, "Not runnable: %s\n\n", m->reason);
        return;
    }
    if (!m->runnable)
        fprintf(f, "Stopped: %s (figures below are over the views it rendered)\n\n", m->reason);
    fprintf(f, "| view | depth | ms median | ms p95 | GPU MiB peak | max layers | rmse | "
               "max_abs | %% over 1/255 | PSNR dB |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int v = 0; v < views; v++) {
        const oit_bench_cell *c = &m->cells[v];
        if (!c->ok) {
            fprintf(f, "| %d | %u | - | - | - | - | - | - | - | - |\n", v, r->ref_layers[v]);
            continue;
        }
        fprintf(f, "| %d | %u | %.3f | %.3f | %.2f | %u | %.3g | %.3g | %.4f | %s |\n", v,
                r->ref_layers[v], c->ms_median, c->ms_p95, (double)c->gpu_bytes_peak / 1048576.0,
                c->max_layers,
                c->diff.rmse, c->diff.max_abs, c->diff.pct_over_1_255,
                oit_bench_number(b[0], 40, c->diff.psnr, "%.2f", "inf"));
    }
    fprintf(f, "| **all** | | **%s** | **%s** | %.2f | %u | %s (mean) | %s (worst) | %s (worst) | "
               "%s (min) |\n\n",
            oit_bench_number(b[1], 40, m->ms_median, "%.3f", "-"), oit_bench_number(b[2], 40, m->ms_p95, "%.3f", "-"),
            (double)m->gpu_bytes_peak / 1048576.0, m->max_layers,
            oit_bench_number(b[3], 40, m->rmse_mean, "%.3g", "-"), oit_bench_number(b[4], 40, m->max_abs_worst, "%.3g", "-"),
            oit_bench_number(b[5], 40, m->pct_over_worst, "%.4f", "-"), oit_bench_number(b[6], 40, m->psnr_min, "%.2f", "inf"));
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

void oit_bench_print_summary(FILE *f, const oit_bench_result *r, int markdown)
{
    char b[5][40];
    if (markdown)
        fprintf(f, "| entry | drew | triangles | ms median | ms p95 | rmse mean | "
                   "worst %% over 1/255 | GPU MiB |\n|---|---|---|---|---|---|---|---|\n");
    else
        fprintf(f, "%-14s  %-19s  %10s  %9s  %9s  %10s  %9s  %8s\n", "entry", "drew",
                "triangles", "ms median", "ms p95", "rmse mean", "% >1/255", "GPU MiB");
    for (int i = 0; i < r->method_count; i++) {
        const oit_bench_method *m = &r->methods[i];
        int ran = m->ms_count > 0;
        fprintf(f, markdown ? "| %s | %s | %llu | %s | %s | %s | %s | %s |\n"
                            : "%-14s  %-19s  %10llu  %9s  %9s  %10s  %9s  %8s\n",
                m->name, oit_bench_geometry_label(m->geometry), (unsigned long long)m->triangles,
                oit_bench_number(b[0], 40, m->ms_median, "%.2f", "not run"),
                oit_bench_number(b[1], 40, m->ms_p95, "%.2f", "-"),
                oit_bench_number(b[2], 40, ran ? m->rmse_mean : NAN, "%.3g", "-"),
                oit_bench_number(b[3], 40, ran ? m->pct_over_worst : NAN, "%.4f", "-"),
                oit_bench_number(b[4], 40, ran ? (double)m->gpu_bytes_peak / 1048576.0 : NAN,
                                 "%.1f", "-"));
    }
    if (markdown)
        fprintf(f, "\n");
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
        write_json(f, ctx, r);
        s = close_out(f, path, err);
    }
    if (s == OIT_OK)
        s = write_plots(dir, ctx, r, err);
    if (s == OIT_OK && (s = open_out(dir, "report.md", &f, path, sizeof path, err)) == OIT_OK) {
        write_md(f, ctx, r);
        s = close_out(f, path, err);
    }
    return s;
}
