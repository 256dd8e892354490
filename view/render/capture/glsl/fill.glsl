/* The slot fill's main: OIT_FILL_SLOTS (a GLSL int, fill_array.glsl or
 * fill_wide.glsl) slots a pixel of the tile u_tile (GL rows, exclusive
 * ends), the first ones of a pixel kept and the pixel flagged once when
 * more come, so that the frame knows it lost fragments. */
uniform ivec4 u_tile;
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    ivec2 px = ivec2(gl_FragCoord.xy) - u_tile.xy;
    uint q = uint(px.y * (u_tile.z - u_tile.x) + px.x);
    uint c = atomicAdd(counts[p], 1u);
    if (c < uint(OIT_FILL_SLOTS)) slots[q * uint(OIT_FILL_SLOTS) + c] = oit_fragment();
    else if (c == uint(OIT_FILL_SLOTS)) atomicAdd(overflow, 1u);
}
