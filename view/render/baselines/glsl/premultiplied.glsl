/* A packed fragment's premultiplied (a * colour, a) (baseline_common.h):
 * the terms oit_composite (view/render/gl/glsl/composite.glsl) adds for one
 * fragment on a clear state, decoded the same way, for the methods that
 * blend fragments without compositing them in order. After
 * oit_glsl_fragment_gen or oit_glsl_composite (u_mode). */
vec4 oit_premultiplied(uvec4 f) {
    if (u_mode == 1) {
        vec2 la = unpackUnorm2x16(f.z);
        return vec4(vec3(la.x * la.y), la.y);
    }
    vec2 rg = unpackUnorm2x16(f.z), ba = unpackUnorm2x16(f.w);
    return vec4(vec3(rg, ba.x) * ba.y, ba.y);
}
