/* The compute capture's shader stages (capture_compute.h): the files
 * glsl/compute_*.glsl, embedded at build time (CMakeLists.txt), and the
 * programs made of them (compute_glsl.c). */
#ifndef OIT_RENDER_COMPUTE_GLSL_H
#define OIT_RENDER_COMPUTE_GLSL_H

#include "view/render/gl/glsl_program.h"

/* Tile side in pixels: a work group of the tile pass. */
#define OIT_COMPUTE_TILE 16
/* uvec4s a triangle record takes (glsl/compute_common.glsl has the
 * layout). */
#define OIT_COMPUTE_RECORD_WORDS 10
/* Storage blocks a batch's records may span (glsl/compute_recs.glsl:
 * the block of a record by an if-chain); a program that reads or writes
 * records gets oit_compute_blocks_define's "#define CS_BLOCKS n\n" (n <=
 * this, what the driver's limits allow) before its other parts. */
#define OIT_COMPUTE_BLOCKS 8
/* Fragments a pixel keeps in registers per sweep. */
#define OIT_COMPUTE_SWEEP 16

/* After oit_glsl_vertex_lib: a triangle's set-up into its record, and its
 * count in every tile its box touches. */
extern const char oit_compute_setup_cs[];
/* Each record's index into the lists of its tiles. */
extern const char oit_compute_scatter_cs[];
/* The sweep's first work list: the rect's tiles with list entries. */
extern const char oit_compute_work_cs[];
/* A work list's indirect dispatch arguments from its count. */
extern const char oit_compute_args_cs[];
/* The iterations one loop of u_probe ran: fewer where the driver cuts
 * loops short. */
extern const char oit_compute_probe_cs[];
/* After u_mode and oit_glsl_state_io: which tiles have a pixel not yet
 * below epsilon. */
extern const char oit_compute_live_cs[];
/* oit_glsl_composite, oit_glsl_state_io, oit_compute_frag_inputs,
 * oit_glsl_fragment_lib, then oit_compute_tiles_cs: coverage, order and
 * compositing per pixel. */
extern const char oit_compute_frag_inputs[];
extern const char oit_compute_tiles_cs[];

/* The capture's programs, one a step of its frame (capture_compute.h). */
enum { OIT_COMPUTE_SETUP, OIT_COMPUTE_SCATTER, OIT_COMPUTE_LIVE, OIT_COMPUTE_TILES,
       OIT_COMPUTE_WORK, OIT_COMPUTE_ARGS, OIT_COMPUTE_PROBE, OIT_COMPUTE_PROGS };

/* The capture's programs into table, those with records after
 * blocks_define (compute_glsl.c); what compute_create builds. */
void oit_compute_programs(const char *blocks_define, oit_glsl_program table[OIT_COMPUTE_PROGS]);
/* Every program the compute capture can build, for every count of
 * blocks, each once (glsl_program.h). */
void oit_compute_glsl_variants(oit_glsl_visit *visit, void *user);

#endif
