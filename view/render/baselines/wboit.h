/* Weighted blended OIT (McGuire & Bavoil, JCGT 2013), APPROXIMATE. One
 * geometry pass with depth test off and additive blending into two targets:
 *   accum  (RGBA32F) += (a * colour, a) * w(t, a)
 *   reveal (R32F)    *= (1 - a)
 * then one resolve per pixel:
 *   final = accum.rgb / max(accum.a, 1e-5) * (1 - reveal) + background * reveal.
 * Total coverage (1 - reveal) is exact; how it is split between the layers
 * is a depth-weighted average instead of the ordered product, so colours
 * blur across layers. Translucent absorption is left out (it needs order).
 *
 * Weight: the paper's eq. 10 with t, the distance from the eye, for |z|:
 *   w(t, a) = a * clamp(10 / (1e-5 + (t / 5)^2 + (t / 200)^6), 1e-2, 3e3)
 * so nearer and more opaque fragments dominate; the constants suit scenes a
 * few to a few hundred units deep. 32-bit float targets, because 16-bit ones overflow
 * past ~20 layers at the weight's top (3e3).
 *
 * Stats: fragments from an occlusion query, max_layers unknown (0),
 * batches 1, gpu_bytes_peak = the three float targets. */
#ifndef OIT_RENDER_BASELINES_WBOIT_H
#define OIT_RENDER_BASELINES_WBOIT_H

#include "view/render/gl/gpu_mesh.h"

typedef struct oit_wboit oit_wboit;

#endif
