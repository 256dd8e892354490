/* Pass 1's resolve, after rect_index.glsl: pixels of at most u_W
 * fragments, from their slots, sorted in registers and composited into
 * their state, their count back to 0 for the next pack. An overflowed
 * pixel keeps its count: pass 2 takes it whole. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
uniform int u_W;
void main() {
    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_rect.z || px.y >= u_rect.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = counts[p];
    if (n == 0u || n > uint(u_W)) return;
    uint q = oit_rect_index(px, u_rect);
    uint P = uint((u_rect.z - u_rect.x) * (u_rect.w - u_rect.y));
    uvec4 f[16];
    for (uint i = 0u; i < n; i++) {
        uvec4 x = slots[i * P + q];
        OIT_SORTED_INSERT(f, i, x)
    }
    oit_state s = oit_state_load(p);
    for (uint i = 0u; i < n; i++) oit_composite(s, f[i]);
    s.nfrag += n;
    oit_state_store(p, s);
    counts[p] = 0u;
}
