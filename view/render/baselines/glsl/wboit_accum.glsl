/* WBOIT's accumulation (wboit.h), after oit_glsl_fragment_gen and
 * premultiplied.glsl: weighted colour into the first target, revealage
 * into the second, blended per draw buffer (wboit.c). */
layout(location = OIT_OUT_COLOUR) out vec4 o_accum;
layout(location = OIT_OUT_SECOND) out float o_reveal;
float oit_weight(float t, float a) {
    return a * clamp(10.0 / (1e-5 + pow(t / 5.0, 2.0) + pow(t / 200.0, 6.0)), 1e-2, 3e3);
}
void main() {
    if (oit_clipped()) discard;
    uvec4 f = oit_fragment();
    vec4 c = oit_premultiplied(f);
    o_accum = c * oit_weight(uintBitsToFloat(f.x), c.a);
    o_reveal = c.a;
}
