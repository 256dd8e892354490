/* B3D's count pass (b3d.h), after oit_glsl_fragment_gen: the fragments of
 * each pixel, so that the slot array is made as deep as the deepest pixel
 * needs before anything is stored. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
void main() { if (oit_clipped()) discard; atomicAdd(counts[oit_pixel_index()], 1u); }
