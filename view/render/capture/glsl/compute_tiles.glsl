/* The compute capture's sweep, after oit_glsl_composite, oit_glsl_state_io,
 * compute_frag_inputs.glsl, oit_glsl_fragment_lib, compute_common.glsl and
 * compute_recs_read.glsl: coverage, order and compositing per pixel. One
 * invocation a pixel, a work group a tile. The sweep: each pass over the
 * tile's triangles keeps, in registers, the CS_N least fragments (key,
 * prim, record) after the last one composited, then composites them; it
 * passes again while any fragment was left out.
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
 * The tiles come from a work list written on the GPU (compute_work.glsl,
 * then each round's pending tiles, appended once a round: tile_stamp
 * holds the round that last appended the tile), dispatched indirectly, so
 * that the host reads nothing back between rounds. A tile whose list lost
 * entries (past u_list_cap, compute_scatter.glsl) sweeps every record of
 * the batch whose pixel box holds the pixel: the same triangles, found
 * slower. */
layout(local_size_x = CS_TILE, local_size_y = CS_TILE) in;
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer TileEnds { uint tile_end[]; };
layout(std430, binding = OIT_BIND_SUMS) readonly buffer TileList { uint tile_list[]; };
layout(std430, binding = OIT_BIND_COUNTS) buffer Resume { uvec4 resume[]; };
layout(std430, binding = OIT_BIND_TOTALS) buffer Pending {
    uint g_pending; uint g_progress; uint g_pad0; uint g_pad1; uint tile_stamp[];
};
layout(std430, binding = OIT_BIND_VERTS) readonly buffer Work { uvec4 work_hdr; uint work[]; };
layout(std430, binding = OIT_BIND_OUT) buffer Next { uvec4 next_hdr; uint next[]; };
uniform float u_epsilon;
uniform int u_resume;
uniform uint u_round;
uniform uint u_list_cap;
uniform uint u_recs;
uniform int u_probe;
/* The fill rule on an edge's line: a pixel centre exactly on it
 * belongs to the side its coefficients point to (top-left in spirit);
 * the neighbour across a shared edge holds the exact negation, so
 * exactly one of the two takes the pixel. */
bool cs_inside(vec3 e, vec2 P, out float v) {
    precise float s = e.x * P.x + e.y * P.y + e.z;
    v = s;
    if (s != 0.0) return s > 0.0;
    return e.x > 0.0 || (e.x == 0.0 && e.y > 0.0);
}
/* Whether record r covers the pixel (NDC centre P) inside the clip
 * volume and survives the section planes and the opaque depths; sets
 * the fragment library's inputs for it when it does. */
bool cs_fragment_at(uint r, vec2 P) {
    uvec4 r0 = cs_rec(r, 0u), r1 = cs_rec(r, 1u), r2 = cs_rec(r, 2u);
    vec3 E;
    if (!cs_inside(uintBitsToFloat(r0.xyz), P, E.x)) return false;
    if (!cs_inside(uintBitsToFloat(r1.xyz), P, E.y)) return false;
    if (!cs_inside(uintBitsToFloat(r2.xyz), P, E.z)) return false;
    E = max(E, vec3(0.0));
    float sum = E.x + E.y + E.z;
    vec3 mu = sum > 0.0 ? E / sum : vec3(1.0 / 3.0);
    uvec4 r3 = cs_rec(r, 3u), r4 = cs_rec(r, 4u);
    float zc = dot(mu, uintBitsToFloat(r3.xyz)), wc = dot(mu, uintBitsToFloat(r4.xyz));
    /* GL's clipping to -w <= z <= w (near and far planes). */
    if (!(wc > 0.0) || zc < -wc || zc > wc) return false;
    cs_frag_coord.z = zc / wc * 0.5 + 0.5;
    uvec4 q0 = cs_rec(r, 5u), q1 = cs_rec(r, 6u), q2 = cs_rec(r, 7u);
    v_pos = mu.x * uintBitsToFloat(q0.xyz) + mu.y * uintBitsToFloat(q1.xyz) +
            mu.z * uintBitsToFloat(q2.xyz);
    v_normal = uintBitsToFloat(uvec3(q0.w, q1.w, q2.w));
    v_plane = uintBitsToFloat(cs_rec(r, 8u));
    v_first_prim = r0.w | 0x80000000u;
    v_opaque = r0.w >> 31;
    if (oit_clipped() || oit_behind_opaque()) return false;
    vec4 c0 = unpackUnorm4x8(r1.w), c1 = unpackUnorm4x8(r2.w), c2 = unpackUnorm4x8(r3.w);
    if (u_colour_space == 1) {
        c0.rgb = oit_srgb_decode(c0.rgb); c1.rgb = oit_srgb_decode(c1.rgb);
        c2.rgb = oit_srgb_decode(c2.rgb);
    }
    v_rgba = mu.x * c0 + mu.y * c1 + mu.z * c2;
    return true;
}
/* The edge tests of cs_fragment_at alone; sweeping every record, also
 * the record's box (the lists hold a record in the tiles its box
 * meets). */
bool cs_all; ivec2 cs_px;
bool cs_covers(uint r, vec2 P) {
    float v;
    if (cs_all) {
        ivec4 bx = ivec4(cs_rec(r, 9u));
        if (any(lessThan(cs_px, bx.xy)) || any(greaterThanEqual(cs_px, bx.zw))) return false;
    }
    return cs_inside(uintBitsToFloat(cs_rec(r, 0u).xyz), P, v) &&
           cs_inside(uintBitsToFloat(cs_rec(r, 1u).xyz), P, v) &&
           cs_inside(uintBitsToFloat(cs_rec(r, 2u).xyz), P, v);
}
bool cs_less(uvec3 a, uvec3 b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}
uvec3 cs_order(uvec4 f, uint r) { return uvec3(f.x, f.y & 0x7fffffffu, r); }
/* The sweep's registers, as globals so that the unrolled steps share
 * them without copies. */
uvec4 cs_f[CS_N]; uint cs_r[CS_N]; uint cs_n; bool cs_more;
uvec3 cs_cursor; bool cs_first; vec2 cs_P;
void cs_consider(uint r) {
    if (!cs_fragment_at(r, cs_P)) return;
    uvec3 o = uvec3(oit_fragment_key(), v_first_prim & 0x7fffffffu, r);
    if (!cs_first && !cs_less(cs_cursor, o)) return;
    if (cs_n == CS_N) {
        cs_more = true;
        if (!cs_less(o, cs_order(cs_f[CS_N - 1u], cs_r[CS_N - 1u]))) return;
        cs_n--;
    }
    uvec4 x = oit_fragment();
    /* Insertion written out, no loop: llvmpipe counts a loop entered by a
     * masked lane against its limit at every triangle of the list, and
     * constant indices keep the arrays in registers on a GPU. Slot j
     * shifts up while x orders before it; the array is sorted, so the
     * shifts stop at x's place. */
    uint pos = cs_n;
#define CS_SHIFT(j) if (j <= cs_n && cs_less(o, cs_order(cs_f[j - 1u], cs_r[j - 1u]))) { cs_f[j] = cs_f[j - 1u]; cs_r[j] = cs_r[j - 1u]; pos = j - 1u; }
    CS_SHIFT(15u) CS_SHIFT(14u) CS_SHIFT(13u) CS_SHIFT(12u) CS_SHIFT(11u)
    CS_SHIFT(10u) CS_SHIFT(9u) CS_SHIFT(8u) CS_SHIFT(7u) CS_SHIFT(6u) CS_SHIFT(5u)
    CS_SHIFT(4u) CS_SHIFT(3u) CS_SHIFT(2u) CS_SHIFT(1u)
    cs_f[pos] = x; cs_r[pos] = r;
    cs_n++;
}
/* True when the driver cut loops short before this (see above). */
bool cs_cut() {
    int i = 0;
    while (i < u_probe) i++;
    return i < u_probe;
}
uint cs_entry(uint k) { return cs_all ? k : tile_list[k]; }
void main() {
    uint g = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
    if (g >= work_hdr.w) return;
    uint t = work[g], tx = cs_tiles_x();
    ivec2 tile = ivec2(int(t % tx), int(t / tx));
    ivec2 px = tile * CS_TILE + ivec2(gl_LocalInvocationID.xy);
    if (any(lessThan(px, u_rect.xy)) || any(greaterThanEqual(px, u_rect.zw))) return;
    uint lo = t == 0u ? 0u : tile_end[t - 1u], hi = tile_end[t];
    if (lo >= hi) return;
    cs_all = hi > u_list_cap;
    cs_px = px;
    if (cs_all) { lo = 0u; hi = u_recs; }
    uint p = uint(px.y) * uint(u_size.x) + uint(px.x);
    cs_cursor = uvec3(0u);
    cs_first = true;
    if (u_resume != 0) {
        uvec4 q = resume[p];
        if (q.w == 0u) return;
        cs_cursor = q.xyz;
        cs_first = q.w == 1u;
    /* Early termination per pixel too, as the other captures drop a
     * saturated pixel's fragments; at the batch's start only, as they do. */
    } else if (u_epsilon > 0.0) {
        vec3 T = oit_state_T(p);
        if (max(T.r, max(T.g, T.b)) < u_epsilon) {
            resume[p] = uvec4(0u);
            return;
        }
    }
    precise vec2 P = (vec2(px) + 0.5) * (2.0 / vec2(u_size)) - 1.0;
    cs_P = P;
    cs_frag_coord = vec4(vec2(px) + 0.5, 0.0, 1.0);
    oit_state s = oit_state_load(p);
    bool done = false, progressed = false;
    for (;;) {
        cs_n = 0u;
        cs_more = false;
        uint k = lo;
        /* Eight triangles at a time: their coverage first (cheap, written
         * out), then the fragments of those that cover the pixel, so that the
         * shading runs as often as the most covered lane needs, not once a
         * triangle (SIMD lanes of a CPU, threads of a warp). */
        for (; k < hi; k += 8u) {
            uint bits = 0u;
#define CS_COVER(u) if (k + u < hi && cs_covers(cs_entry(k + u), P)) bits |= 1u << u;
            CS_COVER(0u) CS_COVER(1u) CS_COVER(2u) CS_COVER(3u)
            CS_COVER(4u) CS_COVER(5u) CS_COVER(6u) CS_COVER(7u)
            while (bits != 0u) {
                uint u = uint(findLSB(bits));
                bits &= bits - 1u;
                cs_consider(cs_entry(k + u));
            }
        }
        oit_state s2 = s;
        for (uint i = 0u; i < cs_n; i++) oit_composite(s2, cs_f[i]);
        if (cs_cut()) break;
        s = s2;
        s.nfrag += cs_n;
        progressed = true;
        if (!cs_more) { done = true; break; }
        cs_cursor = cs_order(cs_f[CS_N - 1u], cs_r[CS_N - 1u]);
        cs_first = false;
    }
    if (progressed) oit_state_store(p, s);
    resume[p] = uvec4(cs_cursor, done ? 0u : cs_first ? 1u : 2u);
    if (!done) {
        atomicAdd(g_pending, 1u);
        if (progressed) atomicAdd(g_progress, 1u);
        if (atomicExchange(tile_stamp[t], u_round) != u_round)
            next[atomicAdd(next_hdr.w, 1u)] = t;
    }
}
