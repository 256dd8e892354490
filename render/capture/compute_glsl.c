/* The compute capture's shaders (capture_compute.h has the design). One
 * string per stage; the fragment maths come from frag_glsl.h's libraries,
 * not copies of them. */
#include "render/capture/compute_glsl.h"

#include "render/gl/gl_util.h"
#include "render/gl/glsl_bindings.h"

_Static_assert(OIT_COMPUTE_SWEEP == 16, "cs_consider shifts 15 slots, written out");

/* What every stage shares: the tile size and the record layout (uvec4s a
 * triangle, indexed by its place in the batch):
 *   r0 = e0.xyz, prim | opaque << 31   e_i: edge i's homogeneous line,
 *   r1 = e1.xyz, rgba0                      oriented so that the inside is
 *   r2 = e2.xyz, rgba1                      positive (below)
 *   r3 = clip z0, z1, z2, rgba2
 *   r4 = clip w0, w1, w2, 0
 *   r5..r7 = view-space vertex k, normal[k]
 *   r8 = the tie rule's plane (v_plane)
 *   r9 = the pixel box (x0, y0, x1, y1), GL rows, exclusive ends; empty
 *        when x0 >= x1 (culled) */
#define CS_COMMON                                                             \
    "#define CS_TILE " OIT_GLSL_STR(OIT_COMPUTE_TILE) "\n"                     \
    "#define CS_REC " OIT_GLSL_STR(OIT_COMPUTE_RECORD_WORDS) "u\n"             \
    "layout(location = 11) uniform ivec2 u_size;\n"                           \
    "layout(location = 12) uniform ivec4 u_rect;\n"                           \
    "uint cs_tiles_x() { return uint(u_size.x + CS_TILE - 1) / uint(CS_TILE); }\n"

/* The records in up to OIT_COMPUTE_BLOCKS storage blocks (CS_BLOCKS of
 * them: oit_compute_blocks_decl comes first), u_block_recs records each,
 * so that a batch is not limited to what one binding spans. Block i holds
 * records [i, i + 1) * u_block_recs. GLSL 4.5 indexes an array of blocks
 * only with a dynamically uniform index, and a tile's records may lie in
 * any block, so the block is picked by an if-chain on the record's index;
 * a batch within one binding takes its first branch. */
#define CS_BLOCK(q, i, bind)                                                  \
    "#if CS_BLOCKS > " #i "\n"                                                \
    "layout(std430, binding = " bind ") " q " buffer Recs" #i                 \
    " { uvec4 recs" #i "[]; };\n"                                              \
    "#endif\n"
#define CS_BLOCKS_DECL(q)                                                     \
    "uniform uint u_block_recs;\n"                                            \
    CS_BLOCK(q, 0, "OIT_BIND_FRAGS") CS_BLOCK(q, 1, "OIT_BIND_RECS1")         \
    CS_BLOCK(q, 2, "OIT_BIND_RECS2") CS_BLOCK(q, 3, "OIT_BIND_RECS3")         \
    CS_BLOCK(q, 4, "OIT_BIND_RECS4") CS_BLOCK(q, 5, "OIT_BIND_RECS5")         \
    CS_BLOCK(q, 6, "OIT_BIND_RECS6") CS_BLOCK(q, 7, "OIT_BIND_RECS7")
#define CS_GET(i)                                                             \
    "#if CS_BLOCKS > " #i "\n"                                                \
    "    if (r < u_block_recs) return recs" #i "[r * CS_REC + w];\n"           \
    "    r -= u_block_recs;\n"                                                \
    "#endif\n"
/* Word w of record r (past every block: zeros, never asked for). */
#define CS_RECS_READ                                                          \
    CS_BLOCKS_DECL("readonly")                                                \
    "uvec4 cs_rec(uint r, uint w) {\n"                                        \
    CS_GET(0) CS_GET(1) CS_GET(2) CS_GET(3) CS_GET(4) CS_GET(5) CS_GET(6)     \
    CS_GET(7)                                                                 \
    "    return uvec4(0u);\n"                                                 \
    "}\n"
#define CS_PUT(i)                                                             \
    "#if CS_BLOCKS > " #i "\n"                                                \
    "    if (r < u_block_recs) { recs" #i "[r * CS_REC + w] = v; return; }\n"  \
    "    r -= u_block_recs;\n"                                                \
    "#endif\n"
#define CS_RECS_WRITE                                                         \
    CS_BLOCKS_DECL("writeonly")                                               \
    "void cs_put(uint r, uint w, uvec4 v) {\n"                                \
    CS_PUT(0) CS_PUT(1) CS_PUT(2) CS_PUT(3) CS_PUT(4) CS_PUT(5) CS_PUT(6)     \
    CS_PUT(7)                                                                 \
    "}\n"

_Static_assert(OIT_COMPUTE_BLOCKS == 8, "CS_BLOCKS_DECL, CS_GET and CS_PUT name 8 blocks");
_Static_assert(OIT_BIND_RECS7 - OIT_BIND_RECS1 == 6, "glsl_bindings.h: 7 record bindings");

const char oit_compute_setup_cs[] =
    CS_COMMON
    "layout(local_size_x = 64) in;\n"
    CS_RECS_WRITE
    "layout(std430, binding = OIT_BIND_OFFSETS) buffer TileCounts { uint tile_count[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer TileDead { uint tile_dead[]; };\n"
    "uniform uint u_window_first;\n"
    "uniform uint u_window_count;\n"
    "uniform uint u_rec_base;\n"
    "uniform uint u_first_prim;\n"
    "uniform uint u_sourced;\n"
    "uniform uint u_prim_word0;\n"
    "uniform int u_live;\n"
    /* Written out and precise, so that the edge a triangle shares with its
     * neighbour is the exact negation of the neighbour's (each component
     * is the same two products subtracted the other way round); in double
     * from the float clip coordinates, where each product is exact, so
     * that the edges and the sign of det (the orientation) stay right for
     * slivers and tiny triangles. */
    "dvec3 cs_cross(dvec3 a, dvec3 b) {\n"
    "    precise dvec3 c;\n"
    "    c.x = a.y * b.z - a.z * b.y;\n"
    "    c.y = a.z * b.x - a.x * b.z;\n"
    "    c.z = a.x * b.y - a.y * b.x;\n"
    "    return c;\n"
    "}\n"
    /* Entirely outside one plane of the clip volume (GL clips x, y and z
     * to [-w, w]); also a triangle with a coordinate that is not a number. */
    "bool cs_culled(vec4 c[3]) {\n"
    "    bvec4 all_lo = bvec4(true), all_hi = bvec4(true);\n"
    "    for (int k = 0; k < 3; k++) {\n"
    "        if (any(isnan(c[k])) || any(isinf(c[k]))) return true;\n"
    "        all_lo = bvec4(all_lo.x && c[k].x < -c[k].w, all_lo.y && c[k].y < -c[k].w,\n"
    "                       all_lo.z && c[k].z < -c[k].w, all_lo.w && c[k].w <= 0.0);\n"
    "        all_hi = bvec4(all_hi.x && c[k].x > c[k].w, all_hi.y && c[k].y > c[k].w,\n"
    "                       all_hi.z && c[k].z > c[k].w, false);\n"
    "    }\n"
    "    return any(all_lo) || any(all_hi);\n"
    "}\n"
    /* The pixels whose centres it may cover, within the batch's rect: the
     * projected vertices' box and a pixel of margin, or the whole rect
     * when a vertex lies behind the eye (w <= 0 projects nowhere useful;
     * the coverage test itself handles it). */
    "ivec4 cs_box(vec4 c[3]) {\n"
    "    vec4 r = vec4(u_rect);\n"
    "    if (c[0].w <= 0.0 || c[1].w <= 0.0 || c[2].w <= 0.0) return u_rect;\n"
    "    vec2 lo = vec2(1e30), hi = vec2(-1e30);\n"
    "    for (int k = 0; k < 3; k++) {\n"
    "        vec2 win = (c[k].xy / c[k].w + 1.0) * 0.5 * vec2(u_size);\n"
    "        lo = min(lo, win); hi = max(hi, win);\n"
    "    }\n"
    "    lo = clamp(floor(lo - 0.5) - 1.0, r.xy, r.zw);\n"
    "    hi = clamp(ceil(hi - 0.5) + 2.0, r.xy, r.zw);\n"
    "    return ivec4(lo, hi);\n"
    "}\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;\n"
    "    if (i >= u_window_count) return;\n"
    "    uint v0 = i * 3u;\n"
    "    uvec4 va[3] = uvec4[3](verts[v0], verts[v0 + 1u], verts[v0 + 2u]);\n"
    "    vec3 wp[3]; vec3 vp[3]; vec4 cl[3];\n"
    /* The vertex stage's transform (oit_glsl_vertex), one vertex at a time
     * through the same code, precise, so that a vertex shared by two
     * triangles lands on the same bits in both. */
    "    for (int k = 0; k < 3; k++) {\n"
    "        wp[k] = oit_world(va[k]);\n"
    "        precise vec4 q = u_view * vec4(wp[k], 1.0);\n"
    "        precise vec4 c = u_proj * q;\n"
    "        vp[k] = q.xyz; cl[k] = c;\n"
    "    }\n"
    "    uint prim = (u_sourced != 0u ? prims[u_prim_word0 + i] : u_first_prim + u_window_first + i)\n"
    "                & 0x7fffffffu;\n"
    "    bool opaque = u_mode == 0 && (u_attrs & 2u) != 0u &&\n"
    "                  (va[0].w & va[1].w & va[2].w) >> 24 == 255u;\n"
    "    vec3 nrm = mat3(u_view) * cross(wp[1] - wp[0], wp[2] - wp[0]);\n"
    "    vec4 plane = oit_tie_plane(wp[0], wp[1], wp[2]);\n"
    /* Homogeneous rasterization (Olano and Greer 1997): e_i . (x, y, 1) in
     * NDC is det * the barycentric lambda_i of the pixel's ray, so the
     * ray meets the triangle in front of the eye exactly where every e_i
     * times sign(det) is >= 0; no clipping against the eye plane. */
    "    dvec3 h0 = dvec3(cl[0].xyw), h1 = dvec3(cl[1].xyw), h2 = dvec3(cl[2].xyw);\n"
    "    dvec3 d0 = cs_cross(h1, h2), d1 = cs_cross(h2, h0), d2 = cs_cross(h0, h1);\n"
    "    precise double det = h0.x * d0.x + h0.y * d0.y + h0.z * d0.z;\n"
    "    ivec4 box = ivec4(0);\n"
    "    if (det != 0.0lf && !cs_culled(cl)) box = cs_box(cl);\n"
    "    double sg = det > 0.0lf ? 1.0lf : -1.0lf;\n"
    "    vec3 e0 = vec3(d0 * sg), e1 = vec3(d1 * sg), e2 = vec3(d2 * sg);\n"
    "    uint b = u_rec_base + i;\n"
    "    cs_put(b, 0u, uvec4(floatBitsToUint(e0), prim | (opaque ? 0x80000000u : 0u)));\n"
    "    cs_put(b, 1u, uvec4(floatBitsToUint(e1), va[0].w));\n"
    "    cs_put(b, 2u, uvec4(floatBitsToUint(e2), va[1].w));\n"
    "    cs_put(b, 3u, uvec4(floatBitsToUint(vec3(cl[0].z, cl[1].z, cl[2].z)), va[2].w));\n"
    "    cs_put(b, 4u, uvec4(floatBitsToUint(vec3(cl[0].w, cl[1].w, cl[2].w)), 0u));\n"
    "    for (int k = 0; k < 3; k++)\n"
    "        cs_put(b, 5u + uint(k), uvec4(floatBitsToUint(vp[k]), floatBitsToUint(nrm[k])));\n"
    "    cs_put(b, 8u, floatBitsToUint(plane));\n"
    "    cs_put(b, 9u, uvec4(box));\n"
    "    if (box.x >= box.z || box.y >= box.w) return;\n"
    "    uint tx = cs_tiles_x();\n"
    "    for (int ty = box.y / CS_TILE; ty <= (box.w - 1) / CS_TILE; ty++)\n"
    "        for (int tc = box.x / CS_TILE; tc <= (box.z - 1) / CS_TILE; tc++) {\n"
    "            uint t = uint(ty) * tx + uint(tc);\n"
    "            if (u_live == 0 || tile_dead[t] == 0u) atomicAdd(tile_count[t], 1u);\n"
    "        }\n"
    "}\n";

/* After the scan, tile_count holds each tile's first entry; taking one
 * with an atomic leaves it at the tile's end, the next tile's start. The
 * order within a tile is whatever the atomics give: the sweep orders.
 * The list holds u_list_cap entries, sized by the host without reading
 * the scan's total back: an entry past it is not written (the sweep
 * finds the tile's triangles among all records instead) and the entries
 * the batch needed go to late_need, which the host reads after the frame
 * to size the next frame's lists. */
const char oit_compute_scatter_cs[] =
    CS_COMMON
    "layout(local_size_x = 64) in;\n"
    CS_RECS_READ
    "layout(std430, binding = OIT_BIND_OFFSETS) buffer TileCounts { uint tile_count[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer TileDead { uint tile_dead[]; };\n"
    "layout(std430, binding = OIT_BIND_SUMS) writeonly buffer TileList { uint tile_list[]; };\n"
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Late { uint late_need; };\n"
    "layout(location = 13) uniform uint u_count;\n"
    "uniform uint u_list_cap;\n"
    "uniform int u_live;\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;\n"
    "    if (i >= u_count) return;\n"
    "    ivec4 box = ivec4(cs_rec(i, 9u));\n"
    "    if (box.x >= box.z || box.y >= box.w) return;\n"
    "    uint tx = cs_tiles_x();\n"
    "    for (int ty = box.y / CS_TILE; ty <= (box.w - 1) / CS_TILE; ty++)\n"
    "        for (int tc = box.x / CS_TILE; tc <= (box.z - 1) / CS_TILE; tc++) {\n"
    "            uint t = uint(ty) * tx + uint(tc);\n"
    "            if (u_live != 0 && tile_dead[t] != 0u) continue;\n"
    "            uint at = atomicAdd(tile_count[t], 1u);\n"
    "            if (at < u_list_cap) tile_list[at] = i;\n"
    "            else atomicMax(late_need, at + 1u);\n"
    "        }\n"
    "}\n";

/* The sweep's work list (uvec4 header: the indirect dispatch's groups in
 * xyz, the tiles in w; then the tiles): the tiles of the rect [u_tile0,
 * u_tile1] with an entry in their list. */
const char oit_compute_work_cs[] =
    CS_COMMON
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer TileEnds { uint tile_end[]; };\n"
    "layout(std430, binding = OIT_BIND_OUT) buffer Work { uvec4 work_hdr; uint work[]; };\n"
    "uniform ivec2 u_tile0;\n"
    "uniform ivec2 u_tile1;\n"
    "void main() {\n"
    "    ivec2 tile = u_tile0 + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (any(greaterThan(tile, u_tile1))) return;\n"
    "    uint t = uint(tile.y) * cs_tiles_x() + uint(tile.x);\n"
    "    uint lo = t == 0u ? 0u : tile_end[t - 1u];\n"
    "    if (tile_end[t] > lo) work[atomicAdd(work_hdr.w, 1u)] = t;\n"
    "}\n";

/* A work list's tiles into its dispatch's groups: rows of 65535 (the
 * least GL_MAX_COMPUTE_WORK_GROUP_COUNT), none when it is empty. */
const char oit_compute_args_cs[] =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = OIT_BIND_OUT) buffer Work { uvec4 work_hdr; };\n"
    "void main() {\n"
    "    uint c = work_hdr.w;\n"
    "    work_hdr.xyz = uvec3(min(c, 65535u), (c + 65534u) / 65535u, 1u);\n"
    "}\n";

/* Whether the driver cuts loops short (tiles_cs says why that matters):
 * the iterations a loop of u_probe ran. */
const char oit_compute_probe_cs[] =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Probe { uint ran; };\n"
    "uniform int u_probe;\n"
    "void main() {\n"
    "    int i = 0;\n"
    "    while (i < u_probe) i++;\n"
    "    ran = uint(i);\n"
    "}\n";

/* Per-tile early termination: tile_dead starts all 1 (a buffer clear);
 * a pixel of the rect whose carried T is not below epsilon in some
 * channel marks its tile live (every writer writes 0). */
const char oit_compute_live_cs[] =
    CS_COMMON
    "layout(local_size_x = CS_TILE, local_size_y = CS_TILE) in;\n"
    "layout(std430, binding = OIT_BIND_TOTALS) buffer TileDead { uint tile_dead[]; };\n"
    "uniform ivec2 u_tile0;\n"
    "uniform float u_epsilon;\n"
    "void main() {\n"
    "    ivec2 tile = u_tile0 + ivec2(gl_WorkGroupID.xy);\n"
    "    ivec2 px = tile * CS_TILE + ivec2(gl_LocalInvocationID.xy);\n"
    "    if (any(lessThan(px, u_rect.xy)) || any(greaterThanEqual(px, u_rect.zw))) return;\n"
    "    vec3 T = oit_state_T(uint(px.y) * uint(u_size.x) + uint(px.x));\n"
    "    if (max(T.r, max(T.g, T.b)) >= u_epsilon)\n"
    "        tile_dead[uint(tile.y) * cs_tiles_x() + uint(tile.x)] = 0u;\n"
    "}\n";

/* The fragment library's inputs, set per (pixel, triangle) by
 * cs_fragment_at; before oit_glsl_fragment_lib. */
const char oit_compute_frag_inputs[] =
    "vec3 v_pos; vec4 v_rgba; vec3 v_normal; uint v_first_prim; vec4 v_plane; uint v_opaque;\n"
    "vec4 cs_frag_coord;\n"
    "#define OIT_FRAG_COORD cs_frag_coord\n"
    "#define OIT_PRIMITIVE_ID 0u\n";

/* One invocation a pixel, a work group a tile. The sweep: each pass over
 * the tile's triangles keeps, in registers, the CS_N least fragments
 * (key, prim, record) after the last one composited, then composites
 * them; it passes again while any fragment was left out.
 *
 * Loops cut short. GL runs a loop to its end, but llvmpipe stops every
 * loop of an invocation once all of them together have iterated 65535
 * times (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), silently: a deep pixel
 * lost fragments past ~270 layers. So a sweep counts only when a probe
 * loop of u_probe iterations afterwards still runs to its end (the limit
 * was not reached inside the sweep, its insertions and its compositing,
 * which goes into a copy of the state); otherwise the pixel records its
 * cursor in resume[] and counts itself pending, and the caller
 * dispatches again (u_resume), each invocation with a fresh limit, until
 * no pixel is pending. On a driver without such a limit nothing is ever
 * pending.
 *
 * The tiles come from a work list written on the GPU (work_cs, then each
 * round's pending tiles, appended once a round: tile_stamp holds the
 * round that last appended the tile), dispatched indirectly, so that the
 * host reads nothing back between rounds. A tile whose list lost entries
 * (past u_list_cap, scatter_cs) sweeps every record of the batch whose
 * pixel box holds the pixel: the same triangles, found slower. */
const char oit_compute_tiles_cs[] =
    CS_COMMON
    "#define CS_N " OIT_GLSL_STR(OIT_COMPUTE_SWEEP) "u\n"
    "layout(local_size_x = CS_TILE, local_size_y = CS_TILE) in;\n"
    CS_RECS_READ
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer TileEnds { uint tile_end[]; };\n"
    "layout(std430, binding = OIT_BIND_SUMS) readonly buffer TileList { uint tile_list[]; };\n"
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Resume { uvec4 resume[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) buffer Pending {\n"
    "    uint g_pending; uint g_progress; uint g_pad0; uint g_pad1; uint tile_stamp[];\n"
    "};\n"
    "layout(std430, binding = OIT_BIND_VERTS) readonly buffer Work { uvec4 work_hdr; uint work[]; };\n"
    "layout(std430, binding = OIT_BIND_OUT) buffer Next { uvec4 next_hdr; uint next[]; };\n"
    "uniform float u_epsilon;\n"
    "uniform int u_resume;\n"
    "uniform uint u_round;\n"
    "uniform uint u_list_cap;\n"
    "uniform uint u_recs;\n"
    "uniform int u_probe;\n"
    /* The fill rule on an edge's line: a pixel centre exactly on it
     * belongs to the side its coefficients point to (top-left in spirit);
     * the neighbour across a shared edge holds the exact negation, so
     * exactly one of the two takes the pixel. */
    "bool cs_inside(vec3 e, vec2 P, out float v) {\n"
    "    precise float s = e.x * P.x + e.y * P.y + e.z;\n"
    "    v = s;\n"
    "    if (s != 0.0) return s > 0.0;\n"
    "    return e.x > 0.0 || (e.x == 0.0 && e.y > 0.0);\n"
    "}\n"
    /* Whether record r covers the pixel (NDC centre P) inside the clip
     * volume and survives the section planes and the opaque depths; sets
     * the fragment library's inputs for it when it does. */
    "bool cs_fragment_at(uint r, vec2 P) {\n"
    "    uvec4 r0 = cs_rec(r, 0u), r1 = cs_rec(r, 1u), r2 = cs_rec(r, 2u);\n"
    "    vec3 E;\n"
    "    if (!cs_inside(uintBitsToFloat(r0.xyz), P, E.x)) return false;\n"
    "    if (!cs_inside(uintBitsToFloat(r1.xyz), P, E.y)) return false;\n"
    "    if (!cs_inside(uintBitsToFloat(r2.xyz), P, E.z)) return false;\n"
    "    E = max(E, vec3(0.0));\n"
    "    float sum = E.x + E.y + E.z;\n"
    "    vec3 mu = sum > 0.0 ? E / sum : vec3(1.0 / 3.0);\n"
    "    uvec4 r3 = cs_rec(r, 3u), r4 = cs_rec(r, 4u);\n"
    "    float zc = dot(mu, uintBitsToFloat(r3.xyz)), wc = dot(mu, uintBitsToFloat(r4.xyz));\n"
    /* GL's clipping to -w <= z <= w (near and far planes). */
    "    if (!(wc > 0.0) || zc < -wc || zc > wc) return false;\n"
    "    cs_frag_coord.z = zc / wc * 0.5 + 0.5;\n"
    "    uvec4 q0 = cs_rec(r, 5u), q1 = cs_rec(r, 6u), q2 = cs_rec(r, 7u);\n"
    "    v_pos = mu.x * uintBitsToFloat(q0.xyz) + mu.y * uintBitsToFloat(q1.xyz) +\n"
    "            mu.z * uintBitsToFloat(q2.xyz);\n"
    "    v_normal = uintBitsToFloat(uvec3(q0.w, q1.w, q2.w));\n"
    "    v_plane = uintBitsToFloat(cs_rec(r, 8u));\n"
    "    v_first_prim = r0.w | 0x80000000u;\n"
    "    v_opaque = r0.w >> 31;\n"
    "    if (oit_clipped() || oit_behind_opaque()) return false;\n"
    "    vec4 c0 = unpackUnorm4x8(r1.w), c1 = unpackUnorm4x8(r2.w), c2 = unpackUnorm4x8(r3.w);\n"
    "    if (u_colour_space == 1) {\n"
    "        c0.rgb = oit_srgb_decode(c0.rgb); c1.rgb = oit_srgb_decode(c1.rgb);\n"
    "        c2.rgb = oit_srgb_decode(c2.rgb);\n"
    "    }\n"
    "    v_rgba = mu.x * c0 + mu.y * c1 + mu.z * c2;\n"
    "    return true;\n"
    "}\n"
    /* The edge tests of cs_fragment_at alone; sweeping every record, also
     * the record's box (the lists hold a record in the tiles its box
     * meets). */
    "bool cs_all; ivec2 cs_px;\n"
    "bool cs_covers(uint r, vec2 P) {\n"
    "    float v;\n"
    "    if (cs_all) {\n"
    "        ivec4 bx = ivec4(cs_rec(r, 9u));\n"
    "        if (any(lessThan(cs_px, bx.xy)) || any(greaterThanEqual(cs_px, bx.zw))) return false;\n"
    "    }\n"
    "    return cs_inside(uintBitsToFloat(cs_rec(r, 0u).xyz), P, v) &&\n"
    "           cs_inside(uintBitsToFloat(cs_rec(r, 1u).xyz), P, v) &&\n"
    "           cs_inside(uintBitsToFloat(cs_rec(r, 2u).xyz), P, v);\n"
    "}\n"
    "bool cs_less(uvec3 a, uvec3 b) {\n"
    "    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));\n"
    "}\n"
    "uvec3 cs_order(uvec4 f, uint r) { return uvec3(f.x, f.y & 0x7fffffffu, r); }\n"
    /* The sweep's registers, as globals so that the unrolled steps share
     * them without copies. */
    "uvec4 cs_f[CS_N]; uint cs_r[CS_N]; uint cs_n; bool cs_more;\n"
    "uvec3 cs_cursor; bool cs_first; vec2 cs_P;\n"
    "void cs_consider(uint r) {\n"
    "    if (!cs_fragment_at(r, cs_P)) return;\n"
    "    uvec3 o = uvec3(oit_fragment_key(), v_first_prim & 0x7fffffffu, r);\n"
    "    if (!cs_first && !cs_less(cs_cursor, o)) return;\n"
    "    if (cs_n == CS_N) {\n"
    "        cs_more = true;\n"
    "        if (!cs_less(o, cs_order(cs_f[CS_N - 1u], cs_r[CS_N - 1u]))) return;\n"
    "        cs_n--;\n"
    "    }\n"
    "    uvec4 x = oit_fragment();\n"
    /* Insertion written out, no loop: llvmpipe counts a loop entered by a
     * masked lane against its limit at every triangle of the list, and
     * constant indices keep the arrays in registers on a GPU. Slot j
     * shifts up while x orders before it; the array is sorted, so the
     * shifts stop at x's place. */
    "    uint pos = cs_n;\n"
    "#define CS_SHIFT(j) if (j <= cs_n && cs_less(o, cs_order(cs_f[j - 1u], cs_r[j - 1u]))) "
    "{ cs_f[j] = cs_f[j - 1u]; cs_r[j] = cs_r[j - 1u]; pos = j - 1u; }\n"
    "    CS_SHIFT(15u) CS_SHIFT(14u) CS_SHIFT(13u) CS_SHIFT(12u) CS_SHIFT(11u)\n"
    "    CS_SHIFT(10u) CS_SHIFT(9u) CS_SHIFT(8u) CS_SHIFT(7u) CS_SHIFT(6u) CS_SHIFT(5u)\n"
    "    CS_SHIFT(4u) CS_SHIFT(3u) CS_SHIFT(2u) CS_SHIFT(1u)\n"
    "    cs_f[pos] = x; cs_r[pos] = r;\n"
    "    cs_n++;\n"
    "}\n"
    /* True when the driver cut loops short before this (see above). */
    "bool cs_cut() {\n"
    "    int i = 0;\n"
    "    while (i < u_probe) i++;\n"
    "    return i < u_probe;\n"
    "}\n"
    "uint cs_entry(uint k) { return cs_all ? k : tile_list[k]; }\n"
    "void main() {\n"
    "    uint g = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;\n"
    "    if (g >= work_hdr.w) return;\n"
    "    uint t = work[g], tx = cs_tiles_x();\n"
    "    ivec2 tile = ivec2(int(t % tx), int(t / tx));\n"
    "    ivec2 px = tile * CS_TILE + ivec2(gl_LocalInvocationID.xy);\n"
    "    if (any(lessThan(px, u_rect.xy)) || any(greaterThanEqual(px, u_rect.zw))) return;\n"
    "    uint lo = t == 0u ? 0u : tile_end[t - 1u], hi = tile_end[t];\n"
    "    if (lo >= hi) return;\n"
    "    cs_all = hi > u_list_cap;\n"
    "    cs_px = px;\n"
    "    if (cs_all) { lo = 0u; hi = u_recs; }\n"
    "    uint p = uint(px.y) * uint(u_size.x) + uint(px.x);\n"
    "    cs_cursor = uvec3(0u);\n"
    "    cs_first = true;\n"
    "    if (u_resume != 0) {\n"
    "        uvec4 q = resume[p];\n"
    "        if (q.w == 0u) return;\n"
    "        cs_cursor = q.xyz;\n"
    "        cs_first = q.w == 1u;\n"
    /* Early termination per pixel too, as the other captures drop a
     * saturated pixel's fragments; at the batch's start only, as they do. */
    "    } else if (u_epsilon > 0.0) {\n"
    "        vec3 T = oit_state_T(p);\n"
    "        if (max(T.r, max(T.g, T.b)) < u_epsilon) {\n"
    "            resume[p] = uvec4(0u);\n"
    "            return;\n"
    "        }\n"
    "    }\n"
    "    precise vec2 P = (vec2(px) + 0.5) * (2.0 / vec2(u_size)) - 1.0;\n"
    "    cs_P = P;\n"
    "    cs_frag_coord = vec4(vec2(px) + 0.5, 0.0, 1.0);\n"
    "    oit_state s = oit_state_load(p);\n"
    "    bool done = false, progressed = false;\n"
    "    for (;;) {\n"
    "        cs_n = 0u;\n"
    "        cs_more = false;\n"
    "        uint k = lo;\n"
    /* Eight triangles at a time: their coverage first (cheap, written
     * out), then the fragments of those that cover the pixel, so that the
     * shading runs as often as the most covered lane needs, not once a
     * triangle (SIMD lanes of a CPU, threads of a warp). */
    "        for (; k < hi; k += 8u) {\n"
    "            uint bits = 0u;\n"
    "#define CS_COVER(u) if (k + u < hi && cs_covers(cs_entry(k + u), P)) bits |= 1u << u;\n"
    "            CS_COVER(0u) CS_COVER(1u) CS_COVER(2u) CS_COVER(3u)\n"
    "            CS_COVER(4u) CS_COVER(5u) CS_COVER(6u) CS_COVER(7u)\n"
    "            while (bits != 0u) {\n"
    "                uint u = uint(findLSB(bits));\n"
    "                bits &= bits - 1u;\n"
    "                cs_consider(cs_entry(k + u));\n"
    "            }\n"
    "        }\n"
    "        oit_state s2 = s;\n"
    "        for (uint i = 0u; i < cs_n; i++) oit_composite(s2, cs_f[i]);\n"
    "        if (cs_cut()) break;\n"
    "        s = s2;\n"
    "        s.nfrag += cs_n;\n"
    "        progressed = true;\n"
    "        if (!cs_more) { done = true; break; }\n"
    "        cs_cursor = cs_order(cs_f[CS_N - 1u], cs_r[CS_N - 1u]);\n"
    "        cs_first = false;\n"
    "    }\n"
    "    if (progressed) oit_state_store(p, s);\n"
    "    resume[p] = uvec4(cs_cursor, done ? 0u : cs_first ? 1u : 2u);\n"
    "    if (!done) {\n"
    "        atomicAdd(g_pending, 1u);\n"
    "        if (progressed) atomicAdd(g_progress, 1u);\n"
    "        if (atomicExchange(tile_stamp[t], u_round) != u_round)\n"
    "            next[atomicAdd(next_hdr.w, 1u)] = t;\n"
    "    }\n"
    "}\n";
