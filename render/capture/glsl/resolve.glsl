/* The slot captures' resolve over the batch rect u_rect, after
 * count_flag.glsl: each pixel's fragments sorted in registers and
 * composited into the state the frame carries, its count back to 0.
 * OIT_STENCIL: the fragments are the routed samples; OIT_WIDE N: a wide
 * tile of u_W slots a pixel (u_rect is the tile, N >= u_W); else K slots
 * a pixel of the rect. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
#if defined(OIT_STENCIL)
layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;
#define LOAD(px, p, i) texelFetch(u_samples, px, int(i))
#define SLOTS uint(u_K)
#define LIST 16
#elif defined(OIT_WIDE)
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
uniform int u_W;
#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_W) + i]
#define SLOTS uint(u_W)
#define LIST OIT_WIDE
#else
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };
#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_K) + i]
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
