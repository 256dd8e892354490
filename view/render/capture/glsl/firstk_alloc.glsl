/* Pass 2's allocation over its rect, after firstk_totals.glsl,
 * rect_index.glsl and firstk_pass2.glsl: each overflowed pixel a segment
 * of its count in the store (the order of segments does not matter, only
 * that they do not overlap). */
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_OFFSETS) writeonly buffer Table { uvec2 table[]; };
uniform int u_W;
/* fragments the store holds */
uniform uint u_cap;
void main() {
    ivec4 b = oit_pass2_rect();
    ivec2 px = b.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= b.z || px.y >= b.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = counts[p];
    uvec2 e = uvec2(0u);
    if (n > uint(u_W)) {
        uint old = atomicAdd(spill_lo, n);
        if (old + n < old) atomicAdd(spill_hi, 1u);
        e = uvec2(old, n);
        /* past the store: left out, the frame flagged short (the verdict) */
        if (old + n < old || old + n > u_cap) { e = uvec2(0u); counts[p] = 0u; }
    }
    table[oit_rect_index(px, u_rect)] = e;
}
