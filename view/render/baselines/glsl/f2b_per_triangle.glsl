/* What F2B's two per-triangle passes (f2b.h: sort keys, gather) share: a
 * triangle index a thread, counted across the frame's meshes
 * (u_mesh_base: triangles of the meshes before) within the dispatch's
 * window of the mesh. */
layout(local_size_x = 64) in;
layout(std430, binding = OIT_BIND_VERTS) readonly buffer Verts { uvec4 verts[]; };
uniform uint u_window_first, u_window_count, u_mesh_base;
uint triangle() { return gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x; }
