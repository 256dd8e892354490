/* F2B's gather (f2b.h), after f2b_per_triangle.glsl: the triangles in
 * their ranks' order, one window of the sorted copy per dispatch
 * (u_out_first..+u_out_count). */
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Rank { uint rank[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Sorted { uvec4 sorted[]; };
uniform uint u_out_first, u_out_count;
void main() {
    uint i = triangle();
    if (i >= u_window_count) return;
    uint r = rank[u_mesh_base + u_window_first + i] - u_out_first;
    if (r >= u_out_count) return;
    for (uint k = 0u; k < 3u; k++) sorted[3u * r + k] = verts[3u * i + k];
}
