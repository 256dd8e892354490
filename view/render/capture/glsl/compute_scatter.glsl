/* The compute capture's scatter, after compute_common.glsl and
 * compute_recs_read.glsl: each record's index into the lists of its tiles.
 * After the scan, tile_count holds each tile's first entry; taking one
 * with an atomic leaves it at the tile's end, the next tile's start. The
 * order within a tile is whatever the atomics give: the sweep orders.
 * The list holds u_list_cap entries, sized by the host without reading
 * the scan's total back: an entry past it is not written (the sweep
 * finds the tile's triangles among all records instead) and the entries
 * the batch needed go to late_need, which the host reads after the frame
 * to size the next frame's lists. */
layout(local_size_x = 64) in;
layout(std430, binding = OIT_BIND_OFFSETS) buffer TileCounts { uint tile_count[]; };
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer TileDead { uint tile_dead[]; };
layout(std430, binding = OIT_BIND_SUMS) writeonly buffer TileList { uint tile_list[]; };
layout(std430, binding = OIT_BIND_COUNTS) buffer Late { uint late_need; };
layout(location = OIT_LOC_COUNT) uniform uint u_count;
uniform uint u_list_cap;
uniform int u_live;
void main() {
    uint i = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    ivec4 box = ivec4(cs_rec(i, 9u));
    if (box.x >= box.z || box.y >= box.w) return;
    uint tx = cs_tiles_x();
    for (int ty = box.y / CS_TILE; ty <= (box.w - 1) / CS_TILE; ty++)
        for (int tc = box.x / CS_TILE; tc <= (box.z - 1) / CS_TILE; tc++) {
            uint t = uint(ty) * tx + uint(tc);
            if (u_live != 0 && tile_dead[t] != 0u) continue;
            uint at = atomicAdd(tile_count[t], 1u);
            if (at < u_list_cap) tile_list[at] = i;
            else atomicMax(late_need, at + 1u);
        }
}
