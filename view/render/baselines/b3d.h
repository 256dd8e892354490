/* Fixed per-pixel arrays, exact: the basic A-buffer that Crassin starts
 * from ("B3D": a 3D block of width x height x L fragment slots). A count
 * pass adds up each pixel's fragments, a reduction finds the frame's most
 * (L), the slot array is sized to L layers for every pixel, a store pass
 * puts each fragment in its pixel's next slot (atomic counter), and the
 * resolve sorts by (t, prim) and composites exactly like PLL (the same
 * oit_glsl_sorted_resolve, walking the pixel's slots).
 *
 * Memory is the point of this baseline: width * height * L * 16 bytes for
 * the slots, whatever most pixels need, so one deep pixel makes the whole
 * frame pay. The slots live in an RGBA32UI 2D array texture (layer = slot),
 * not a storage buffer, so L is not capped by the storage block size (128
 * MiB on llvmpipe) but by GL_MAX_ARRAY_TEXTURE_LAYERS and memory; beyond
 * either the frame fails with OIT_ERR_NOMEM naming the size. The array only
 * grows (a frame needing fewer layers reuses it), like PLL's pool.
 *
 * Stats: fragments (all, stored), max_layers (L of the frame), batches = 2
 * geometry passes (count, store), gpu_bytes_peak (slots included). */
#ifndef OIT_RENDER_BASELINES_B3D_H
#define OIT_RENDER_BASELINES_B3D_H

#include "view/render/gl/gpu_mesh.h"

typedef struct oit_b3d oit_b3d;

#endif
