/* First-K's pass 1, after firstk_totals.glsl, rect_index.glsl and
 * saturated.glsl: every fragment counted, the first u_W of a pixel kept in
 * slot c * P + q of the tile u_tile (neighbouring pixels' c-th fragments
 * neighbours in memory), a pixel of more flagged for pass 2. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };
uniform int u_W;
uniform ivec4 u_tile;
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    uint q = oit_rect_index(ivec2(gl_FragCoord.xy), u_tile);
    uint P = uint((u_tile.z - u_tile.x) * (u_tile.w - u_tile.y));
    uint c = atomicAdd(counts[p], 1u);
    if (c < uint(u_W)) slots[c * P + q] = oit_fragment();
    else if (c == uint(u_W)) oit_spill(uvec2(gl_FragCoord.xy));
}
