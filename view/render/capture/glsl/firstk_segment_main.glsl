/* Pass 2's resolve: each pixel of its rect with a segment composites the
 * segment into its state. */
void main() {
    ivec4 b = oit_pass2_rect();
    ivec2 px = b.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= b.z || px.y >= b.w) return;
    uvec2 e = table[oit_rect_index(px, u_rect)];
    if (e.y == 0u) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = oit_state_load(p);
    oit_segment_composite(s, e.x, e.y);
    s.nfrag += e.y;
    oit_state_store(p, s);
}
