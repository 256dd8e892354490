/* B3D's store pass (b3d.h), after oit_glsl_fragment_gen. Counts start
 * again from 0, so after this pass they hold the pixel's fragment count
 * once more, for the walk. The bound only guards against a driver
 * rasterizing the two passes differently. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(rgba32ui, binding = OIT_IMG_SLOTS) writeonly uniform uimage2DArray u_slots;
layout(location = OIT_LOC_K) uniform int u_k;
void main() {
    if (oit_clipped()) discard;
    uint s = atomicAdd(counts[oit_pixel_index()], 1u);
    if (s < uint(u_k)) imageStore(u_slots, ivec3(ivec2(gl_FragCoord.xy), s), oit_fragment());
}
