/* DFB's resolve: each pixel's segment sorted and composited, its colour
 * over the background into out_rgba (after dfb_resolve_out.glsl) or, with
 * OIT_TO_STATE, its (C, T) state into oit_glsl_state_io's buffer, for a
 * caller that goes on compositing (liboit). */
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, u_rows.x);
    if (px.x >= u_size.x || px.y >= u_rows.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = oit_state_begin();
    oit_segment_composite(s, offsets[p] - u_base, offsets[p + 1u] - offsets[p]);
#if defined(OIT_TO_STATE)
    oit_state_store(p, s);
#else
    out_rgba[p] = oit_state_final(s);
#endif
}
