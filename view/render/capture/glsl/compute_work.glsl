/* The sweep's first work list, after compute_common.glsl (uvec4 header:
 * the indirect dispatch's groups in xyz, the tiles in w; then the tiles):
 * the tiles of the rect [u_tile0, u_tile1] with an entry in their list,
 * so that the sweep's groups go only where there is work. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer TileEnds { uint tile_end[]; };
layout(std430, binding = OIT_BIND_OUT) buffer Work { uvec4 work_hdr; uint work[]; };
uniform ivec2 u_tile0;
uniform ivec2 u_tile1;
void main() {
    ivec2 tile = u_tile0 + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(tile, u_tile1))) return;
    uint t = uint(tile.y) * cs_tiles_x() + uint(tile.x);
    uint lo = t == 0u ? 0u : tile_end[t - 1u];
    if (tile_end[t] > lo) work[atomicAdd(work_hdr.w, 1u)] = t;
}
