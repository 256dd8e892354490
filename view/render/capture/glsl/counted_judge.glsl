/* The counted capture's judge of a band of a batch's rows, one invocation
 * after the scan: whether the store holds its fragments (the store pass
 * and the resolve run only then, through the gate and the groups), where
 * they start, and the frame's figures, all on the GPU so that the host
 * need not read the scan back. The scan's totals: the fragments (lo, hi),
 * the largest count, the counts over K (added once a batch, at its first
 * band). Offsets follow the frame's rows, so a band's fragments are the
 * difference of the offsets at its first pixels. The words' order is
 * capture_counted.c's J_* and counted_band.glsl's. */
layout(local_size_x = 1) in;
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Scan { uint lo; uint hi; uint most; uint over; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = OIT_BIND_SUMS) buffer Judge { uint gate; uint frame_short; uint deep; uint pad; uvec4 groups; uint base; uint cap; };
uniform uint u_cap;
uniform uint u_width;
uniform uvec2 u_rows;
uniform uvec2 u_groups;
uniform uint u_first;
void main() {
    uint start = offsets[u_rows.x * u_width];
    uint n = offsets[u_rows.y * u_width] - start;
    bool fits = hi == 0u && n <= u_cap;
    gate = fits && n != 0u ? 1u : 0u;
    if (!fits) frame_short = 1u;
    if (u_first != 0u) deep += over;
    groups = uvec4(gate != 0u ? u_groups : uvec2(0u), 1u, 0u);
    base = start;
    cap = u_cap;
}
