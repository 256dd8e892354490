/* The compute capture's programs (capture_compute.h has the design): its
 * stages are the files glsl/compute_*.glsl (compute_glsl.h); the fragment
 * maths come from frag_glsl.h's libraries, not copies of them. */

#include "view/render/capture/capture_glsl.h"
#include "view/render/capture/compute_glsl.h"
#include "view/render/gl/glsl_bindings.h"
#include "view/render/gl/frag_glsl.h"

#include <stdio.h>
#include <string.h>

_Static_assert(OIT_COMPUTE_SWEEP == 16,
               "compute_tiles.glsl's cs_consider shifts 15 slots, written out");
_Static_assert(OIT_COMPUTE_BLOCKS == 8,
               "compute_recs.glsl names 8 blocks");
_Static_assert(OIT_BIND_RECS7 - OIT_BIND_RECS1 == 6, "glsl_bindings.h: 7 record bindings");

/* The C constants that the stages of compute_common.glsl name. */
static const char defines[] =
    "#define CS_TILE " OIT_GLSL_STR(OIT_COMPUTE_TILE) "\n"
    "#define CS_REC " OIT_GLSL_STR(OIT_COMPUTE_RECORD_WORDS) "u\n"
    "#define CS_N " OIT_GLSL_STR(OIT_COMPUTE_SWEEP) "u\n";

static const oit_glsl_program programs[OIT_COMPUTE_PROGS] = {
    [OIT_COMPUTE_SETUP] = {"compute capture set-up",
                           .cs = {defines, oit_glsl_vertex_lib, oit_compute_setup_cs}},
    [OIT_COMPUTE_SCATTER] = {"compute capture scatter", .cs = {defines, oit_compute_scatter_cs}},
    [OIT_COMPUTE_LIVE] = {"compute capture live tiles",
                          .cs = {defines, oit_capture_mode, oit_glsl_state_io,
                                 oit_compute_live_cs}},
    [OIT_COMPUTE_TILES] = {"compute capture sweep",
                           .cs = {defines, oit_glsl_composite, oit_glsl_state_io,
                                  oit_compute_frag_inputs, oit_glsl_fragment_lib,
                                  oit_compute_tiles_cs}},
    [OIT_COMPUTE_WORK] = {"compute capture work list", .cs = {defines, oit_compute_work_cs}},
    [OIT_COMPUTE_ARGS] = {"compute capture dispatch", .cs = {oit_compute_args_cs}},
    [OIT_COMPUTE_PROBE] = {"compute capture loop probe", .cs = {oit_compute_probe_cs}},
};

/* The programs that read or write records: their blocks' count first. */
static int with_records(int i)
{
    return i == OIT_COMPUTE_SETUP || i == OIT_COMPUTE_SCATTER || i == OIT_COMPUTE_TILES;
}

void oit_compute_blocks_define(int blocks, char *buf, size_t size)
{
    snprintf(buf, size, "#define CS_BLOCKS %d\n", blocks);
}

void oit_compute_programs(const char *blocks_define, oit_glsl_program table[OIT_COMPUTE_PROGS])
{
    memcpy(table, programs, sizeof programs);
    for (int i = 0; i < OIT_COMPUTE_PROGS; i++) {
        if (!with_records(i))
            continue;
        const char **cs = table[i].cs;
        memmove(cs + 1, cs, sizeof(cs[0]) * (OIT_GLSL_PARTS_MAX - 1));
        cs[0] = blocks_define;
    }
}

void oit_compute_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int blocks = 1; blocks <= OIT_COMPUTE_BLOCKS; blocks++) {
        char define[32];
        oit_glsl_program table[OIT_COMPUTE_PROGS];
        oit_compute_blocks_define(blocks, define, sizeof define);
        oit_compute_programs(define, table);
        for (int i = 0; i < OIT_COMPUTE_PROGS; i++)
            if (with_records(i) || blocks == 1)
                visit(user, &table[i]);
    }
}
