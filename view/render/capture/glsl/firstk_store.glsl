/* Pass 2's store, after firstk_totals.glsl, rect_index.glsl and
 * saturated.glsl: only pixels with a segment, counted back down to 0. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Table { uvec2 table[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };
uniform ivec4 u_tile;
void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec4 b = oit_box();
    /* the table holds only the box's pixels */
    if (px.x < b.x || px.y < b.y || px.x >= b.z || px.y >= b.w) discard;
    if (oit_clipped()) discard;
    if (oit_behind_opaque()) discard;
    uvec2 e = table[oit_rect_index(px, u_tile)];
    uint p = oit_pixel_index();
    if (e.y == 0u || oit_saturated(p)) discard;
    uint c = atomicAdd(counts[p], 0xffffffffu);
    if (c != 0u && c <= e.y) frags[e.x + c - 1u] = oit_fragment();
}
