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
 *
 * Chunks. The seed's shader samples the texture it blends into, in the
 * same draw: a feedback loop whose reads GL leaves undefined (GL 4.5
 * section 9.3; glTextureBarrier only shows earlier draws' writes, and only
 * if each texel was written once since). Drivers differ: llvmpipe shows
 * every earlier fragment's write, NVIDIA's texture cache none, so there
 * nothing was ever discarded. Here the sorted triangles are drawn in
 * OIT_F2B_CHUNKS equal chunks (oit_f2b_chunk_triangles), and chunk c's
 * test reads a copy of the accumulation taken after chunk c - 1 (T = 1 for
 * the first; glCopyImageSubData into a third target), never the target it
 * blends into: the same fragments are discarded on every driver. The test
 * lags by at most a chunk: a pixel blends the rest of the chunk in which
 * it fell below the threshold, then nothing. An older, higher T only
 * discards less, so the bound above holds. Why 64: the lag is then at most
 * 1/64 of the frame's triangles; each chunk costs one full-frame RGBA32F
 * copy (16 bytes a pixel read and written: about 4 GB a 1080p frame, a
 * millisecond on a current GPU, small beside the CPU sort), so many more
 * chunks cost more than the fragments they save.
 *
 * Default threshold 0.02, the value the seed measures as "roughly optimal"
 * (Table 5: 0.01 shows no visible difference, 0.05 small changes).
 * Translucent shading blends colour and Fresnel alpha but ignores
 * absorption between surfaces (it needs per-pixel state blending lacks).
 *
 * Memory: three RGBA32F targets per pixel (accumulation, its copy for the
 * test, output) and, per triangle, a sort key, its rank and the sorted copy
 * (48 bytes).
 *
 * Stats: fragments = fragments blended (GL_SAMPLES_PASSED over the chunks;
 * discarded ones are not), max_layers = 0 (not known without a count
 * pass), batches = 1 (one geometry pass, in chunks), gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_F2B_H
#define OIT_RENDER_BASELINES_F2B_H

#include "view/render/gl/gpu_mesh.h"

#define OIT_F2B_DEFAULT_THRESHOLD 0.02f
#define OIT_F2B_CHUNKS 64

typedef struct oit_f2b oit_f2b;

/* Alpha (transmittance) threshold in [0, 1); 0 discards nothing.
 * OIT_ERR_ARGUMENT outside it (NaN included). The method (methods.h)
 * starts at OIT_F2B_DEFAULT_THRESHOLD. */
oit_status oit_f2b_set_threshold(oit_f2b *f, float threshold, oit_error *err);

/* Sorted triangles in each blend chunk of a frame of tris (the last may
 * hold fewer): an OIT_F2B_CHUNKS-th share, at least 1, rounded up to keep
 * each chunk's byte offset at the current context's
 * GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT. Chunk c draws sorted
 * triangles [c * size, (c + 1) * size). */
uint64_t oit_f2b_chunk_triangles(uint64_t tris);

#endif
