/* Front-to-back blending with early fragment discarding (Vlcek
 * et al. 2010). APPROXIMATE: exact only where its two conditions hold.
 *
 * The seed's method: draw the primitives front to back with premultiplied
 * colour in rgb and transmittance in alpha, blended by
 * glBlendFuncSeparate(DST_ALPHA, ONE, ZERO, SRC_ALPHA) (C += T a c,
 * T *= 1 - a) into a texture that the fragment shader also samples; a
 * fragment whose pixel's transmittance already reads below the alpha
 * threshold is discarded before any shading. The frame is C + T *
 * background. The seed's application supplies the front-to-back order;
 * here each frame computes it: a compute pass keys every triangle by the
 * view depth of its centroid, the CPU sorts the keys (stable radix, ties by
 * triangle index, as the exact methods break t ties by prim), and a compute
 * pass copies the triangles into that order for the draw.
 *
 * What is exact: with threshold 0 no fragment is discarded and the image
 * equals the exact one (within float rounding) wherever the centroid order
 * is the per-pixel depth order, e.g. non-intersecting triangles parallel
 * to the image plane. Elsewhere (intersecting or steep overlapping
 * triangles) it blends out of order like any sorted-primitive method.
 *
 * What the threshold costs: in that order, a discarded fragment's pixel had
 * transmittance T < threshold when it was met, and everything behind can
 * change the pixel by at most T per channel; so the error is below the
 * threshold, and zero on pixels whose transmittance never falls below it.
 * Reading the target while blending into it is undefined in GL (the seed's
 * cache incoherence): a stale read is an older, higher T, which only
 * discards less, so the bound holds; glTextureBarrier after the clear keeps
 * old frames out, as the seed asks.
 *
 * Default threshold 0.02, the value the seed measures as "roughly optimal"
 * (Table 5: 0.01 shows no visible difference, 0.05 small changes).
 * Translucent shading blends colour and Fresnel alpha but ignores
 * absorption between surfaces (it needs per-pixel state blending lacks).
 *
 * Memory: two RGBA32F targets per pixel (accumulation, output) and, per
 * triangle, a sort key, its rank and the sorted copy (48 bytes).
 *
 * Stats: fragments = fragments blended (GL_SAMPLES_PASSED; discarded ones
 * are not), max_layers = 0 (not known without a count pass), batches = 1,
 * gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_F2B_H
#define OIT_RENDER_BASELINES_F2B_H

#include "render/gpu_mesh.h"

#define OIT_F2B_DEFAULT_THRESHOLD 0.02f

typedef struct oit_f2b oit_f2b;

/* Alpha (transmittance) threshold in [0, 1); 0 discards nothing.
 * OIT_ERR_ARGUMENT outside it (NaN included). The method (methods.h)
 * starts at OIT_F2B_DEFAULT_THRESHOLD. */
oit_status oit_f2b_set_threshold(oit_f2b *f, float threshold, oit_error *err);

#endif
