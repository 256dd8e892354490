/* WBOIT's resolve (wboit.h), after to_texture.glsl, srgb.glsl and
 * output.glsl: the weighted average over the background by the
 * revealage. */
layout(binding = OIT_TEX_ACCUM) uniform sampler2D u_accum;
layout(binding = OIT_TEX_REVEAL) uniform sampler2D u_reveal;
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    vec4 acc = texelFetch(u_accum, px, 0);
    float r = texelFetch(u_reveal, px, 0).r;
    vec3 c = acc.rgb / max(acc.a, 1e-5);
    imageStore(u_out, px, vec4(oit_output(c * (1.0 - r) + oit_background() * r), 1.0));
}
