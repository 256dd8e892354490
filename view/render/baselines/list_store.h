/* The frame machinery the list baselines share: per-pixel linked lists
 * (ppll.h), paged lists (ppll4.h) and guarded OIT (guarded.h). They differ
 * only in their append shader and in how a pixel's list is walked.
 *
 * Storage: per pixel, words_per_pixel head words (cleared to 0xffffffff each
 * pass); a pool of units, each of slots_per_unit fragment slots (a node, or
 * a page of nodes), with one link word per unit; one atomic unit counter.
 *
 * Sizing, the same policy for all three: a frame starts with the capacity
 * the previous frames needed (at first one fragment slot per pixel, so every
 * method starts with the same bytes whatever its unit). The append
 * shader takes units from the counter, which keeps counting past the
 * capacity (the shader writes no unit at or beyond u_capacity), so after the
 * pass the frame's need is known; when it overflowed, the pool grows to that
 * need and the frame is drawn again. A fragment is never dropped, and the
 * capacity never shrinks. A method whose need can change between passes
 * (units wasted under contention, culling that depends on what was stored)
 * may take a few passes; one whose count overstates the need (growth_cap)
 * grows by at most that factor a pass; more than OIT_LIST_MAX_PASSES is an
 * error.
 *
 * Resolve: oit_glsl_sorted_resolve (baseline_common.h) with the method's
 * walk, so every list method sorts and composites exactly like the others.
 *
 * GLSL interface, for both the append and the walk: heads at OIT_BIND_COUNTS
 * (uint; pixel p's words at p * words_per_pixel), slots at OIT_BIND_FRAGS
 * (uvec4; unit u's at u * slots_per_unit), links at OIT_BIND_TOTALS (uint per
 * unit), Stats { uint counter; uint max_len; uint total; } at OIT_BIND_STATE,
 * and the append shader's `layout(location = OIT_LOC_CAPACITY) uniform uint
 * u_capacity` (units). The append program is built from oit_glsl_fragment_gen,
 * oit_glsl_premultiplied and the method's fragment stage.
 *
 * Stats: fragments (stored, counted by the resolve), max_layers (longest
 * list), batches = geometry passes drawn, gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_LIST_STORE_H
#define OIT_RENDER_BASELINES_LIST_STORE_H

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/methods.h"
#include "view/render/gl/gpu_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_LIST_MAX_PASSES 16

/* The walk GLSL of a store whose units are single nodes, each with its own
 * link (PLL, guarded; glsl/node_walk.glsl): nodes, links, relinking for
 * the merge sort, and a pixel's list from the first of its head words,
 * after OIT_LIST_HEAD_WORDS_GLSL(WORDS), the method's words_per_pixel
 * spelt as the GLSL uint that the walk multiplies by. */
extern const char oit_glsl_node_walk[];
#define OIT_LIST_HEAD_WORDS_GLSL(WORDS) "#define OIT_LIST_HEAD_WORDS " OIT_GLSL_STR(WORDS) "u\n"

typedef struct oit_list_desc {
    const char *method;       /* names the method in errors: "PLL" */
    const char *append_fs;    /* the fragment stage's main */
    const char *walk[2];      /* oit_list_first/next/load and their buffers:
                                 GLSL pieces up to the first NULL */
    uint32_t slots_per_unit;  /* 1: nodes; 4: pages of four */
    uint32_t words_per_pixel; /* head words per pixel */
    uint64_t max_units;       /* the most units the method's indices address */
    uint32_t growth_cap;      /* 0: an overflowing pass grows the pool to its
                                 count; g: to at most g times the pool */
} oit_list_desc;

enum { OIT_LIST_PROG_APPEND, OIT_LIST_PROG_RESOLVE, OIT_LIST_PROG_N };

/* Its fields are the store's own (list_store.c); the list methods hold one
 * (methods.h allocates it). */
typedef struct oit_list_store {
    oit_list_desc d;
    GLuint prog[OIT_LIST_PROG_N], fbo;
    oit_gpu_buffers b;
    uint64_t units; /* pool capacity in units */
    uint64_t limit; /* this frame's most bytes in one storage binding; 0: the driver's */
    int *split;     /* this frame's request to be split (oit_method_frame.split) */
} oit_list_store;

/* A list method's functions for OIT_BASELINE_METHOD_OF (methods.h): init
 * with the method's desc (its strings must outlive the store), release,
 * and one frame of meshes[0..n) as one scene. */
oit_status oit_list_store_init(oit_list_store *ls, const oit_list_desc *desc, oit_error *err);
void oit_list_store_release(oit_list_store *ls);
oit_status oit_list_store_render(oit_list_store *ls, const oit_gpu_mesh *const *meshes, int n,
                                 const oit_view *v, oit_image *out, oit_frame_stats *stats,
                                 oit_error *err);

/* The table of the list method T (a typedef of oit_list_store) whose store
 * DESC (a static oit_list_desc) describes; a method with more to set up
 * writes its own T_init and uses OIT_BASELINE_METHOD_OF. */
#define OIT_LIST_METHOD(NAME, T, DESC, FLAGS, SET)                                          \
    static oit_status T##_init(T *ls, oit_error *err)                                       \
    {                                                                                       \
        return oit_list_store_init(ls, &(DESC), err);                                       \
    }                                                                                       \
    OIT_BASELINE_METHOD_FRAMED(NAME, T, (DESC).method, T##_init, oit_list_store_release,    \
                               oit_list_store_render, OIT_LIST_FRAME, FLAGS, SET)

/* The method frame's storage limit and split request (view/render/method.h)
 * for the next frame: a pool that must pass the limit asks for the bands
 * of rows that would each fit, and the frame fails. split may be NULL. */
void oit_list_store_frame(oit_list_store *ls, uint64_t limit, int *split);
#define OIT_LIST_FRAME(impl, f) oit_list_store_frame((impl), (f)->store_limit, (f)->split)

/* The store's programs for desc, each once, as oit_list_store_init builds
 * them (view/render/gl/glsl_program.h): a list method's oit_*_glsl_variants. */
void oit_list_store_glsl_variants(const oit_list_desc *desc, oit_glsl_visit *visit, void *user);

/* For the method's own uniforms (a threshold). */
unsigned oit_list_store_append_program(const oit_list_store *ls);

/* Fragment slots the pool holds now (units * slots_per_unit). */
uint64_t oit_list_store_capacity(const oit_list_store *ls);

#ifdef __cplusplus
}
#endif
#endif
