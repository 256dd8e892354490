/* oitbench: measures rendering methods side by side on one model over an
 * orbit of views (speed, memory, layers, error against the Embree
 * reference) and writes results.csv, results.json, two PNG charts and
 * report.md; "oitbench plot" draws charts across earlier runs. Errors are
 * one line on stderr; the exit status follows oit_status_exit_code, except
 * that a run in which no method could render at all exits 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <errno.h>
#include <sys/stat.h>

#include "formats/paths.h"
#include "stream/bench_args.h"
#include "stream/bench_csv.h"
#include "stream/bench_plot.h"
#include "stream/bench_report.h"
#include "stream/bench_run.h"
#include "stream/part_triangles.h"

static int fail(const oit_error *err)
{
    fprintf(stderr, "oitbench: %s\n", err->message);
    return oit_status_exit_code(err->status);
}

static int is_part_file(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && !strcasecmp(path + n - 5, ".oitp");
}

/* A mesh file in core, or a part file: the streamer reads it part by part,
 * the reference and the other methods render its triangles in core. */
static oit_status load_scene(const oit_bench_args *a, oit_partfile **pf, oit_mesh *mesh,
                             oit_error *err)
{
    memset(mesh, 0, sizeof *mesh);
    *pf = NULL;
    if (!is_part_file(a->model))
        return oit_mesh_load(a->model, NULL, mesh, err);
    int streams = 0;
    for (int i = 0; i < a->method_count; i++)
        streams |= oit_render_method_find(a->methods[i])->needs_partfile;
    oit_partfile_open_desc desc = {streams};
    oit_status s = oit_partfile_open(a->model, &desc, pf, err);
    return s == OIT_OK ? oit_partfile_load_mesh(*pf, mesh, err) : s;
}

/* The command line as one string, for the report. */
static void join_args(int argc, char **argv, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; i < argc && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s", i ? " " : "", argv[i]);
}

static int any_ran(const oit_bench_result *r)
{
    for (int i = 0; i < r->method_count; i++)
        if (r->methods[i].ms_count > 0)
            return 1;
    return 0;
}

static void report_unrunnable(const oit_bench_result *r)
{
    for (int i = 0; i < r->method_count; i++)
        if (!r->methods[i].runnable)
            fprintf(stderr, "oitbench: %s not runnable: %s\n", r->methods[i].name,
                    r->methods[i].reason);
}

static int run(const oit_bench_args *a, const char *command_line)
{
    oit_error err = {0};
    oit_partfile *pf = NULL;
    oit_mesh mesh;
    oit_bench_result r = {0};
    oit_status s = load_scene(a, &pf, &mesh, &err);
    oit_bench_desc d = {.mesh = &mesh, .partfile = pf, .entries = a->entries,
                        .entry_count = a->entry_count, .views = a->orbit, .width = a->width,
                        .height = a->height, .frames = a->frames, .warmup = a->warmup,
                        .max_layers = a->max_layers, .shading = a->shading, .progress = stderr};
    if (s == OIT_OK) {
        fprintf(stderr, "oitbench: %s: %llu triangles, %d entries, %d views\n", a->model,
                (unsigned long long)mesh.info.triangles, a->entry_count, a->orbit);
        s = oit_bench_run(&d, &r, &err);
    }
    oit_bench_context ctx = {a->model, command_line, a->width, a->height, a->frames,
                             a->warmup, sysconf(_SC_NPROCESSORS_ONLN),
                             (unsigned long long)mesh.info.triangles,
                             a->shading == OIT_SHADING_TRANSLUCENT ? "translucent"
                                                                   : "transparent"};
    if (s == OIT_OK)
        s = oit_bench_write_reports(a->out, &ctx, &r, &err);
    int code = s == OIT_OK ? 0 : fail(&err);
    if (s == OIT_OK) {
        report_unrunnable(&r);
        fprintf(stderr, "oitbench: wrote %s/results.csv, results.json, speed_vs_error.png, "
                "memory_vs_depth.png, report.md\n", a->out);
        if (!any_ran(&r)) {
            fprintf(stderr, "oitbench: no method could render %s\n", a->model);
            code = 1;
        }
    }
    oit_bench_result_free(&r);
    oit_mesh_free(&mesh);
    oit_partfile_close(pf);
    return code;
}

/* The last component of a folder name, trailing slashes ignored. */
static const char *base_name(const char *path, char *buf, size_t cap)
{
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    size_t start = n;
    while (start > 0 && path[start - 1] != '/')
        start--;
    snprintf(buf, cap, "%.*s", (int)(n - start), path + start);
    return buf;
}

/* oitbench plot: every run's results.csv, then the two cross-run charts. */
static oit_status plot_runs(const oit_bench_args *a, oit_bench_table *runs, oit_error *err)
{
    char path[4096], title[128], sub[512] = "runs:";
    oit_status s = OIT_OK;
    for (int i = 0; i < a->run_count; i++) {
        char name[256];
        size_t used = strlen(sub);
        snprintf(sub + used, sizeof sub - used, "%s %s", i ? "," : "",
                 base_name(a->runs[i], name, sizeof name));
    }
    for (int i = 0; i < a->run_count && s == OIT_OK; i++) {
        snprintf(path, sizeof path, "%s/results.csv", a->runs[i]);
        s = oit_bench_csv_load(path, &runs[i], err);
    }
    if (s == OIT_OK && mkdir(a->plot_out, 0777) != 0 && errno != EEXIST)
        s = oit_error_set(err, OIT_ERR_IO, "%s: cannot create folder: %s", a->plot_out,
                          strerror(errno));
    snprintf(title, sizeof title, "oitbench: %d run%s", a->run_count, a->run_count > 1 ? "s" : "");
    snprintf(path, sizeof path, "%s/time_vs_triangles.png", a->plot_out);
    if (s == OIT_OK)
        s = oit_bench_plot_time_triangles(runs, a->run_count, title, sub, path, err);
    snprintf(path, sizeof path, "%s/memory_vs_depth.png", a->plot_out);
    if (s == OIT_OK)
        s = oit_bench_plot_memory_depth(runs, a->run_count, title, sub, path, err);
    return s;
}

static int plot(const oit_bench_args *a)
{
    oit_error err = {0};
    oit_bench_table *runs = calloc((size_t)a->run_count, sizeof *runs);
    oit_status s = runs ? plot_runs(a, runs, &err)
                        : oit_error_set(&err, OIT_ERR_NOMEM, "cannot allocate %d runs",
                                        a->run_count);
    for (int i = 0; runs && i < a->run_count; i++)
        oit_bench_table_free(&runs[i]);
    free(runs);
    if (s != OIT_OK)
        return fail(&err);
    fprintf(stderr, "oitbench: wrote %s/time_vs_triangles.png, memory_vs_depth.png from %d "
            "runs\n", a->plot_out, a->run_count);
    return 0;
}

int main(int argc, char **argv)
{
    oit_bench_args a;
    oit_error err = {0};
    char methods[512], line[4096];
    if (oit_bench_args_parse(argc, argv, &a, methods, sizeof methods, &err) != OIT_OK)
        return fail(&err);
    if (a.help) {
        char names[OIT_METHOD_NAMES_MAX];
        oit_render_method_names(names, sizeof names);
        oit_bench_usage(stdout, names);
        return 0;
    }
    /* The output folder is made and tested before the run, not after it. */
    const char *out = a.plot ? a.plot_out : a.out;
    const char *in = a.plot ? NULL : a.model;
    int created = 0;
    if (oit_output_dir_check(out, a.plot ? "plot OUT" : "--out", &in, 1, &created, &err) != OIT_OK)
        return fail(&err);
    int code;
    if (a.plot) {
        code = plot(&a);
    } else {
        join_args(argc, argv, line, sizeof line);
        code = run(&a, line);
    }
    if (code != 0 && created)
        rmdir(out); /* the folder this run made, when nothing went into it */
    return code;
}
