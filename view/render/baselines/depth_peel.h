/* Depth peeling, front to back (Everitt 2001). Each geometry pass keeps, per
 * pixel, the nearest fragment strictly behind the layer peeled before: the
 * fragment shader discards t <= t_prev (read from the previous layer) and
 * the depth test (LESS, depth = t scaled by a power of two, so the scaling
 * is exact and the test orders exactly like t) keeps the nearest of the
 * rest. A compute pass composites the new layer into a per-pixel state
 * (shade.h), and peeling stops when an occlusion query reports that a pass
 * kept no fragment. Cost: max_layers + 1 geometry passes.
 *
 * Exact, equal to DFB's (key, prim) order (the tie rule, shade.h), ties
 * included: a pass discards every fragment at or before the previous layer
 * in (key, prim) order, which the layer target holds whole, and of the rest
 * the depth test (LESS on the key) keeps the nearest key and, among tied
 * keys, the first fragment rasterized: GL rasterizes in primitive order, so
 * the lowest prim, as (key, prim) puts first. The next pass then finds the
 * other tied fragments after this one and peels them in turn.
 *
 * Stats: fragments = fragments composited,
 * max_layers = layers peeled, batches = geometry passes, gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_DEPTH_PEEL_H
#define OIT_RENDER_BASELINES_DEPTH_PEEL_H

#include "view/render/gl/gpu_mesh.h"

typedef struct oit_depth_peel oit_depth_peel;

#endif
