/* The stencil target's fill (capture_stencil.h), after count_flag.glsl and
 * saturated.glsl: every fragment counted exactly (the atomic count, not
 * the stencil, tells overflow: it does not saturate and needs no read of
 * the target), the fragment written to the sample the stencil routes it
 * to. OIT_FIRSTK_PASS: first-K's pass 1, whose overflowed pixels are not
 * lost (the second pass takes them), so they are not flagged.
 * OIT_ROUTE_BY_COPY (testing, capture_stencil.h): the fragment goes to
 * slot c of its pixel in a buffer, copied into sample c after the draw,
 * as routing would have put it. */
#ifdef OIT_ROUTE_BY_COPY
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Routed { uvec4 routed[]; };
#else
layout(location = OIT_OUT_COLOUR) out uvec4 o_frag;
#endif
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    uint c = atomicAdd(counts[p], 1u);
#ifndef OIT_FIRSTK_PASS
    if (c == uint(u_K)) atomicAdd(overflow, 1u);
#endif
#ifdef OIT_ROUTE_BY_COPY
    if (c < uint(u_K)) routed[oit_pixel_index() * uint(u_K) + c] = oit_fragment();
#else
    o_frag = oit_fragment();
#endif
}
