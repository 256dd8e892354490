/* oitbench's command line, validated, with no I/O done yet. Parsing never
 * prints; a usage error comes back as OIT_ERR_ARGUMENT with one line.
 * Two forms: a measurement (MODEL [--methods LIST] [--out DIR] ...) and
 * "plot OUT_DIR RUN_DIR..." (charts across earlier runs). */
#ifndef OIT_OITBENCH_BENCH_ARGS_H
#define OIT_OITBENCH_BENCH_ARGS_H

#include <stddef.h>
#include <stdio.h>

#include "oit/status.h"
#include "tools/oitbench/bench_run.h"

#define OIT_BENCH_MAX_METHODS 16
#define OIT_BENCH_MAX_EPSILONS 16
#define OIT_BENCH_MAX_ENTRIES 64
#define OIT_BENCH_MAX_RUNS 256
/* What runs without --methods: the exact methods and the common
 * approximate baselines (a method the driver cannot run becomes a row with
 * its reason, bench_run.h). */
#define OIT_BENCH_DEFAULT_METHODS "dfb,stream,compute,pll,wboit,unsorted"

typedef struct oit_bench_args {
    int help;
    int plot;           /* the "plot" form: plot_out and runs are set */
    const char *model;
    /* names checked against tools/common/methods.h; no duplicates */
    const char *methods[OIT_BENCH_MAX_METHODS];
    int method_count;
    int methods_defaulted; /* no --methods: OIT_BENCH_DEFAULT_METHODS */
    /* --epsilon: thresholds in [0, 1), no duplicates; none: defaults */
    float epsilons[OIT_BENCH_MAX_EPSILONS];
    int epsilon_count;
    /* what runs: every method once, except that a method taking a threshold
     * runs once per --epsilon value, as "NAME@E" */
    oit_bench_entry entries[OIT_BENCH_MAX_ENTRIES];
    int entry_count;
    oit_shading_mode shading; /* default transparent */
    oit_colour_space colour_space; /* default srgb (view/render/image/shade.h) */
    int orbit;          /* views around the model; default 8 */
    int width, height;  /* default 512x512 */
    int frames, warmup; /* per method per view; default 5 and 1 */
    int max_layers;     /* K of the capture backends; default 16 */
    oit_render_capture capture; /* --capture: the stream's; 0 auto */
    const char *out;    /* folder, created when missing; default out_buf */
    char out_buf[512];  /* "oitbench-STEM", MODEL's name without extension */
    /* which triangles the methods draw (bench_models.h) */
    const char *parts;      /* --parts: MODEL's part file (MODEL a mesh) */
    const char *mesh;       /* --mesh: the part file's source (MODEL a .oitp) */
    const char *save_parts; /* --save-parts: keep the conversion there */
    const char *scheme;     /* --scheme guaranteed|fast; NULL: oitprep's default */
    unsigned part_triangles; /* --part-triangles; 0: the scheme's default */
    /* the plot form */
    const char *plot_out;
    const char *runs[OIT_BENCH_MAX_RUNS];
    int run_count;
} oit_bench_args;

/* buf receives the split copy of --methods; args->methods point into it,
 * the other strings into argv. */
oit_status oit_bench_args_parse(int argc, char **argv, oit_bench_args *args, char *buf,
                                size_t cap, oit_error *err);

/* default_scheme and default_part_triangles: the conversion's, as oitprep
 * has them (prepare/convert/convert.h). */
void oit_bench_usage(FILE *f, const char *method_list, const char *default_scheme,
                     unsigned default_part_triangles);

#endif
