/* F2B's final pass (f2b.h), after to_texture.glsl, srgb.glsl and
 * output.glsl: the accumulation over the background. */
layout(binding = OIT_TEX_ACCUM) uniform sampler2D u_accum;
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    vec4 a = texelFetch(u_accum, px, 0);
    imageStore(u_out, px, vec4(oit_output(a.rgb + a.a * oit_background()), 1.0));
}
