/* The compute capture's triangle set-up, after oit_glsl_vertex_lib (the
 * vertex stage's transform and tie plane, so that the set-up gives what
 * the raster captures' vertex stage would), compute_common.glsl and
 * compute_recs_write.glsl: each triangle of the window into its record,
 * and its count in every tile its box touches (tiles of dead pixels left
 * out where u_live). */
layout(local_size_x = 64) in;
layout(std430, binding = OIT_BIND_OFFSETS) buffer TileCounts { uint tile_count[]; };
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer TileDead { uint tile_dead[]; };
uniform uint u_window_first;
uniform uint u_window_count;
uniform uint u_rec_base;
uniform uint u_first_prim;
uniform uint u_sourced;
uniform uint u_prim_word0;
uniform int u_live;
/* Written out and precise, so that the edge a triangle shares with its
 * neighbour is the exact negation of the neighbour's (each component
 * is the same two products subtracted the other way round); in double
 * from the float clip coordinates, where each product is exact, so
 * that the edges and the sign of det (the orientation) stay right for
 * slivers and tiny triangles. */
dvec3 cs_cross(dvec3 a, dvec3 b) {
    precise dvec3 c;
    c.x = a.y * b.z - a.z * b.y;
    c.y = a.z * b.x - a.x * b.z;
    c.z = a.x * b.y - a.y * b.x;
    return c;
}
/* Entirely outside one plane of the clip volume (GL clips x, y and z
 * to [-w, w]); also a triangle with a coordinate that is not a number. */
bool cs_culled(vec4 c[3]) {
    bvec4 all_lo = bvec4(true), all_hi = bvec4(true);
    for (int k = 0; k < 3; k++) {
        if (any(isnan(c[k])) || any(isinf(c[k]))) return true;
        all_lo = bvec4(all_lo.x && c[k].x < -c[k].w, all_lo.y && c[k].y < -c[k].w,
                       all_lo.z && c[k].z < -c[k].w, all_lo.w && c[k].w <= 0.0);
        all_hi = bvec4(all_hi.x && c[k].x > c[k].w, all_hi.y && c[k].y > c[k].w,
                       all_hi.z && c[k].z > c[k].w, false);
    }
    return any(all_lo) || any(all_hi);
}
/* The pixels whose centres it may cover, within the batch's rect: the
 * projected vertices' box and a pixel of margin, or the whole rect
 * when a vertex lies behind the eye (w <= 0 projects nowhere useful;
 * the coverage test itself handles it). */
ivec4 cs_box(vec4 c[3]) {
    vec4 r = vec4(u_rect);
    if (c[0].w <= 0.0 || c[1].w <= 0.0 || c[2].w <= 0.0) return u_rect;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    for (int k = 0; k < 3; k++) {
        vec2 win = (c[k].xy / c[k].w + 1.0) * 0.5 * vec2(u_size);
        lo = min(lo, win); hi = max(hi, win);
    }
    lo = clamp(floor(lo - 0.5) - 1.0, r.xy, r.zw);
    hi = clamp(ceil(hi - 0.5) + 2.0, r.xy, r.zw);
    return ivec4(lo, hi);
}
void main() {
    uint i = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
    if (i >= u_window_count) return;
    uint v0 = i * 3u;
    uvec4 va[3] = uvec4[3](verts[v0], verts[v0 + 1u], verts[v0 + 2u]);
    vec3 wp[3]; vec3 vp[3]; vec4 cl[3];
    /* The vertex stage's transform (oit_glsl_vertex), one vertex at a time
     * through the same code, precise, so that a vertex shared by two
     * triangles lands on the same bits in both. */
    for (int k = 0; k < 3; k++) {
        wp[k] = oit_world(va[k]);
        precise vec4 q = u_view * vec4(wp[k], 1.0);
        precise vec4 c = u_proj * q;
        vp[k] = q.xyz; cl[k] = c;
    }
    uint prim = (u_sourced != 0u ? prims[u_prim_word0 + i] : u_first_prim + u_window_first + i)
                & 0x7fffffffu;
    bool opaque = u_mode == 0 && (u_attrs & 2u) != 0u &&
                  (va[0].w & va[1].w & va[2].w) >> 24 == 255u;
    vec3 nrm = mat3(u_view) * cross(wp[1] - wp[0], wp[2] - wp[0]);
    vec4 plane = oit_tie_plane(wp[0], wp[1], wp[2]);
    /* Homogeneous rasterization (Olano and Greer 1997): e_i . (x, y, 1) in
     * NDC is det * the barycentric lambda_i of the pixel's ray, so the
     * ray meets the triangle in front of the eye exactly where every e_i
     * times sign(det) is >= 0; no clipping against the eye plane. */
    dvec3 h0 = dvec3(cl[0].xyw), h1 = dvec3(cl[1].xyw), h2 = dvec3(cl[2].xyw);
    dvec3 d0 = cs_cross(h1, h2), d1 = cs_cross(h2, h0), d2 = cs_cross(h0, h1);
    precise double det = h0.x * d0.x + h0.y * d0.y + h0.z * d0.z;
    ivec4 box = ivec4(0);
    if (det != 0.0lf && !cs_culled(cl)) box = cs_box(cl);
    double sg = det > 0.0lf ? 1.0lf : -1.0lf;
    vec3 e0 = vec3(d0 * sg), e1 = vec3(d1 * sg), e2 = vec3(d2 * sg);
    uint b = u_rec_base + i;
    cs_put(b, 0u, uvec4(floatBitsToUint(e0), prim | (opaque ? 0x80000000u : 0u)));
    cs_put(b, 1u, uvec4(floatBitsToUint(e1), va[0].w));
    cs_put(b, 2u, uvec4(floatBitsToUint(e2), va[1].w));
    cs_put(b, 3u, uvec4(floatBitsToUint(vec3(cl[0].z, cl[1].z, cl[2].z)), va[2].w));
    cs_put(b, 4u, uvec4(floatBitsToUint(vec3(cl[0].w, cl[1].w, cl[2].w)), 0u));
    for (int k = 0; k < 3; k++)
        cs_put(b, 5u + uint(k), uvec4(floatBitsToUint(vp[k]), floatBitsToUint(nrm[k])));
    cs_put(b, 8u, floatBitsToUint(plane));
    cs_put(b, 9u, uvec4(box));
    if (box.x >= box.z || box.y >= box.w) return;
    uint tx = cs_tiles_x();
    for (int ty = box.y / CS_TILE; ty <= (box.w - 1) / CS_TILE; ty++)
        for (int tc = box.x / CS_TILE; tc <= (box.z - 1) / CS_TILE; tc++) {
            uint t = uint(ty) * tx + uint(tc);
            if (u_live == 0 || tile_dead[t] == 0u) atomicAdd(tile_count[t], 1u);
        }
}
