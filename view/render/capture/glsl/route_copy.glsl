/* Routing by copies (testing, capture_stencil.h), after fullscreen.glsl's
 * draw masked to sample u_sample: each pixel's sample takes the pixel's
 * slot u_sample, where the fill put the fragment that routing would have
 * put there. */
layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Routed { uvec4 routed[]; };
layout(location = OIT_OUT_COLOUR) out uvec4 o_frag;
uniform int u_sample;
uniform int u_K;
uniform int u_width;
void main() {
    uvec2 px = uvec2(gl_FragCoord.xy);
    uint p = px.y * uint(u_width) + px.x;
    if (uint(u_sample) >= min(counts[p], uint(u_K))) discard;
    o_frag = routed[p * uint(u_K) + uint(u_sample)];
}
