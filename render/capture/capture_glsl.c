/* GLSL of the capture backends (capture_glsl.h). Totals buffer layout:
 * uint overflow, fragments lo, fragments hi, max layers. */
#include "render/capture/capture_glsl.h"
#include "render/gl/frag_glsl.h"

#define COUNT_AND_FLAG                                                              \
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n" \
    "layout(std430, binding = OIT_BIND_TOTALS) "                                    \
    "buffer Totals { uint overflow; uint f_lo; uint f_hi; uint f_max; };\n"         \
    "layout(location = 10) uniform int u_K;\n"

/* Early termination: a pixel whose carried transmittance is below
 * u_epsilon in every channel can gain at most epsilon from anything behind
 * it, so its later fragments are dropped before they take a slot. The fill
 * stage cannot include oit_glsl_composite (its uniforms clash with the
 * fragment generator's); its program puts oit_glsl_state_io before this. */
#define SATURATED                                                           \
    "uniform float u_epsilon;\n"                                          \
    "bool oit_saturated(uint p) {\n"                                      \
    "    if (u_epsilon <= 0.0) return false;\n"                           \
    "    vec3 T = oit_state_T(p);\n"                                      \
    "    return max(T.r, max(T.g, T.b)) < u_epsilon;\n"                   \
    "}\n"

const char oit_capture_saturated[] = SATURATED;

#define SLOTS_BUFFER                                                                       \
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };\n"

/* The fill's main: N (a GLSL int) slots per pixel of the tile u_tile, the
 * first N fragments of a pixel kept and the pixel flagged when more come. */
#define FILL_MAIN(N)                                                                       \
    "void main() {\n"                                                                      \
    "    if (oit_clipped()) discard;\n"                                                    \
    "    uint p = oit_pixel_index();\n"                                                    \
    "    if (oit_behind_opaque()) discard;\n"                                              \
    "    if (oit_saturated(p)) discard;\n"                                                 \
    "    ivec2 px = ivec2(gl_FragCoord.xy) - u_tile.xy;\n"                                 \
    "    uint q = uint(px.y * (u_tile.z - u_tile.x) + px.x);\n"                            \
    "    uint c = atomicAdd(counts[p], 1u);\n"                                             \
    "    if (c < uint(" N ")) slots[q * uint(" N ") + c] = oit_fragment();\n"              \
    "    else if (c == uint(" N ")) atomicAdd(overflow, 1u);\n"                            \
    "}\n"

const char oit_capture_array_fs[] =
    COUNT_AND_FLAG
    SATURATED
    SLOTS_BUFFER
    "uniform ivec4 u_tile;\n"
    FILL_MAIN("u_K");

/* Wide batches: u_W slots per pixel of the current tile u_tile (GL rows,
 * exclusive ends), so a part with more than K layers fits the same slots
 * buffer over fewer pixels. */
const char oit_capture_wide_fs[] =
    COUNT_AND_FLAG
    SATURATED
    SLOTS_BUFFER
    "uniform int u_W;\n"
    "uniform ivec4 u_tile;\n"
    FILL_MAIN("u_W");

/* The stencil target's fill (capture_stencil.h): every fragment counted
 * exactly (the atomic count, not the stencil, tells overflow: it does not
 * saturate and needs no read of the target), the fragment written to the
 * sample the stencil routes it to. OIT_FIRSTK_PASS: first-K's pass 1, whose
 * overflowed pixels are not lost (the second pass takes them), so they are
 * not flagged. OIT_ROUTE_BY_COPY (testing, capture_stencil.h): the fragment
 * goes to slot c of its pixel in a buffer, copied into sample c after the
 * draw, as routing would have put it. */
const char oit_capture_stencil_fs[] =
    COUNT_AND_FLAG
    SATURATED
    "#ifdef OIT_ROUTE_BY_COPY\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Routed { uvec4 routed[]; };\n"
    "#else\n"
    "layout(location = 0) out uvec4 o_frag;\n"
    "#endif\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    if (oit_behind_opaque()) discard;\n"
    "    if (oit_saturated(oit_pixel_index())) discard;\n"
    "    uint c = atomicAdd(counts[oit_pixel_index()], 1u);\n"
    "#ifndef OIT_FIRSTK_PASS\n"
    "    if (c == uint(u_K)) atomicAdd(overflow, 1u);\n"
    "#endif\n"
    "#ifdef OIT_ROUTE_BY_COPY\n"
    "    if (c < uint(u_K)) routed[oit_pixel_index() * uint(u_K) + c] = oit_fragment();\n"
    "#else\n"
    "    o_frag = oit_fragment();\n"
    "#endif\n"
    "}\n";

/* Testing (OIT_ROUTE_BY_COPY): sample u_sample of each pixel of a
 * full-screen draw masked to that sample takes the pixel's slot u_sample,
 * where the fill put the fragment routing would have put there. */
const char oit_capture_route_copy_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Routed { uvec4 routed[]; };\n"
    "layout(location = 0) out uvec4 o_frag;\n"
    "uniform int u_sample;\n"
    "uniform int u_K;\n"
    "uniform int u_width;\n"
    "void main() {\n"
    "    uvec2 px = uvec2(gl_FragCoord.xy);\n"
    "    uint p = px.y * uint(u_width) + px.x;\n"
    "    if (uint(u_sample) >= min(counts[p], uint(u_K))) discard;\n"
    "    o_frag = routed[p * uint(u_K) + uint(u_sample)];\n"
    "}\n";

const char oit_capture_resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    COUNT_AND_FLAG
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    "#if defined(OIT_STENCIL)\n"
    "layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;\n"
    "#define LOAD(px, p, i) texelFetch(u_samples, px, int(i))\n"
    "#define SLOTS uint(u_K)\n"
    "#define LIST 16\n"
    "#elif defined(OIT_WIDE)\n"
    "layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };\n"
    "uniform int u_W;\n"
    "#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_W) + i]\n"
    "#define SLOTS uint(u_W)\n"
    "#define LIST OIT_WIDE\n"
    "#else\n"
    "layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };\n"
    "#define LOAD(px, p, i) slots[uint((px.y - u_rect.y) * (u_rect.z - u_rect.x) + px.x - u_rect.x) * uint(u_K) + i]\n"
    "#define SLOTS uint(u_K)\n"
    "#define LIST 16\n"
    "#endif\n"
    "void main() {\n"
    "    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_rect.z || px.y >= u_rect.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = counts[p];\n"
    /* most pixels of a pack's rectangle get nothing: leave their state */
    "    if (n == 0u) return;\n"
    "    uint m = min(n, SLOTS);\n"
    "    uvec4 f[LIST];\n"
    "    for (uint i = 0u; i < m; i++) {\n"
    "        uvec4 x = LOAD(px, p, i);\n"
    "        OIT_SORTED_INSERT(f, i, x)\n"
    "    }\n"
    "    oit_state s = oit_state_load(p);\n"
    "    for (uint i = 0u; i < m; i++) oit_composite(s, f[i]);\n"
    "    s.nfrag += n;\n"
    "    oit_state_store(p, s);\n"
    "    counts[p] = 0u;\n"
    "}\n";

/* Pixels [u_first, u_first + u_count): their totals, and (u_out) their
 * final colour at out_rgba[0..u_count), so a frame's output can be read in
 * bands through a buffer smaller than the frame. The totals are summed in
 * the workgroup first: a million invocations adding to one word serialise
 * on it. */
const char oit_capture_end_cs[] =
    "layout(local_size_x = 64) in;\n"
    COUNT_AND_FLAG
    "layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };\n"
    "layout(location = 13) uniform uint u_count;\n"
    "uniform uint u_first;\n"
    "uniform int u_out;\n"
    "uniform uint u_group0;\n"
    "shared uint g_lo, g_hi, g_max;\n"
    "void main() {\n"
    "    if (gl_LocalInvocationIndex == 0u) { g_lo = 0u; g_hi = 0u; g_max = 0u; }\n"
    "    barrier();\n"
    "    uint i = (gl_WorkGroupID.x + u_group0) * 64u + gl_LocalInvocationID.x;\n"
    "    if (i < u_count) {\n"
    "        oit_state s = oit_state_load(u_first + i);\n"
    "        if (u_out != 0) out_rgba[i] = oit_state_final(s);\n"
    "        atomicMax(g_max, s.nfrag);\n"
    "        uint old = atomicAdd(g_lo, s.nfrag);\n"
    "        if (old + s.nfrag < old) atomicAdd(g_hi, 1u);\n"
    "    }\n"
    "    barrier();\n"
    "    if (gl_LocalInvocationIndex == 0u && (g_lo | g_hi) != 0u) {\n"
    "        atomicMax(f_max, g_max);\n"
    "        uint old = atomicAdd(f_lo, g_lo);\n"
    "        atomicAdd(f_hi, g_hi + (old + g_lo < old ? 1u : 0u));\n"
    "    }\n"
    "}\n";

const char oit_capture_fullscreen_vs[] =
    "void main() {\n"
    "    vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);\n"
    "    gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";

/* The counted capture (capture_counted.h). Count and store run the same
 * rasterization with the same saturation test, so every counted fragment
 * finds its slot; the store counts each pixel back down to 0. The band's
 * first offset and the store's capacity are the judge's (capture_counted.c),
 * written on the GPU; the store checks the capacity itself, so that a
 * band the judge closed stays within the store where the draws could not
 * be gated. */
#define BAND                                                                              \
    "layout(std430, binding = OIT_BIND_SUMS) readonly buffer Band { uint band_gate; "     \
    "uint band_short; uint band_deep; uint band_pad; uvec4 band_groups; uint band_base; " \
    "uint band_cap; };\n"

/* The head of the counted capture's geometry passes: pixel p's fragment,
 * unless clipped, behind the opaque depth or saturated. */
#define KEPT_FRAGMENT                                                                       \
    "    if (oit_clipped()) discard;\n"                                                     \
    "    uint p = oit_pixel_index();\n"                                                     \
    "    if (oit_behind_opaque()) discard;\n"                                               \
    "    if (oit_saturated(p)) discard;\n"

const char oit_capture_counted_count_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    SATURATED
    "void main() {\n"
    KEPT_FRAGMENT
    "    atomicAdd(counts[p], 1u);\n"
    "}\n";

const char oit_capture_counted_store_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };\n"
    BAND
    SATURATED
    "void main() {\n"
    KEPT_FRAGMENT
    /* a pixel without a segment keeps its count (a predicted batch's
     * spill pass: one the prediction held is at 0 already) */
    "    if (offsets[p + 1u] == offsets[p]) discard;\n"
    "    uint c = atomicAdd(counts[p], 0xffffffffu);\n"
    "    uint slot = offsets[p] - band_base + c - 1u;\n"
    "    if (c != 0u && slot < offsets[p + 1u] - band_base && slot < band_cap)\n"
    "        frags[slot] = oit_fragment();\n"
    "}\n";

/* Before oit_glsl_segment_composite; oit_capture_counted_resolve_main after. */
const char oit_capture_counted_resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };\n"
    BAND;

const char oit_capture_counted_resolve_main[] =
    "void main() {\n"
    "    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_rect.z || px.y >= u_rect.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = offsets[p + 1u] - offsets[p];\n"
    "    if (n == 0u) return;\n"
    "    oit_state s = oit_state_load(p);\n"
    "    oit_segment_composite(s, offsets[p] - band_base, n);\n"
    "    s.nfrag += n;\n"
    "    oit_state_store(p, s);\n"
    "}\n";

/* A predicted band (capture_counted.h): the last frame's offsets of the
 * batch at OIT_BIND_OFFSETS give each pixel its segment, the band's
 * fragments from the offset at pixel u_band_pixel on, in a store of u_cap;
 * every fragment is counted, those within the segment stored. */
#define PREDICTED                                                                          \
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"        \
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };\n" \
    "uniform uint u_band_pixel;\n"                                                         \
    "uniform uint u_cap;\n"                                                                \
    "bool oit_predicted_holds(uint p, uint n) {\n"                                         \
    "    return n <= offsets[p + 1u] - offsets[p] &&\n"                                     \
    "           offsets[p + 1u] - offsets[u_band_pixel] <= u_cap;\n"                       \
    "}\n"

const char oit_capture_counted_predicted_fs[] =
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };\n"
    PREDICTED
    SATURATED
    "void main() {\n"
    KEPT_FRAGMENT
    "    uint c = atomicAdd(counts[p], 1u);\n"
    "    if (oit_predicted_holds(p, c + 1u))\n"
    "        frags[offsets[p] - offsets[u_band_pixel] + c] = oit_fragment();\n"
    "}\n";

/* Before oit_glsl_segment_composite; oit_capture_counted_predicted_main
 * after. */
const char oit_capture_counted_predicted_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    "layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next_counts[]; };\n"
    PREDICTED;

/* Every pixel's count kept for the next frame's prediction; a pixel the
 * prediction held composited and its count back to 0; one it did not
 * keeps its count for the band's spill pass. */
const char oit_capture_counted_predicted_main[] =
    "void main() {\n"
    "    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_rect.z || px.y >= u_rect.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = counts[p];\n"
    "    next_counts[p] = n;\n"
    "    if (n == 0u || !oit_predicted_holds(p, n)) return;\n"
    "    oit_state s = oit_state_load(p);\n"
    "    oit_segment_composite(s, offsets[p] - offsets[u_band_pixel], n);\n"
    "    s.nfrag += n;\n"
    "    oit_state_store(p, s);\n"
    "    counts[p] = 0u;\n"
    "}\n";
