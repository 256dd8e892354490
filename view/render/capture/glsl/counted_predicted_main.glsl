/* A predicted band's resolve: every pixel's count kept for the next
 * frame's prediction; a pixel the prediction held composited and its
 * count back to 0; one it did not keeps its count for the band's spill
 * pass. */
void main() {
    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_rect.z || px.y >= u_rect.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = counts[p];
    next_counts[p] = n;
    if (n == 0u || !oit_predicted_holds(p, n)) return;
    oit_state s = oit_state_load(p);
    oit_segment_composite(s, offsets[p] - offsets[u_band_pixel], n);
    s.nfrag += n;
    oit_state_store(p, s);
    counts[p] = 0u;
}
