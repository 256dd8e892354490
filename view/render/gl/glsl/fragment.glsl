/* The packed fragment (frag_glsl.h, "A fragment is packed"), after
 * fragment_key.glsl and opaque.glsl. */
uvec4 oit_fragment() {
    vec3 rel = v_pos - oit_ray_origin();
    float t_interp = length(rel);
    vec3 v = -rel / t_interp;
    /* Degenerate triangles shade as edge-on, like shade.c. */
    float nn = dot(v_normal, v_normal);
    float nv = nn > 0.0 ? dot(v_normal * inversesqrt(nn), v) : 0.0;
    float ndv = abs(nv);
    float light = 0.3 + 0.7 * ndv;
    vec3 base = (u_attrs & 1u) != 0u ? v_rgba.rgb : u_default_rgb;
    float a = v_opaque != 0u ? 1.0 : (u_attrs & 2u) != 0u ? v_rgba.a : u_alpha;
    uint prim = (v_first_prim & 0x80000000u) != 0u ? v_first_prim
                                                   : v_first_prim + uint(OIT_PRIMITIVE_ID);
    uvec4 f;
    f.x = oit_fragment_key();
    f.y = (prim & 0x7fffffffu) | (nv > 0.0 ? 0x80000000u : 0u);
    if (u_mode == 1) {
        float fresnel = 0.04 + 0.96 * pow(1.0 - ndv, 5.0);
        f.z = packUnorm2x16(vec2(light, fresnel));
        f.w = oit_pack_111110(base);
    } else {
        vec3 c = base * light;
        f.z = packUnorm2x16(c.rg);
        f.w = packUnorm2x16(vec2(c.b, a));
    }
    return f;
}
