/* Writes every GLSL program the renderer can build (each module's
 * oit_*_glsl_variants, glsl_program.h) as the stage files GL would compile,
 * for the offline check (test_glsl_offline.sh): DIR/NNNN.vert, .frag or
 * .comp, and DIR/index.txt, a line a program: "NNNN HASH what". HASH is
 * oit_glsl_program_hash's, which the suite's log of built programs
 * (OIT_GLSL_LOG) uses too. Needs no GL context.
 * usage: glsl_variants DIR */
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/capture/capture_glsl_variants.h"
#include "view/render/gl/glsl_program.h"

#include <stdio.h>
#include <stdlib.h>

typedef struct writer {
    const char *dir;
    FILE *index;
    int n, failed;
} writer;

static void write_stage(writer *w, const oit_glsl_program *p, oit_glsl_stage stage, const char *ext)
{
    const char *src[OIT_GLSL_SOURCES_MAX];
    if (!oit_glsl_program_stage(p, stage, src))
        return;
    char path[4096];
    snprintf(path, sizeof path, "%s/%04d.%s", w->dir, w->n, ext);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "glsl_variants: %s: cannot write\n", path);
        w->failed = 1;
        return;
    }
    for (int i = 0; src[i]; i++)
        fputs(src[i], f);
    if (fclose(f) != 0)
        w->failed = 1;
}

static void visit(void *user, const oit_glsl_program *p)
{
    writer *w = user;
    write_stage(w, p, OIT_GLSL_VERTEX, "vert");
    write_stage(w, p, OIT_GLSL_FRAGMENT, "frag");
    write_stage(w, p, OIT_GLSL_COMPUTE, "comp");
    fprintf(w->index, "%04d %016llx %s\n", w->n, (unsigned long long)oit_glsl_program_hash(p), p->what);
    w->n++;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: glsl_variants DIR\n");
        return 2;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/index.txt", argv[1]);
    writer w = {argv[1], fopen(path, "w"), 0, 0};
    if (!w.index) {
        fprintf(stderr, "glsl_variants: %s: cannot write\n", path);
        return 1;
    }
    oit_gl_glsl_variants(visit, &w);
    oit_capture_glsl_variants(visit, &w);
    oit_baseline_glsl_variants(visit, &w);
    if (fclose(w.index) != 0 || w.failed)
        return 1;
    printf("glsl_variants: %d programs in %s\n", w.n, argv[1]);
    return 0;
}
