/* DFB's resolve to state: the same as dfb_resolve_main.glsl, leaving each
 * pixel's (C, T) state in oit_glsl_state_io's buffer instead of its colour
 * over the background, for a caller that goes on compositing (liboit). */
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, u_rows.x);
    if (px.x >= u_size.x || px.y >= u_rows.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = oit_state_begin();
    oit_segment_composite(s, offsets[p] - u_base, offsets[p + 1u] - offsets[p]);
    oit_state_store(p, s);
}
