/* The counted capture's resolve: each pixel of the rect u_rect with
 * fragments in the band composites its segment into its state. */
void main() {
    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_rect.z || px.y >= u_rect.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = offsets[p + 1u] - offsets[p];
    if (n == 0u) return;
    oit_state s = oit_state_load(p);
    oit_segment_composite(s, offsets[p] - band_base, n);
    s.nfrag += n;
    oit_state_store(p, s);
}
