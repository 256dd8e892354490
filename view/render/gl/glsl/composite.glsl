/* Front-to-back compositing of packed fragments (frag_glsl.h,
 * oit_glsl_composite): shade.c's oit_pixel_* line for line. */
oit_state oit_state_begin() {
    return oit_state(vec3(0.0), 0.0, vec3(1.0), 0, vec3(0.0), 0u);
}
bool oit_frag_less(uvec4 a, uvec4 b) {
    return a.x < b.x || (a.x == b.x && (a.y & 0x7fffffffu) < (b.y & 0x7fffffffu));
}
/* One insertion-sort step: x joins the sorted f[0..i). A while loop with
 * a break, because llvmpipe miscompiles the for-loop form whose
 * condition calls oit_frag_less. */
#define OIT_SORTED_INSERT(f, i, x) { uint j_ = (i); while (j_ > 0u) { if (!oit_frag_less((x), f[j_ - 1u])) break; f[j_] = f[j_ - 1u]; j_--; } f[j_] = (x); }
vec3 oit_unpack_111110(uint w) {
    return vec3(float(w & 0x7ffu) / 2047.0, float((w >> 11) & 0x7ffu) / 2047.0,
                float(w >> 22) / 1023.0);
}
void oit_composite(inout oit_state s, uvec4 f) {
    float t = uintBitsToFloat(f.x);
    bool translucent = u_mode == 1;
    vec3 colour; float a;
    if (translucent) {
        vec2 la = unpackUnorm2x16(f.z);
        colour = vec3(la.x); a = la.y;
        if (s.nest > 0)
            s.T *= exp(-u_sigma * (vec3(1.0) - s.medium) * (t - s.t_prev));
    } else {
        vec2 rg = unpackUnorm2x16(f.z), ba = unpackUnorm2x16(f.w);
        colour = vec3(rg, ba.x); a = ba.y;
    }
    s.C += s.T * a * colour;
    s.T *= 1.0 - a;
    if (translucent) {
        if ((f.y & 0x80000000u) != 0u) { s.nest += 1; s.medium = oit_unpack_111110(f.w); }
        else s.nest = max(s.nest - 1, 0);
        s.t_prev = t;
    }
}
vec4 oit_state_final(oit_state s) {
    return vec4(oit_output(s.C + s.T * oit_background()), 1.0);
}
