/* liboit's blend of a frame's state into the caller's framebuffer
 * (blend_into.h), after oit_glsl_composite and oit_glsl_state_io: one
 * fragment a pixel over the target's rect at u_origin, dst = C + T * dst
 * through dual-source blending, so that the caller's colour is never read
 * back and the blend unit does the compositing in the target's format. */
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_ORIGIN) uniform ivec2 u_origin;
layout(location = OIT_OUT_COLOUR, index = 0) out vec4 o_colour;
layout(location = OIT_OUT_COLOUR, index = 1) out vec4 o_transmit;
void main() {
    ivec2 px = ivec2(gl_FragCoord.xy) - u_origin;
    oit_state s = oit_state_load(uint(px.y * u_size.x + px.x));
    /* Transparent T is one number: the mean of three copies rounds away
     * from it (oitstream-mpi's shares blend this alpha, bit for bit the
     * state's 1 - T as the tool read it before it drew through liboit). */
    float t = u_mode != 1 ? s.T.r : (s.T.r + s.T.g + s.T.b) / 3.0;
    o_colour = vec4(s.C, 1.0 - t);
    o_transmit = vec4(s.T, t);
}
