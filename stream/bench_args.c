/* oitbench's command line (bench_args.h). */
#include "stream/bench_args.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "stream/render_methods.h"

static int parse_int(const char *v, int *out, long lo, long hi)
{
    char *end;
    errno = 0;
    long x = strtol(v, &end, 10);
    if (errno || end == v || *end || x < lo || x > hi)
        return 0;
    *out = (int)x;
    return 1;
}

static int parse_size(const char *v, int *w, int *h)
{
    char a[32];
    const char *x = strchr(v, 'x');
    if (!x || (size_t)(x - v) >= sizeof a)
        return 0;
    memcpy(a, v, (size_t)(x - v));
    a[x - v] = 0;
    return parse_int(a, w, 1, 16384) && parse_int(x + 1, h, 1, 16384);
}

/* Splits "dfb,pll" in place in buf; every name must exist and appear once. */
static oit_status split_methods(const char *list, oit_bench_args *a, char *buf, size_t cap,
                                oit_error *err)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_render_method_names(names, sizeof names);
    if (strlen(list) >= cap)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods '%s' is too long", list);
    strcpy(buf, list);
    a->method_count = 0;
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (!oit_render_method_find(t))
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

/* One "--name value" option; 0 when the name is unknown. */
static int value_option(oit_bench_args *a, const char *opt, const char *v, char *buf, size_t cap,
                        oit_status *s, oit_error *err)
{
    if (!strcmp(opt, "--methods")) *s = split_methods(v, a, buf, cap, err);
    else if (!strcmp(opt, "--orbit")) {
        if (!parse_int(v, &a->orbit, 1, 100000)) *s = bad(err, opt, v, "a view count >= 1");
    } else if (!strcmp(opt, "--size")) {
        if (!parse_size(v, &a->width, &a->height)) *s = bad(err, opt, v, "WxH, e.g. 512x512");
    } else if (!strcmp(opt, "--frames")) {
        if (!parse_int(v, &a->frames, 1, 100000)) *s = bad(err, opt, v, "a frame count >= 1");
    } else if (!strcmp(opt, "--warmup")) {
        if (!parse_int(v, &a->warmup, 0, 100000)) *s = bad(err, opt, v, "a frame count >= 0");
    } else if (!strcmp(opt, "--max-layers")) {
        if (!parse_int(v, &a->max_layers, 2, 16)) *s = bad(err, opt, v, "K in [2, 16]");
    } else if (!strcmp(opt, "--out")) a->out = v;
    else return 0;
    return 1;
}

oit_status oit_bench_args_parse(int argc, char **argv, oit_bench_args *a, char *buf, size_t cap,
                                oit_error *err)
{
    memset(a, 0, sizeof *a);
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
    if (a->method_count == 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--methods is required (see --help)");
    if (!a->out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--out DIR is required (see --help)");
    return OIT_OK;
}

void oit_bench_usage(FILE *f, const char *method_list)
{
    fprintf(f,
        "usage: oitbench MODEL_OR_PARTFILE --methods LIST --out DIR [options]\n"
        "  Renders MODEL (a mesh, or a .oitp part file) from an orbit of views with\n"
        "  every method of LIST, interleaved view by view (warm-up frames, then timed\n"
        "  frames per method, methods round-robin, so that drift hits all alike), and\n"
        "  compares each method's image with the Embree reference of the same view.\n"
        "  A method that cannot open or render the case (stream on a mesh, out of\n"
        "  memory, no GL) is reported with the reason, not dropped.\n"
        "options:\n"
        "  --methods LIST   comma-separated, from %s\n"
        "                   (guarded and f2b run at their seeds' thresholds, 0.0025\n"
        "                   and 0.02; see oitstream --help for each method)\n"
        "  --out DIR        writes DIR/results.csv, DIR/results.json, DIR/report.md\n"
        "  --orbit N        N views around the model, elevation 20 deg (default 8)\n"
        "  --size WxH       image size (default 512x512)\n"
        "  --frames F       timed frames per method per view (default 5)\n"
        "  --warmup W       untimed frames per method per view first (default 1)\n"
        "  --max-layers K   K of the capture backends, 2..16 (default 16)\n"
        "  --help           this text\n"
        "figures per method: median and 95th-percentile ms per frame over all timed\n"
        "frames, GPU bytes at peak, most layers seen, and against the reference per\n"
        "view: mean rmse, worst max_abs, worst %% of pixels off by > 1/255, least PSNR.\n"
        "Absolute times mean something only from a GPU; ratios are side by side.\n"
        "progress goes to stderr.\n"
        "exit: 0 results written (even when some methods could not run), 1 runtime\n"
        "failure (reference failed, no method ran, output not writable), 2 usage\n"
        "error, 3 bad input model.\n",
        method_list);
}
