/* Per-pixel linked lists (PLL), exact. One geometry pass appends every
 * fragment to a node buffer (slot from one atomic counter) and links it
 * into its pixel's list (atomic exchange of the head); a compute pass walks
 * each list, sorts by (t, prim) and composites per shade.h.
 *
 * Node buffer sizing: a frame starts with the capacity the previous frames
 * needed (at first one node per pixel). The counter keeps counting past the
 * capacity, so after the pass the frame's true fragment count is known; when
 * it overflowed, the node buffer grows to that count and the frame is drawn
 * once more. A fragment is never dropped, and the capacity never shrinks.
 *
 * Resolve: lists of up to 32 fragments are insertion-sorted in registers;
 * longer ones are merge-sorted in place by relinking (stable, O(n log n),
 * no layer limit of its own). On llvmpipe, which stops a shader's loops
 * after 65535 iterations in all, that holds to about 2500 fragments a pixel;
 * the quadratic walk it replaces broke at about 256.
 *
 * Stats: fragments (the counter), max_layers (longest list), batches = the
 * geometry passes drawn (1, or 2 after an overflow), gpu_bytes_peak. */
#ifndef OIT_RENDER_PPLL_H
#define OIT_RENDER_PPLL_H

#include "render/gpu_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_pll oit_pll;

oit_status oit_pll_create(oit_pll **out, oit_error *err);
void oit_pll_destroy(oit_pll *p);

/* Renders meshes[0..n) as one scene; out is allocated by the call. */
oit_status oit_pll_render(oit_pll *p, const oit_gpu_mesh *const *meshes, int n,
                          const oit_view *view, oit_image *out, oit_frame_stats *stats,
                          oit_error *err);

/* Nodes the node buffer holds now (grows with the frames seen). */
uint64_t oit_pll_capacity(const oit_pll *p);

#ifdef __cplusplus
}
#endif
#endif
