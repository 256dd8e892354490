/* The slot captures' resolve over the batch rect u_rect: each pixel's
 * fragments sorted in registers and composited into the state the frame
 * carries, its count back to 0. After count_flag.glsl: OIT_STENCIL, the
 * fragments are the routed samples; OIT_WIDE N, a wide tile of u_W slots
 * a pixel (u_rect is the tile, N >= u_W); else K slots a pixel of the
 * rect. OIT_FIRSTK: first-K's pass 1, pixels of at most u_W fragments, an
 * overflowed one left to pass 2 with its count: after rect_index.glsl,
 * from the slots (slot i of the rect's pixel q at i * P + q, P the rect's
 * pixels); with OIT_STENCIL, after firstk_totals.glsl, from the samples,
 * where a pixel of more is found by its exact count and flagged here (the
 * routed fill cannot: it does not know a pixel's last fragment), into the
 * same spill totals and box the array fill writes. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
#if defined(OIT_FIRSTK)
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
uniform int u_W;
#define SLOTS uint(u_W)
#define LIST 16
#endif
#if defined(OIT_STENCIL)
layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;
#define LOAD(px, p, i) texelFetch(u_samples, px, int(i))
#elif defined(OIT_FIRSTK)
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
#define LOAD(px, p, i) slots[(i) * uint((u_rect.z - u_rect.x) * (u_rect.w - u_rect.y)) + oit_rect_index(px, u_rect)]
#elif defined(OIT_WIDE)
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
uniform int u_W;
#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_W) + i]
#define SLOTS uint(u_W)
#define LIST OIT_WIDE
#else
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_K) + i]
#endif
#if !defined(SLOTS)
#define SLOTS uint(u_K)
#define LIST 16
#endif
void main() {
    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_rect.z || px.y >= u_rect.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = counts[p];
    /* most pixels of a pack's rectangle get nothing: leave their state */
    if (n == 0u) return;
#if defined(OIT_FIRSTK) && defined(OIT_STENCIL)
    if (n > SLOTS) {
        oit_spill(uvec2(px));
        return;
    }
#elif defined(OIT_FIRSTK)
    if (n > SLOTS) return;
#endif
    uint m = min(n, SLOTS);
    uvec4 f[LIST];
    for (uint i = 0u; i < m; i++) {
        uvec4 x = LOAD(px, p, i);
        OIT_SORTED_INSERT(f, i, x)
    }
    oit_state s = oit_state_load(p);
    for (uint i = 0u; i < m; i++) oit_composite(s, f[i]);
    s.nfrag += n;
    oit_state_store(p, s);
    counts[p] = 0u;
}
