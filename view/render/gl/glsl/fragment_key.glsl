/* The fragment library's ray, key and section planes (frag_glsl.h) over
 * OIT_FRAG_COORD and OIT_PRIMITIVE_ID, which the fragment stage defines as
 * gl_FragCoord and gl_PrimitiveID and the compute capture as its own
 * per-pixel values. */
layout(location = OIT_LOC_RAY) uniform vec4 u_ray;
layout(location = OIT_LOC_ORIGIN_MAP) uniform vec4 u_org;
layout(location = OIT_LOC_ORIGIN_Z) uniform float u_org_z;
/* The view-space origin of the pixel centre's ray (view.h,
 * oit_view_origin_map): the eye, 0, for a perspective; the point of the
 * near plane for an orthographic view. */
vec3 oit_ray_origin() {
    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;
    precise vec3 o = vec3(c.x * u_org.x + u_org.z, c.y * u_org.y + u_org.w, u_org_z);
    return o;
}
uint oit_pixel_index() {
    return uint(OIT_FRAG_COORD.y) * uint(u_width) + uint(OIT_FRAG_COORD.x);
}
uint oit_pack_111110(vec3 c) {
    uvec3 q = uvec3(round(clamp(c, 0.0, 1.0) * vec3(2047.0, 2047.0, 1023.0)));
    return q.x | (q.y << 11) | (q.z << 22);
}
/* The tie rule's key (shade.h, oit_depth_key): t of the triangle's
 * plane along the pixel centre's unit ray from its origin o, which every
 * triangle at this pixel shares, with the low mantissa bits cleared:
 * (d - n . o) / (n . dir), d - 0 = d for a perspective (o = 0); an
 * orthographic ray map is 0, so dir = (0, 0, -1). */
/* floor + 0.5: the centre even where a multisampled target lets
 * OIT_FRAG_COORD lie anywhere in the pixel. */
/* Every operation is written out in the order view.c
 * (oit_view_pixel_ray) and shade.c (oit_depth_key) use, and precise:
 * a GPU compiler may otherwise fuse multiply-adds or reassociate
 * (GLSL 4.50 4.7.1), so that faces coplanar up to rounding get keys on
 * either side of a grid line than the CPU reference's. Division and
 * sqrt stay within GLSL's stated ulps of the CPU's. */
uint oit_depth_key(float t_interp) {
    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;
    precise vec3 dir = vec3(c.x * u_ray.x + u_ray.z, c.y * u_ray.y + u_ray.w, -1.0);
    precise float len2 = dir.x * dir.x + dir.y * dir.y + dir.z * dir.z;
    precise float inv = 1.0 / sqrt(len2);
    dir = dir * inv;
    vec3 n = v_plane.xyz;
    precise float nd = n.x * dir.x + n.y * dir.y + n.z * dir.z;
    float t = t_interp;
    if (abs(nd) >= OIT_DEPTH_GRAZING) {
        vec3 o = oit_ray_origin();
        precise float no = n.x * o.x + n.y * o.y + n.z * o.z;
        precise float tp = (v_plane.w - no) / nd;
        if (tp > 0.0 && !isinf(tp)) t = tp;
    }
    return floatBitsToUint(t) & ~uint(OIT_DEPTH_KEY_MASK);
}
/* Section planes (clip.h): u_clip holds them in view space
 * (oit_clip_eye). The point tested is where the pixel centre's ray
 * meets the triangle's plane, computed as oit_depth_key computes its t
 * and as reference.c does, not the interpolated position, which a
 * multisampled capture may take anywhere in the pixel; a grazing
 * plane falls back to the interpolated distance along the same ray. */
layout(location = OIT_LOC_CLIP_COUNT) uniform int u_clip_count;
layout(location = OIT_LOC_CLIP) uniform vec4 u_clip[OIT_CLIP_MAX];
bool oit_clipped() {
    if (u_clip_count == 0) return false;
    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;
    precise vec3 dir = vec3(c.x * u_ray.x + u_ray.z, c.y * u_ray.y + u_ray.w, -1.0);
    precise float len2 = dir.x * dir.x + dir.y * dir.y + dir.z * dir.z;
    precise float inv = 1.0 / sqrt(len2);
    dir = dir * inv;
    vec3 o = oit_ray_origin();
    vec3 n = v_plane.xyz;
    precise float nd = n.x * dir.x + n.y * dir.y + n.z * dir.z;
    float t = length(v_pos - o);
    if (abs(nd) >= OIT_DEPTH_GRAZING) {
        precise float no = n.x * o.x + n.y * o.y + n.z * o.z;
        precise float tp = (v_plane.w - no) / nd;
        if (tp > 0.0 && !isinf(tp)) t = tp;
    }
    precise vec3 p = o + dir * t;
    for (int i = 0; i < u_clip_count; i++) {
        vec4 q = u_clip[i];
        precise float s = q.x * p.x + q.y * p.y + q.z * p.z + q.w;
        if (s < 0.0) return true;
    }
    return false;
}
/* One expression for the key, so that the opaque pre-pass and the
 * captures compute the same bits. */
uint oit_fragment_key() {
    precise vec3 rel = v_pos - oit_ray_origin();
    precise float t_interp = length(rel);
    return oit_depth_key(t_interp);
}
