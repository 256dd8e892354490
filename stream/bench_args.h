/* oitbench's command line, validated, with no I/O done yet. Parsing never
 * prints; a usage error comes back as OIT_ERR_ARGUMENT with one line. */
#ifndef OIT_STREAM_BENCH_ARGS_H
#define OIT_STREAM_BENCH_ARGS_H

#include <stddef.h>
#include <stdio.h>

#include "oit/status.h"

#define OIT_BENCH_MAX_METHODS 16

typedef struct oit_bench_args {
    int help;
    const char *model;
    /* names checked against render_methods.h; no duplicates */
    const char *methods[OIT_BENCH_MAX_METHODS];
    int method_count;
    int orbit;          /* views around the model; default 8 */
    int width, height;  /* default 512x512 */
    int frames, warmup; /* per method per view; default 5 and 1 */
    int max_layers;     /* K of the capture backends; default 16 */
    const char *out;    /* folder, created when missing */
} oit_bench_args;

/* buf receives the split copy of --methods; args->methods point into it. */
oit_status oit_bench_args_parse(int argc, char **argv, oit_bench_args *args, char *buf,
                                size_t cap, oit_error *err);

void oit_bench_usage(FILE *f, const char *method_list);

#endif
