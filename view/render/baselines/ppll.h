/* Per-pixel linked lists (PLL), exact. One geometry pass appends every
 * fragment to a node buffer (slot from one atomic counter) and links it
 * into its pixel's list (atomic exchange of the head); a compute pass walks
 * each list, sorts by (t, prim) and composites per shade.h.
 *
 * Built on list_store.h, which holds the policy it shares with ppll4.h and
 * guarded.h: node buffer sizing (at first one node per pixel; an overflowing
 * frame grows the buffer to its true fragment count and is drawn once more,
 * so a fragment is never dropped, and the capacity never shrinks) and the
 * resolve (oit_glsl_sorted_resolve: up to 32 fragments sorted in registers,
 * longer lists merge-sorted by relinking, O(n log n); on llvmpipe, which
 * stops a shader's loops after 65535 iterations in all, that holds to about
 * 2500 fragments a pixel).
 *
 * Stats: fragments (stored: all of them), max_layers (longest list),
 * batches = the geometry passes drawn (1, or 2 after an overflow),
 * gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_PPLL_H
#define OIT_RENDER_BASELINES_PPLL_H

#include "view/render/gl/gpu_mesh.h"

/* A list store (list_store.h) with this method's shaders. */
typedef struct oit_list_store oit_pll;

/* Nodes the node buffer holds now (grows with the frames seen). */
uint64_t oit_pll_capacity(const oit_pll *p);

#endif
