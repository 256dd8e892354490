/* oitbench's command line (bench_args.h). */
#include "tools/oitbench/bench_args.h"


#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "base/args.h"
#include "tools/oitbench/bench_models.h"
#include "tools/common/methods.h"
#include "tools/common/render_args.h"

/* Splits "dfb,pll" in place in buf; every name must exist and appear once. */
static oit_status split_methods(const char *list, oit_bench_args *a, char *buf, size_t cap,
                                oit_error *err)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_method_names(names, sizeof names);
    if (strlen(list) >= cap)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods '%s' is too long", list);
    strcpy(buf, list);
    a->method_count = 0;
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (!oit_method_find(t))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods: unknown method '%s' "
                                 "(expected names from %s)", t, names);
        for (int i = 0; i < a->method_count; i++)
            if (!strcmp(a->methods[i], t))
                return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods: '%s' given twice", t);
        if (a->method_count == OIT_BENCH_MAX_METHODS)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods: more than %d methods",
                                 OIT_BENCH_MAX_METHODS);
        a->methods[a->method_count++] = t;
    }
    if (a->method_count == 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods '%s' names no method", list);
    return OIT_OK;
}

static oit_status bad(oit_error *err, const char *opt, const char *v, const char *want)
{
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s '%s': expected %s", opt, v, want);
}

/* "0,0.01,0.1": each in [0, 1), none twice (as the float the method gets). */
static oit_status split_epsilons(const char *list, oit_bench_args *a, oit_error *err)
{
    double v[OIT_BENCH_MAX_EPSILONS];
    int n = oit_parse_doubles(list, ',', v, OIT_BENCH_MAX_EPSILONS);
    /* a threshold is written plainly: no sign (not even "-0"), in range */
    int bad_item = list[0] == '-' || strstr(list, ",-") != NULL;
    a->epsilon_count = 0;
    for (int i = 0; i < n && i < OIT_BENCH_MAX_EPSILONS && !bad_item; i++)
        bad_item = !(v[i] >= 0.0 && v[i] < 1.0);
    if (n < 0 || bad_item)
        return bad(err, "--epsilon", list, "comma-separated thresholds, each in [0, 1)");
    for (int i = 0; i < n && i < OIT_BENCH_MAX_EPSILONS; i++) {
        for (int k = 0; k < i; k++)
            if (a->epsilons[k] == (float)v[i])
                return oit_error_set(err, OIT_ERR_ARGUMENT, "--epsilon '%s': %g given twice",
                                     list, v[i]);
        a->epsilons[a->epsilon_count++] = (float)v[i];
    }
    if (n > OIT_BENCH_MAX_EPSILONS)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--epsilon '%s': more than %d values",
                             list, OIT_BENCH_MAX_EPSILONS);
    return OIT_OK;
}

static oit_status add_entry(oit_bench_args *a, const char *method, float epsilon,
                            oit_error *err)
{
    if (a->entry_count == OIT_BENCH_MAX_ENTRIES)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods x --epsilon: more than %d entries",
                             OIT_BENCH_MAX_ENTRIES);
    oit_bench_entry *e = &a->entries[a->entry_count++];
    e->method = method;
    e->epsilon = epsilon;
    if (epsilon >= 0.0f)
        snprintf(e->name, sizeof e->name, "%s@%g", method, (double)epsilon);
    else
        snprintf(e->name, sizeof e->name, "%s", method);
    return OIT_OK;
}

/* Every method once, a method that takes a threshold once per --epsilon. */
static oit_status expand_entries(oit_bench_args *a, oit_error *err)
{
    int swept = 0;
    oit_status s = OIT_OK;
    a->entry_count = 0;
    for (int i = 0; i < a->method_count && s == OIT_OK; i++) {
        int sweep = a->epsilon_count > 0 && !!(oit_method_find(a->methods[i])->flags & OIT_RENDER_METHOD_EPSILON);
        swept |= sweep;
        for (int k = 0; k < (sweep ? a->epsilon_count : 1) && s == OIT_OK; k++)
            s = add_entry(a, a->methods[i], sweep ? a->epsilons[k] : -1.0f, err);
    }
    if (s == OIT_OK && a->epsilon_count > 0 && !swept)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "--epsilon applies to stream, guarded and "
                          "f2b (and reference, which counts what it would drop); --methods "
                          "names none of them");
    return s;
}

/* One "--name value" option; 0 when the name is unknown. */
static int value_option(oit_bench_args *a, const char *opt, const char *v, char *buf, size_t cap,
                        oit_status *s, oit_error *err)
{
    if (!strcmp(opt, "--methods")) *s = split_methods(v, a, buf, cap, err);
    else if (!strcmp(opt, "--orbit")) {
        if (oit_parse_int(v, 1, 100000, &a->orbit)) *s = bad(err, opt, v, "a view count >= 1");
    } else if (!strcmp(opt, "--size")) {
        if (oit_parse_size(v, 1, 16384, &a->width, &a->height))
            *s = bad(err, opt, v, "WxH, e.g. 512x512");
    } else if (!strcmp(opt, "--frames")) {
        if (oit_parse_int(v, 1, 100000, &a->frames)) *s = bad(err, opt, v, "a frame count >= 1");
    } else if (!strcmp(opt, "--warmup")) {
        if (oit_parse_int(v, 0, 100000, &a->warmup)) *s = bad(err, opt, v, "a frame count >= 0");
    } else if (!strcmp(opt, "--max-layers")) {
        if (oit_parse_int(v, INT_MIN, INT_MAX, &a->max_layers)) *s = bad(err, opt, v, "an integer");
        else *s = oit_tool_check_k(a->max_layers, "--max-layers", err);
    } else if (!strcmp(opt, "--capture")) {
        *s = oit_tool_parse_capture(v, opt, &a->capture, err);
    } else if (!strcmp(opt, "--epsilon")) *s = split_epsilons(v, a, err);
    else if (!strcmp(opt, "--shading")) {
        if (!strcmp(v, "transparent")) a->shading = OIT_SHADING_TRANSPARENT;
        else if (!strcmp(v, "translucent")) a->shading = OIT_SHADING_TRANSLUCENT;
        else *s = bad(err, opt, v, "transparent or translucent");
    } else if (!strcmp(opt, "--colour-space") || !strcmp(opt, "--color-space")) {
        if (!strcmp(v, "srgb")) a->colour_space = OIT_COLOUR_SRGB;
        else if (!strcmp(v, "linear")) a->colour_space = OIT_COLOUR_LINEAR;
        else *s = bad(err, opt, v, "srgb or linear");
    } else if (!strcmp(opt, "--out")) a->out = v;
    else if (!strcmp(opt, "--parts")) a->parts = v;
    else if (!strcmp(opt, "--mesh")) a->mesh = v;
    else if (!strcmp(opt, "--save-parts")) a->save_parts = v;
    else if (!strcmp(opt, "--scheme")) {
        if (strcmp(v, "guaranteed") && strcmp(v, "fast")) *s = bad(err, opt, v, "guaranteed or fast");
        else a->scheme = v;
    } else if (!strcmp(opt, "--part-triangles")) {
        int t = 0;
        if (oit_parse_int(v, 1, 1 << 24, &t))
            *s = bad(err, opt, v, "a triangle count in 1..16777216");
        a->part_triangles = (unsigned)t;
    } else return 0;
    return 1;
}

/* The first conversion option given, or NULL. */
static const char *conversion_option(const oit_bench_args *a)
{
    return a->scheme ? "--scheme" : a->part_triangles ? "--part-triangles"
           : a->save_parts ? "--save-parts" : NULL;
}

/* --parts, --mesh and the conversion's options fit MODEL and the methods. */
static oit_status check_geometry_options(const oit_bench_args *a, oit_error *err)
{
    int streams = 0;
    const char *conv = conversion_option(a);
    for (int i = 0; i < a->method_count; i++)
        streams |= !!(oit_method_find(a->methods[i])->flags & OIT_RENDER_METHOD_PART_FILE);
    if (oit_bench_is_part_file(a->model)) {
        const char *o = a->parts ? "--parts" : conv;
        if (o)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s applies to a mesh MODEL; %s is "
                                 "already a part file", o, a->model);
        return OIT_OK;
    }
    if (a->mesh)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--mesh names a part file's source; %s "
                             "is a mesh already (for its part file: --parts FILE.oitp)", a->model);
    if (!streams && (a->parts || conv))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s is for the stream's part file, and "
                             "--methods has no stream", a->parts ? "--parts" : conv);
    if (a->parts && conv)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s applies to the conversion; with "
                             "--parts %s nothing is converted", conv, a->parts);
    return OIT_OK;
}

/* "oitbench-STEM" in the working folder: STEM is MODEL's file name
 * without its extension, so that runs on two models land apart. */
static const char *default_out(const char *model, char *buf, size_t cap)
{
    const char *name = strrchr(model, '/') ? strrchr(model, '/') + 1 : model;
    const char *dot = strrchr(name, '.');
    size_t n = dot && dot != name ? (size_t)(dot - name) : strlen(name);
    snprintf(buf, cap, "oitbench-%.*s", (int)n, name);
    return buf;
}

/* oitbench plot OUT_DIR RUN_DIR... */
static oit_status parse_plot(int argc, char **argv, oit_bench_args *a, oit_error *err)
{
    a->plot = 1;
    for (int i = 2; i < argc; i++) {
        const char *arg = argv[i];
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h"))
            a->help = 1;
        else if (!strncmp(arg, "--", 2))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "plot: unknown option '%s' (see "
                                 "oitbench --help)", arg);
        else if (!a->plot_out)
            a->plot_out = arg;
        else if (a->run_count == OIT_BENCH_MAX_RUNS)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "plot: more than %d run folders",
                                 OIT_BENCH_MAX_RUNS);
        else
            a->runs[a->run_count++] = arg;
    }
    if (!a->help && a->run_count == 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "plot needs OUT_DIR and at least one "
                             "RUN_DIR (see oitbench --help)");
    return OIT_OK;
}

oit_status oit_bench_args_parse(int argc, char **argv, oit_bench_args *a, char *buf, size_t cap,
                                oit_error *err)
{
    memset(a, 0, sizeof *a);
    if (argc >= 2 && !strcmp(argv[1], "plot"))
        return parse_plot(argc, argv, a, err);
    a->shading = OIT_SHADING_TRANSPARENT;
    a->orbit = 8;
    a->width = a->height = 512;
    a->frames = 5;
    a->warmup = 1;
    a->max_layers = 16;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        oit_status s = OIT_OK;
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            a->help = 1;
        } else if (!strncmp(arg, "--", 2)) {
            const char *v = i + 1 < argc ? argv[i + 1] : NULL;
            if (!value_option(a, arg, v ? v : "", buf, cap, &s, err))
                return oit_error_set(err, OIT_ERR_ARGUMENT, "unknown option '%s' (see --help)", arg);
            if (!v)
                return oit_error_set(err, OIT_ERR_ARGUMENT, "%s needs a value", arg);
            i++;
        } else if (a->model) {
            s = oit_error_set(err, OIT_ERR_ARGUMENT, "unexpected argument '%s': one model only", arg);
        } else {
            a->model = arg;
        }
        if (s != OIT_OK)
            return s;
    }
    if (a->help)
        return OIT_OK;
    if (!a->model)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "no model given (see --help)");
    oit_status s = OIT_OK;
    if (a->method_count == 0) {
        a->methods_defaulted = 1;
        s = split_methods(OIT_BENCH_DEFAULT_METHODS, a, buf, cap, err);
    }
    if (!a->out)
        a->out = default_out(a->model, a->out_buf, sizeof a->out_buf);
    if (s == OIT_OK)
        s = expand_entries(a, err);
    return s == OIT_OK ? check_geometry_options(a, err) : s;
}

void oit_bench_usage(FILE *f, const char *method_list, const char *default_scheme,
                     unsigned default_part_triangles)
{
    fprintf(f,
        "usage: oitbench MODEL_OR_PARTFILE [--methods LIST] [--out DIR] [options]\n"
        "       oitbench plot OUT_DIR RUN_DIR [RUN_DIR...]\n"
        "       oitbench bus [--bytes B] [--repeat N]\n"
        "  Renders MODEL (a mesh, or a .oitp part file) from an orbit of views with\n"
        "  every method of LIST, interleaved view by view (warm-up frames, then timed\n"
        "  frames per method, methods round-robin, so that drift hits all alike), and\n"
        "  compares each method's image with the Embree reference of the same view.\n"
        "  A method that cannot open or render the case (out of memory, no GL) is\n"
        "  reported with the reason, not dropped.\n"
        "what each method draws (the choice a user makes: the mesh in core, or its\n"
        "part file streamed):\n"
        "  MODEL a mesh (as oitprep reads): the in-core methods and the\n"
        "    reference draw its triangles; stream draws the part file of --parts, or\n"
        "    one converted now as oitprep would (progress on stderr; its seconds and\n"
        "    triangles in and out reported) into a temporary file in $TMPDIR or /tmp,\n"
        "    removed once opened, or into --save-parts FILE, kept\n"
        "  MODEL a .oitp: stream draws it; the in-core methods and the reference draw\n"
        "    the source mesh of --mesh, else the source named in the file's META when\n"
        "    it lies beside the file and matches, else the part file's own triangles,\n"
        "    clipped at part boundaries (the report, results.csv and charts say so)\n"
        "  A part file matches a mesh when it read as many triangles as the mesh has,\n"
        "  from the same origin, within 1/1000 of the mesh's bounds, and its surface\n"
        "  has the mesh's area and centroid (clipping keeps both): --parts or --mesh\n"
        "  of another model is refused (exit 3), a mismatched source beside the file\n"
        "  is not used (and said so); a different recorded source name alone is\n"
        "  noted. Errors are always against the reference, which draws the source\n"
        "  mesh whenever there is one.\n"
        "options:\n"
        "  --methods LIST   comma-separated, from %s\n"
        "                   (guarded and f2b run at their seeds' thresholds, 0.0025\n"
        "                   and 0.02, unless --epsilon; see oitstream --help).\n"
        "                   default: " OIT_BENCH_DEFAULT_METHODS ": the exact\n"
        "                   methods (the stream on a part file converted now, or\n"
        "                   MODEL itself when it is one) and the common approximate\n"
        "                   baselines; a method this driver cannot run is skipped\n"
        "                   with its reason (a not_runnable row, a line on stderr)\n"
        "  --epsilon LIST   comma-separated thresholds, each in [0, 1): every method\n"
        "                   of LIST that takes one (stream: early termination at\n"
        "                   transmittance E, exact at 0; guarded: contribution\n"
        "                   threshold; f2b: alpha threshold; reference: counts the\n"
        "                   fragments behind pixels below E) runs once per value, as\n"
        "                   its own entry NAME@E (e.g. stream@0.01), so each value is\n"
        "                   a point on the speed-against-error chart. Default: each\n"
        "                   method once at its default (stream exact)\n"
        "  --out DIR        writes DIR/results.csv, results.json, speed_vs_error.png,\n"
        "                   memory_vs_depth.png and report.md (which shows the PNGs);\n"
        "                   default: ./oitbench-MODEL (MODEL's name without its\n"
        "                   extension), created when missing\n"
        "  --orbit N        N views around the model, 1..100000, elevation 20 deg (default 8),\n"
        "                   about its up axis as oitstream's default views take it: z for\n"
        "                   STEP and IGES and a model flat in z, else y\n"
        "  --size WxH       image size, W and H in 1..16384 (default 512x512)\n"
        "  --frames F       timed frames per method per view, 1..100000 (default 5)\n"
        "  --warmup W       untimed frames per method per view first, 0..100000 (default 1)\n"
        "  --max-layers K   K of the capture backends, 2..16 (default 16)\n"
        "  --capture C      stream's K-slot fills: auto (default), stencil, array, or\n"
        "                   compute (no K-slot fill: packs captured in compute shaders)\n"
        "                   (oitstream --help, --capture)\n"
        "  --shading S      transparent (default) or translucent (Beer-Lambert and\n"
        "                   Fresnel, as oitstream --shading)\n"
        "  --colour-space S srgb (default): composite the sRGB-encoded colours; linear:\n"
        "                   in linear light, the result encoded (as oitstream)\n"
        "  --parts FILE     MODEL (a mesh)'s part file for stream, instead of converting\n"
        "  --mesh SRC       the source mesh of MODEL (a .oitp) for the in-core methods\n"
        "  --scheme S       the conversion's scheme, guaranteed or fast (default:\n"
        "                   oitprep's, now %s; see oitprep --help)\n"
        "  --part-triangles T  the fast scheme's part size, 1..16777216 (default %u)\n"
        "  --save-parts FILE   keep the converted part file as FILE (default: temporary)\n"
        "  --help           this text\n"
        "figures per entry: median and 95th-percentile ms per frame over all timed\n"
        "frames, GPU bytes at peak (every buffer and texture held: an in-core\n"
        "method's working memory and the mesh it uploaded, gpu_mesh_bytes of it; the\n"
        "stream's ring, cache, capture and per-pixel state), most layers seen, and\n"
        "against the reference per\n"
        "view: mean rmse, worst max_abs, worst %% of pixels off by > 1/255\n"
        "(pct_over_1_255) and the same over the pixels outside the reference's\n"
        "ambiguity mask (pct_over_1_255_outside_ambiguity: edge pixels, where\n"
        "raster and ray may disagree, left out; ~0 for exact methods), least PSNR;\n"
        "per view its depth complexity (the most surfaces the reference ray met at\n"
        "one pixel); results.csv carries the source model's triangle count on every\n"
        "row, and per entry which triangles it drew (geometry: source_mesh or\n"
        "part_file) and how many (drawn_triangles), and gpu_ms_median (GPU time from\n"
        "GL timestamp queries; empty where the driver has none); stdout gets a\n"
        "summary table.\n"
        "Absolute times mean something only from a GPU; ratios are side by side.\n"
        "plot: reads RUN_DIR/results.csv of each earlier run (this oitbench's format\n"
        "  or an older one, whose in-core GPU bytes left the mesh out, as the chart\n"
        "  notes; a malformed file is named with its line) and writes OUT_DIR/\n"
        "  time_vs_triangles.png (median ms against the run's triangles, log-log, a\n"
        "  line per method) and OUT_DIR/memory_vs_depth.png (GPU MiB at peak against\n"
        "  each view's depth, every run). A model file named 'plot' needs ./plot.\n"
        "bus: the host-to-device rate, as one JSON object on stdout: B bytes (default\n"
        "  256M) by glNamedBufferSubData and by glCopyNamedBufferSubData from a\n"
        "  persistently mapped buffer (the streamer's path) into GPU memory, each\n"
        "  timed with GL_TIME_ELAPSED and on the wall, the median of N (default 5);\n"
        "  GB/s are 1e9 bytes a second, -1 where the driver has no timer queries.\n"
        "progress goes to stderr.\n"
        "exit: 0 results written (even when some methods could not run), 1 runtime\n"
        "failure (reference failed, no method ran, output not writable), 2 usage\n"
        "error, 3 bad input model or results.csv, or a part file not made from the\n"
        "mesh it was given with.\n",
        method_list, default_scheme, default_part_triangles);
}
