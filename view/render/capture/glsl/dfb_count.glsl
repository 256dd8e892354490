/* DFB's count pass: each pixel's fragments, so that the scan of the
 * counts gives each pixel its segment of the store. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
void main() {
    if (oit_clipped()) discard;
    if (oit_behind_opaque()) discard;
    atomicAdd(counts[oit_pixel_index()], 1u);
}
