/* Depth peeling's geometry pass (depth_peel.h), after
 * oit_glsl_fragment_gen: the nearest fragment behind the layer before.
 * The depth test does the choosing, on t scaled into [0, 1) so that it
 * keeps t's order (depth_peel.c, depth_scale). */
layout(binding = OIT_TEX_LAYER) uniform usampler2D u_prev;
uniform float u_depth_scale;
layout(location = OIT_OUT_COLOUR) out uvec4 o_frag;
void main() {
    if (oit_clipped()) discard;
    uvec4 f = oit_fragment();
    uvec2 prev = texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0).xy;
    /* Keep only fragments after the previous layer in (key, prim) order. */
    uint pf = f.y & 0x7fffffffu, pp = prev.y & 0x7fffffffu;
    if (f.x < prev.x || (f.x == prev.x && pf <= pp)) discard;
    gl_FragDepth = uintBitsToFloat(f.x) * u_depth_scale;
    o_frag = f;
}
