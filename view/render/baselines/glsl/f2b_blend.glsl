/* F2B's blend pass (f2b.h), after oit_glsl_fragment_gen and
 * premultiplied.glsl: Vlcek et al.'s shader, the test before any shading
 * work. It reads u_seen, the accumulation the chunks before left, never
 * the target it blends into (f2b.h, "Chunks"). */
layout(binding = OIT_TEX_ACCUM) uniform sampler2D u_seen;
uniform float u_threshold;
layout(location = OIT_OUT_COLOUR) out vec4 o_colour;
void main() {
    if (oit_clipped()) discard;
    if (texelFetch(u_seen, ivec2(gl_FragCoord.xy), 0).a < u_threshold) discard;
    vec4 c = oit_premultiplied(oit_fragment());
    o_colour = vec4(c.rgb, 1.0 - c.a);
}
