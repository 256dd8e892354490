/* A predicted band's store, after counted_predicted.glsl and
 * saturated.glsl: every fragment counted, those within the pixel's
 * predicted segment stored, in one pass instead of a count and a store. */
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    uint c = atomicAdd(counts[p], 1u);
    if (oit_predicted_holds(p, c + 1u))
        frags[offsets[p] - offsets[u_band_pixel] + c] = oit_fragment();
}
