/* The opaque pre-pass (shade.h, "Opaque triangles"): per pixel, the least
 * tie-rule key of the fragments of opaque triangles, so that the captures
 * and DFB discard every fragment behind it (oit_behind_opaque) before it
 * is counted or stored.
 *
 * Its owner (a capture, DFB) begins it with each frame and draws every
 * batch into it just before capturing that batch: a batch's opaque
 * fragments then hide the batch's own fragments behind them, and those of
 * every later batch. That is all the stream needs, because it captures
 * its packs front to back in a visibility order (design.md): a fragment
 * behind an opaque one along a pixel's ray belongs to the same part or to
 * a later one. The cost is one extra raster pass over each batch (vertex
 * work and a depth-like write per fragment); nothing is uploaded twice.
 *
 * The keys are an r32f texture of the frame's size cleared to +inf and
 * written with GL_MIN blending, which is exact and order-free; a
 * fragment's key is a positive float, so float order is its bits' order.
 * Requires a current GL context for every call but on_frame. */
#ifndef OIT_RENDER_OPAQUE_KEYS_H
#define OIT_RENDER_OPAQUE_KEYS_H

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_opaque_keys oit_opaque_keys;

oit_status oit_opaque_keys_create(oit_opaque_keys **out, oit_error *err);
void oit_opaque_keys_destroy(oit_opaque_keys *k);
/* Its program, for the offline check (glsl_program.h). */
void oit_opaque_keys_glsl_variants(oit_glsl_visit *visit, void *user);

/* Starts a frame of view v. On (returns 1 in *on) when v's shading has
 * opaque triangles (oit_shading_opaque): the keys are cleared to +inf and
 * bound at OIT_TEX_OPAQUE_KEYS. o: the caller's depth (NULL: none), whose
 * projection the pre-pass then draws with, as the captures do. */
oit_status oit_opaque_keys_begin(oit_opaque_keys *k, const oit_view *v, const oit_opaque_depth *o,
                                 int *on, oit_error *err);
/* Draws the opaque triangles of meshes[0..n) into the keys within the GL
 * rect r (bottom rows first, exclusive ends), with the scratch of draws
 * (NULL: one oit_gpu_mesh_draw a mesh); nothing when the frame is off. Leaves the keys bound at
 * OIT_TEX_OPAQUE_KEYS and a framebuffer of k's bound. */
void oit_opaque_keys_draw(oit_opaque_keys *k, struct oit_gpu_draws *draws,
                          const oit_gpu_mesh *const *meshes, int n, const int r[4]);
/* GPU bytes of the key texture. */
uint64_t oit_opaque_keys_gpu_bytes(const oit_opaque_keys *k);

#ifdef __cplusplus
}
#endif
#endif
