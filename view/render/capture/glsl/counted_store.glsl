/* The counted capture's store, after counted_band.glsl and saturated.glsl:
 * the count pass's fragments at their pixel's offsets, each pixel counted
 * back down to 0. The store checks the band's capacity itself, so that a
 * band the judge closed stays within the store where the draws could not
 * be gated. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    /* a pixel without a segment keeps its count (a predicted batch's
     * spill pass: one the prediction held is at 0 already) */
    if (offsets[p + 1u] == offsets[p]) discard;
    uint c = atomicAdd(counts[p], 0xffffffffu);
    uint slot = offsets[p] - band_base + c - 1u;
    if (c != 0u && slot < offsets[p + 1u] - band_base && slot < band_cap)
        frags[slot] = oit_fragment();
}
