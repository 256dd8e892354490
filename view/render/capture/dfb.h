/* Dynamic Fragment Buffer (Maule et al.): count fragments per pixel, prefix-sum
 * the counts in a compute shader, store every fragment at its pixel's offset,
 * sort per pixel and composite. The fragment store is sized to the frame's
 * exact fragment count and grown when a frame needs more; nothing is ever
 * dropped. The in-core exact renderer and the fallback of the streaming path.
 *
 * Depth: unlimited on a GPU. llvmpipe stops a shader's loops after 65535
 * iterations in all, which the resolve's heap sort (about 1.5 n log2 n
 * steps) reaches near 3000 fragments on one pixel; beyond that the pixel is
 * wrong there, silently. Frames whose fragments exceed one storage buffer
 * are stored and resolved in bands of rows (stats: batches = bands). */
#ifndef OIT_RENDER_DFB_H
#define OIT_RENDER_DFB_H

#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/frag_glsl.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_dfb oit_dfb;

oit_status oit_dfb_create(oit_dfb **out, oit_error *err);
void oit_dfb_destroy(oit_dfb *d);
/* Its programs, for the offline check (glsl_program.h). */
void oit_dfb_glsl_variants(oit_glsl_visit *visit, void *user);

/* Renders meshes[0..n) as one scene into out: empty (allocated by the call;
 * free with oit_image_free) or an image of the view's size, written in place
 * (oit_image_reserve). counts, when non-NULL, receives width*height fragment
 * counts, row 0 at the top (for the layer heat map). */
oit_status oit_dfb_render(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                          const oit_view *view, oit_image *out,
                          uint32_t *counts, oit_frame_stats *stats,
                          oit_error *err);

/* Renders as oit_dfb_render, but reads nothing back: each pixel's
 * composited state (premultiplied colour C and transmittance T, before any
 * background) is left in a GPU buffer in oit_glsl_state_io's layout for
 * view->shading.mode (frag_glsl.h), width*height pixels, GL rows (bottom
 * first). *state receives the buffer's name; it belongs to d and holds the
 * frame until d renders again or is destroyed. view->shading.background is
 * not used. For liboit, which blends the state over a caller's framebuffer. */
oit_status oit_dfb_render_state(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                                const oit_view *view, unsigned *state,
                                oit_frame_stats *stats, oit_error *err);

/* Bytes a pixel of view takes in DFB's largest per-pixel buffer, which
 * must hold the whole frame in one storage binding: the colour (16) for
 * oit_dfb_render, the state (shade.h) for oit_dfb_render_state (state 1).
 * Its fragments are stored in bands past one binding; a frame whose output
 * does not fit is refused, to be rendered in bands (view/render/gl/band.h). */
uint64_t oit_dfb_pixel_bytes(const oit_view *view, int state);

/* GPU phases of the next frames are marked on t (view/render/gl/gpu_timer.h: the
 * count pass and scan as pass 1, the store as pass 2; NULL: none). */
struct oit_gpu_timer;
void oit_dfb_set_gpu_timer(oit_dfb *d, struct oit_gpu_timer *t);

/* The caller's opaque depth (frag_glsl.h, oit_opaque_depth) for d's next
 * frames; NULL: none (the default). Fragments behind it are neither counted
 * nor stored; the texture must be bound at unit OIT_TEX_OPAQUE_DEPTH while
 * d renders. */
void oit_dfb_set_opaque(oit_dfb *d, const oit_opaque_depth *o);

#ifdef __cplusplus
}
#endif
#endif
