/* DFB's store pass: each fragment at its pixel's offset, its slot by an
 * atomic decrement of the count. The count pass ran the same
 * rasterization, so every fragment finds its slot; the bounds check only
 * guards against a driver breaking invariance. The store holds one band
 * of rows (the scissor) from offset u_base on. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };
layout(location = OIT_LOC_BASE) uniform uint u_base;
void main() {
    if (oit_clipped()) discard;
    if (oit_behind_opaque()) discard;
    uint p = oit_pixel_index();
    uint c = atomicAdd(counts[p], 0xffffffffu);
    uint slot = offsets[p] + c - 1u;
    if (c != 0u && slot < offsets[p + 1u] && slot >= u_base) frags[slot - u_base] = oit_fragment();
}
