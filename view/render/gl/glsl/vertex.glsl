/* The vertex-pulling vertex stage (frag_glsl.h), after vertex_lib.glsl,
 * srgb.glsl and tie_plane.glsl. */
layout(location = OIT_IN_DRAW) in uvec2 a_draw;
out vec3 v_pos;
/* The opaque pre-pass and the captures are different programs that
 * must compute the same key from it (oit_fragment_key). */
invariant v_pos;
out vec4 v_rgba;
flat out vec3 v_normal;
flat out uint v_first_prim;
flat out vec4 v_plane;
/* Opaque triangle (shade.h, "Opaque triangles"): every vertex reads
 * all three alphas, so the flat value is the same whichever provokes. */
flat out uint v_opaque;
invariant gl_Position;
/* Whether the triangle's three vertices and its prim lie in their
 * bindings. A draw's own vertices always do; the test keeps a wrong
 * record or binding from reading out of range, which GL leaves
 * undefined (robust drivers return 0: a collapsed triangle). Every
 * vertex of a triangle computes the same answer. */
bool oit_in_range(uint vid, uint v0, uint prim_word, bool sourced) {
    uint nv = uint(verts.length());
    return vid >= a_draw.x && v0 + 2u < nv &&
           (!sourced || prim_word < uint(prims.length()));
}
void main() {
    /* The draw's triangles start at vertex a_draw.x of the binding. */
    uint vid = uint(gl_VertexID);
    uint tri = (vid - a_draw.x) / 3u;
    uint v0 = a_draw.x + tri * 3u;
    bool sourced = (a_draw.y & 0x80000000u) != 0u;
    uint prim_word = (a_draw.y & 0x7fffffffu) + tri;
    if (!oit_in_range(vid, v0, prim_word, sourced)) {
        /* Outside the clip volume: the triangle is dropped whole. */
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_pos = vec3(0.0); v_rgba = vec4(0.0); v_normal = vec3(0.0);
        v_first_prim = 0u; v_plane = vec4(0.0); v_opaque = 0u;
        return;
    }
    vec3 p0 = oit_world(verts[v0]);
    vec3 p1 = oit_world(verts[v0 + 1u]);
    vec3 p2 = oit_world(verts[v0 + 2u]);
    uvec4 me = verts[vid];
    /* Geometric normal in world space, then rotated: dot products with
     * view-space vectors equal the world-space ones of shade.h. */
    v_normal = mat3(u_view) * cross(p1 - p0, p2 - p0);
    v_first_prim = sourced ? prims[prim_word] | 0x80000000u : a_draw.y;
    v_plane = oit_tie_plane(p0, p1, p2);
    v_opaque = u_mode == 0 && (u_attrs & 2u) != 0u &&
               (verts[v0].w & verts[v0 + 1u].w & verts[v0 + 2u].w) >> 24 == 255u ? 1u : 0u;
    vec4 vp = u_view * vec4(oit_world(me), 1.0);
    v_pos = vp.xyz;
    v_rgba = unpackUnorm4x8(me.w);
    if (u_colour_space == 1) v_rgba.rgb = oit_srgb_decode(v_rgba.rgb);
    gl_Position = u_proj * vp;
}
