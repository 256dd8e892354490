/* DFB's resolve to colours: each pixel's segment sorted and composited,
 * its colour over the background into out_rgba. */
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, u_rows.x);
    if (px.x >= u_size.x || px.y >= u_rows.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = oit_state_begin();
    oit_segment_composite(s, offsets[p] - u_base, offsets[p + 1u] - offsets[p]);
    out_rgba[p] = oit_state_final(s);
}
