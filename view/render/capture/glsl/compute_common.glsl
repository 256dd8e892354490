/* What the compute capture's stages share (compute_glsl.c gives them
 * CS_TILE, the tile side, and CS_REC, the uvec4s of a triangle's record):
 * the frame's size, the batch's rect, and the tiles a row. A record,
 * indexed by the triangle's place in the batch:
 *   r0 = e0.xyz, prim | opaque << 31   e_i: edge i's homogeneous line,
 *   r1 = e1.xyz, rgba0                      oriented so that the inside is
 *   r2 = e2.xyz, rgba1                      positive (compute_setup.glsl)
 *   r3 = clip z0, z1, z2, rgba2
 *   r4 = clip w0, w1, w2, 0
 *   r5..r7 = view-space vertex k, normal[k]
 *   r8 = the tie rule's plane (v_plane)
 *   r9 = the pixel box (x0, y0, x1, y1), GL rows, exclusive ends; empty
 *        when x0 >= x1 (culled) */
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
uint cs_tiles_x() { return uint(u_size.x + CS_TILE - 1) / uint(CS_TILE); }
