/* A segment of fragments composited front to back (frag_glsl.h,
 * oit_glsl_segment_composite); OIT_SEGMENT_LOCAL comes with the prologue. */
void oit_segment_sift(uint b, uint root, uint n) {
    for (;;) {
        uint child = 2u * root + 1u;
        if (child >= n) return;
        if (child + 1u < n && oit_frag_less(frags[b + child], frags[b + child + 1u])) child++;
        if (!oit_frag_less(frags[b + root], frags[b + child])) return;
        uvec4 tmp = frags[b + root]; frags[b + root] = frags[b + child]; frags[b + child] = tmp;
        root = child;
    }
}
void oit_segment_composite(inout oit_state s, uint b, uint n) {
    if (n <= OIT_SEGMENT_LOCAL) {
        uvec4 f[OIT_SEGMENT_LOCAL];
        for (uint i = 0u; i < n; i++) {
            uvec4 x = frags[b + i];
            OIT_SORTED_INSERT(f, i, x)
        }
        for (uint i = 0u; i < n; i++) oit_composite(s, f[i]);
        return;
    }
    for (uint i = n / 2u; i > 0u; i--) oit_segment_sift(b, i - 1u, n);
    for (uint e = n - 1u; e > 0u; e--) {
        uvec4 tmp = frags[b]; frags[b] = frags[b + e]; frags[b + e] = tmp;
        oit_segment_sift(b, 0u, e);
    }
    for (uint i = 0u; i < n; i++) oit_composite(s, frags[b + i]);
}
