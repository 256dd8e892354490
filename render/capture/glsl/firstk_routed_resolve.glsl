/* Pass 1's resolve when the stencil routed it, after firstk_totals.glsl:
 * the same as firstk_resolve.glsl for the pixels of at most u_W
 * fragments, from the samples; a pixel of more is found by its exact
 * count and flagged here (the fill cannot: it does not know a pixel's
 * last fragment), into the same spill totals and box the array fill
 * writes. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
uniform int u_W;
void main() {
    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_rect.z || px.y >= u_rect.w) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint n = counts[p];
    if (n == 0u) return;
    if (n > uint(u_W)) {
        oit_spill(uvec2(px));
        return;
    }
    uvec4 f[16];
    for (uint i = 0u; i < n; i++) {
        uvec4 x = texelFetch(u_samples, px, int(i));
        OIT_SORTED_INSERT(f, i, x)
    }
    oit_state s = oit_state_load(p);
    for (uint i = 0u; i < n; i++) oit_composite(s, f[i]);
    s.nfrag += n;
    oit_state_store(p, s);
    counts[p] = 0u;
}
