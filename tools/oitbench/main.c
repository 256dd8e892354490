/* oitbench: measures rendering methods side by side on one model over an
 * orbit of views (speed, memory, layers, error against the Embree
 * reference): the in-core methods on the source mesh, the stream on its
 * part file, converted now when none is given (bench_models.h); writes
 * results.csv, results.json, two PNG charts and
 * report.md; "oitbench plot" draws charts across earlier runs; "oitbench
 * bus" measures the host-to-device rate (bench_bus.c). Errors are
 * one line on stderr; the exit status follows oit_tool_exit_code, except
 * that a run in which no method could render at all exits 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <errno.h>
#include <signal.h>
#include <sys/stat.h>

#include "tools/common/exit_code.h"
#include "tools/common/flag_spelling.h"
#include "tools/common/heap.h"
#include "tools/common/paths.h"
#include "tools/common/progress_mode.h"
#include "tools/common/signals.h"
#include "prepare/convert/convert.h"
#include "prepare/convert/progress.h"
#include "formats/up_axis.h"
#include "tools/oitbench/bench_args.h"
#include "tools/oitbench/bench_bus.h"
#include "tools/oitbench/bench_csv.h"
#include "tools/oitbench/bench_models.h"
#include "tools/oitbench/bench_plot.h"
#include "tools/oitbench/bench_report.h"
#include "tools/oitbench/bench_run.h"

static int fail(const oit_error *err)
{
    oit_error e = *err; /* liboit names its fields, a tool its flags */
    oit_flags_spell_error(&e);
    fprintf(stderr, "oitbench: %s\n", e.message);
    return oit_tool_exit_code(err->status);
}

/* oitprep's conversion options, with the run's --scheme and --part-triangles. */
static oit_status convert_options(const oit_bench_args *a, oit_convert_options *o,
                                  oit_error *err)
{
    oit_convert_options_init(o);
    oit_tool_progress tp = oit_tool_progress_get("oitbench");
    o->progress = tp.bar ? OIT_PROGRESS_BAR : OIT_PROGRESS_LINES;
    o->progress_period_s = tp.period_s;
    if (a->scheme)
        o->scheme = strcmp(a->scheme, "fast") ? OIT_SCHEME_GUARANTEED : OIT_SCHEME_FAST;
    o->part_triangles = a->part_triangles;
    if (a->part_triangles && o->scheme != OIT_SCHEME_FAST)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--part-triangles %u applies to the fast "
                             "scheme, and the conversion's is %s (add --scheme fast)",
                             a->part_triangles, oit_scheme_name(o->scheme));
    return OIT_OK;
}

static int streams(const oit_bench_args *a)
{
    int any = 0;
    for (int i = 0; i < a->method_count; i++)
        any |= !!(oit_method_find(a->methods[i])->flags & OIT_RENDER_METHOD_PART_FILE);
    return any;
}

/* The part file the conversion writes: --save-parts, else a temporary file,
 * made now so that SIGINT and SIGTERM can remove it (and the writer's
 * OUT.tmp and OUT.spill) during the conversion. */
static oit_status conversion_output(const oit_bench_args *a, oit_bench_models_desc *d,
                                    char *tmp, size_t cap, oit_error *err)
{
    static const char *const temp_files[] = {".tmp", "", ".spill", NULL};
    static const char *const kept_files[] = {".tmp", ".spill", NULL};
    if (oit_bench_is_part_file(a->model) || a->parts || !d->need_parts)
        return OIT_OK;
    oit_status s = OIT_OK;
    if (a->save_parts) {
        d->convert.output = a->save_parts;
    } else if ((s = oit_bench_temp_part_file(tmp, cap, err)) == OIT_OK) {
        d->convert.output = tmp;
        d->output_is_temp = 1;
    }
    if (s == OIT_OK)
        oit_tool_signals_install("oitbench", d->convert.output,
                                 d->output_is_temp ? temp_files : kept_files);
    return s;
}

static oit_status open_models(const oit_bench_args *a, oit_bench_models *m, oit_error *err)
{
    char tmp[OIT_BENCH_PATH_MAX];
    oit_bench_models_desc d = {.model = a->model, .parts = a->parts, .mesh = a->mesh,
                               .need_parts = streams(a), .progress = stderr};
    oit_status s = convert_options(a, &d.convert, err);
    if (s == OIT_OK)
        s = conversion_output(a, &d, tmp, sizeof tmp, err);
    if (s == OIT_OK)
        s = oit_bench_models_open(&d, m, err);
    else if (d.output_is_temp)
        unlink(tmp);
    /* the temporary file is gone (or kept): nothing left for a handler */
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    return s;
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

static void print_geometry(const oit_bench_models *m, const oit_bench_args *a)
{
    if (m->have_source)
        fprintf(stderr, "oitbench: in-core methods and the reference draw the source mesh %s "
                "(%zu triangles)\n", m->source_path, m->source.count);
    else
        fprintf(stderr, "oitbench: in-core methods and the reference draw %s's clipped "
                "triangles (%zu)\n", a->model, m->clipped.count);
    if (m->pf)
        fprintf(stderr, "oitbench: stream draws %s (%llu triangles)\n",
                m->conv.done && !m->conv.kept ? "the converted part file" : m->parts_path,
                (unsigned long long)m->part_triangles);
}

static int run(const oit_bench_args *a, const char *command_line)
{
    oit_error err = {0};
    oit_bench_models models;
    oit_bench_result r = {0};
    oit_status s = open_models(a, &models, &err);
    if (s != OIT_OK)
        return fail(&err);
    const oit_mesh *mesh = oit_bench_models_in_core(&models);
    oit_bench_desc d = {.mesh = mesh, .mesh_geometry = oit_bench_models_in_core_geometry(&models),
                        .reference_mesh = mesh, .partfile = models.pf,
                        .partfile_triangles = models.part_triangles,
                        .source_triangles = models.source_triangles, .entries = a->entries,
                        .entry_count = a->entry_count, .views = a->orbit, .width = a->width,
                        .height = a->height, .frames = a->frames, .warmup = a->warmup,
                        .max_layers = a->max_layers, .capture = a->capture,
                        .shading = a->shading,
                        .colour_space = a->colour_space, .progress = stderr};
    const char *why = NULL;
    d.up_axis = oit_up_axis_guess(models.pf ? oit_partfile_source_name(models.pf) : a->model,
                                  mesh->info.bounds_min, mesh->info.bounds_max, &why);
    if (d.up_axis != 1)
        fprintf(stderr, "oitbench: %s: the views turn about %c (%s)\n", a->model,
                "xyz"[d.up_axis], why);
    if (a->methods_defaulted)
        fprintf(stderr, "oitbench: no --methods: the default set %s\n",
                OIT_BENCH_DEFAULT_METHODS);
    print_geometry(&models, a);
    fprintf(stderr, "oitbench: %s: %llu triangles, %d entries, %d views\n", a->model,
            (unsigned long long)models.source_triangles, a->entry_count, a->orbit);
    s = oit_bench_run(&d, &r, &err);
    oit_bench_context ctx = {a->model, command_line, a->width, a->height, a->frames,
                             a->warmup, sysconf(_SC_NPROCESSORS_ONLN),
                             (unsigned long long)models.source_triangles,
                             a->shading == OIT_SHADING_TRANSLUCENT ? "translucent"
                                                                   : "transparent",
                             &models};
    if (s == OIT_OK)
        s = oit_bench_write_reports(a->out, &ctx, &r, &err);
    int code = s == OIT_OK ? 0 : fail(&err);
    if (s == OIT_OK) {
        oit_bench_print_summary(stdout, &r, 0);
        report_unrunnable(&r);
        fprintf(stderr, "oitbench: wrote %s/results.csv, results.json, speed_vs_error.png, "
                "memory_vs_depth.png, report.md\n", a->out);
        if (!any_ran(&r)) {
            fprintf(stderr, "oitbench: no method could render %s\n", a->model);
            code = 1;
        }
    }
    oit_bench_result_free(&r);
    oit_bench_models_close(&models);
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
    oit_tool_heap_setup();
    oit_bench_args a;
    oit_error err = {0};
    char methods[512], line[4096];
    if (argc >= 2 && !strcmp(argv[1], "bus"))
        return oit_bench_bus_main(argc, argv);
    if (oit_bench_args_parse(argc, argv, &a, methods, sizeof methods, &err) != OIT_OK)
        return fail(&err);
    if (a.help) {
        char names[OIT_METHOD_NAMES_MAX];
        oit_convert_options o;
        oit_convert_options_init(&o);
        oit_method_names(names, sizeof names);
        oit_bench_usage(stdout, names, oit_scheme_name(o.scheme), OIT_FAST_PART_TRIANGLES);
        return 0;
    }
    /* The output folder is made and tested before the run, not after it. */
    const char *out = a.plot ? a.plot_out : a.out;
    const char *in[3] = {a.plot ? NULL : a.model, a.parts, a.mesh};
    int created = 0;
    if (oit_output_dir_check(out, a.plot ? "plot OUT" : "--out", in, 3, &created, &err) != OIT_OK)
        return fail(&err);
    /* --save-parts is checked before the conversion, as oitprep checks -o */
    if (!a.plot && a.save_parts &&
        oit_output_check(a.save_parts, "--save-parts", in, 3, &err) != OIT_OK) {
        if (created)
            rmdir(out);
        return fail(&err);
    }
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
