/* The first-K capture (capture_firstk.h). Buffers in GL row order; the
 * slots and the pass-2 table are indexed relative to their rectangle (the
 * pack's, a band's), so they scale with what a pack covers, not the frame.
 * Slot c of the rectangle's pixel q is slots[c * P + q] (P: its pixels):
 * neighbouring pixels' c-th fragments are neighbours in memory, the layout
 * a GPU's adjacent threads write and read together (on llvmpipe the same
 * speed as q * W + c within its noise: engine, 1024x1024, W = 2 and 8). */
#include "render/capture/capture_firstk.h"

#include "render/capture/capture_glsl.h"
#include "render/capture/capture_stencil.h"
#include "render/gl/frag_glsl.h"
#include "render/gl/gpu_timer.h"

#include <string.h>

/* The pass-2 totals at a binding no other program of a pack uses while
 * they are live: overflowed pixels, their fragments as 64 bits, the gate
 * of pass 2's draw (ahead mode), the GL rect that holds them (x0, y0, x1,
 * y1; exclusive ends), so that pass 2 works only there; then the frame's
 * words (oit_firstk_begin) and pass 2's dispatch (ahead mode). */
#define TOTALS_BLOCK                                                        \
    "layout(std430, binding = OIT_BIND_SUMS) buffer Spill { uint spill_pixels; uint spill_lo; "    \
    "uint spill_hi; uint gate; uint box[4]; uint frame_short; uint need; "  \
    "uint second_pixels; uint second_packs; uvec4 groups; };\n"            \
    "ivec4 oit_box() { return ivec4(box[0], box[1], box[2], box[3]); }\n" \
    "void oit_spill(uvec2 px) {\n"                                        \
    "    atomicAdd(spill_pixels, 1u);\n"                                  \
    "    atomicMin(box[0], px.x); atomicMin(box[1], px.y);\n"             \
    "    atomicMax(box[2], px.x + 1u); atomicMax(box[3], px.y + 1u);\n"   \
    "}\n"
/* The end of a pass-1 resolve: pixel p's n fragments, each read by LOAD
 * (a GLSL expression of i), sorted in registers and composited into its
 * state; its count goes back to zero for the next pack. */
#define RESOLVE_SORTED(LOAD)                                                \
    "    uvec4 f[16];\n"                                                   \
    "    for (uint i = 0u; i < n; i++) {\n"                                \
    "        uvec4 x = " LOAD ";\n"                                        \
    "        OIT_SORTED_INSERT(f, i, x)\n"                                 \
    "    }\n"                                                              \
    "    oit_state s = oit_state_load(p);\n"                               \
    "    for (uint i = 0u; i < n; i++) oit_composite(s, f[i]);\n"          \
    "    s.nfrag += n;\n"                                                  \
    "    oit_state_store(p, s);\n"                                         \
    "    counts[p] = 0u;\n"                                                \
    "}\n"
/* Pass 2's own rect: the pack's overflow box (ahead mode, dispatched by
 * the GPU over it) or the band u_rect the host gave. */
#define PASS2_RECT                                                          \
    "uniform int u_from_box;\n"                                            \
    "ivec4 oit_pass2_rect() { return u_from_box != 0 ? oit_box() : u_rect; }\n"
#define RECT_INDEX                                                          \
    "uint oit_rect_index(ivec2 px, ivec4 r) {\n"                          \
    "    return uint((px.y - r.y) * (r.z - r.x) + (px.x - r.x));\n"       \
    "}\n"

/* Pass 1: every fragment counted, the first u_W of a pixel kept. */
static const char fill_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };\n"
    TOTALS_BLOCK RECT_INDEX
    "uniform int u_W;\n"
    "uniform ivec4 u_tile;\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    if (oit_behind_opaque()) discard;\n"
    "    uint p = oit_pixel_index();\n"
    "    if (oit_saturated(p)) discard;\n"
    "    uint q = oit_rect_index(ivec2(gl_FragCoord.xy), u_tile);\n"
    "    uint P = uint((u_tile.z - u_tile.x) * (u_tile.w - u_tile.y));\n"
    "    uint c = atomicAdd(counts[p], 1u);\n"
    "    if (c < uint(u_W)) slots[c * P + q] = oit_fragment();\n"
    "    else if (c == uint(u_W)) oit_spill(uvec2(gl_FragCoord.xy));\n"
    "}\n";

/* Pass 1's resolve: pixels of at most u_W fragments, from their slots. An
 * overflowed pixel keeps its count: pass 2 takes it whole. */
static const char resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Slots { uvec4 slots[]; };\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    "uniform int u_W;\n"
    RECT_INDEX
    "void main() {\n"
    "    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_rect.z || px.y >= u_rect.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = counts[p];\n"
    "    if (n == 0u || n > uint(u_W)) return;\n"
    "    uint q = oit_rect_index(px, u_rect);\n"
    "    uint P = uint((u_rect.z - u_rect.x) * (u_rect.w - u_rect.y));\n"
    RESOLVE_SORTED("slots[i * P + q]");

/* Pass 1's resolve when the stencil routed it: the same for the pixels of
 * at most u_W fragments, from the samples; a pixel of more is found by its
 * exact count and flagged here (the fill cannot: it does not know a
 * pixel's last fragment), into the same spill totals and box the array
 * fill writes. */
static const char routed_resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;\n"
    TOTALS_BLOCK
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    "uniform int u_W;\n"
    "void main() {\n"
    "    ivec2 px = u_rect.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_rect.z || px.y >= u_rect.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = counts[p];\n"
    "    if (n == 0u) return;\n"
    "    if (n > uint(u_W)) {\n"
    "        oit_spill(uvec2(px));\n"
    "        return;\n"
    "    }\n"
    RESOLVE_SORTED("texelFetch(u_samples, px, int(i))");

/* Pass 2, over a band: each overflowed pixel a segment of its count (the
 * order of segments does not matter, only that they do not overlap). */
static const char alloc_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) writeonly buffer Table { uvec2 table[]; };\n"
    TOTALS_BLOCK RECT_INDEX
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    PASS2_RECT
    "uniform int u_W;\n"
    "uniform uint u_cap;\n" /* fragments the store holds */
    "void main() {\n"
    "    ivec4 b = oit_pass2_rect();\n"
    "    ivec2 px = b.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= b.z || px.y >= b.w) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = counts[p];\n"
    "    uvec2 e = uvec2(0u);\n"
    "    if (n > uint(u_W)) {\n"
    "        uint old = atomicAdd(spill_lo, n);\n"
    "        if (old + n < old) atomicAdd(spill_hi, 1u);\n"
    "        e = uvec2(old, n);\n"
    /* past the store: left out, the frame flagged short (the verdict) */
    "        if (old + n < old || old + n > u_cap) { e = uvec2(0u); counts[p] = 0u; }\n"
    "    }\n"
    "    table[oit_rect_index(px, u_rect)] = e;\n"
    "}\n";

/* Ahead mode's judge, one invocation. Step 0, after pass 1's resolve: pass
 * 2's dispatch over the overflow box (none when nothing overflowed). Step
 * 1, after the allocation: the gate of the store's draw, the frame's
 * figures, and its flag when the store proved short. */
static const char judge_cs[] =
    "layout(local_size_x = 1) in;\n"
    TOTALS_BLOCK
    "uniform int u_step;\n"
    "uniform uint u_cap;\n"
    "void main() {\n"
    "    if (u_step == 0) {\n"
    "        bool any = spill_pixels != 0u;\n"
    "        groups = uvec4(any ? (box[2] - box[0] + 7u) / 8u : 0u,\n"
    "                       any ? (box[3] - box[1] + 7u) / 8u : 0u, 1u, 0u);\n"
    "        return;\n"
    "    }\n"
    "    gate = spill_pixels != 0u ? 1u : 0u;\n"
    "    if (spill_hi != 0u || spill_lo > u_cap) frame_short = 1u;\n"
    "    need = max(need, spill_hi != 0u ? 0xffffffffu : spill_lo);\n"
    "    second_pixels += spill_pixels;\n"
    "    second_packs += gate;\n"
    "}\n";

/* Pass 2's store: only pixels with a segment, counted back down to 0. */
static const char store_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Table { uvec2 table[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Frags { uvec4 frags[]; };\n"
    TOTALS_BLOCK RECT_INDEX
    "uniform ivec4 u_tile;\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    ivec4 b = oit_box();\n" /* the table holds only the box's pixels */
    "    if (px.x < b.x || px.y < b.y || px.x >= b.z || px.y >= b.w) discard;\n"
    "    if (oit_clipped()) discard;\n"
    "    if (oit_behind_opaque()) discard;\n"
    "    uvec2 e = table[oit_rect_index(px, u_tile)];\n"
    "    uint p = oit_pixel_index();\n"
    "    if (e.y == 0u || oit_saturated(p)) discard;\n"
    "    uint c = atomicAdd(counts[p], 0xffffffffu);\n"
    "    if (c != 0u && c <= e.y) frags[e.x + c - 1u] = oit_fragment();\n"
    "}\n";

/* Pass 2's resolve: before oit_glsl_segment_composite, segment_main after. */
static const char segment_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Table { uvec2 table[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 12) uniform ivec4 u_rect;\n"
    TOTALS_BLOCK PASS2_RECT RECT_INDEX;

static const char segment_main[] =
    "void main() {\n"
    "    ivec4 b = oit_pass2_rect();\n"
    "    ivec2 px = b.xy + ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= b.z || px.y >= b.w) return;\n"
    "    uvec2 e = table[oit_rect_index(px, u_rect)];\n"
    "    if (e.y == 0u) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    oit_state s = oit_state_load(p);\n"
    "    oit_segment_composite(s, e.x, e.y);\n"
    "    s.nfrag += e.y;\n"
    "    oit_state_store(p, s);\n"
    "}\n";

/* TOTALS_BLOCK's bytes, and its words the host names */
#define TOTALS_BYTES 64
enum { W_SPILL_LO = 1, W_GATE = 3, W_FRAME = 8, W_GROUPS = 12 };

static const oit_glsl_program programs[OIT_FIRSTK_PROGS] = {
    [OIT_FIRSTK_FILL] = {"first-k capture fill",
                         .fs = {oit_glsl_state_io, oit_capture_saturated, fill_fs}},
    [OIT_FIRSTK_STORE] = {"first-k capture store",
                          .fs = {oit_glsl_state_io, oit_capture_saturated, store_fs}},
    [OIT_FIRSTK_RESOLVE] = {"first-k capture resolve",
                            .cs = {oit_glsl_composite, oit_glsl_state_io, resolve_cs}},
    [OIT_FIRSTK_ALLOC] = {"first-k capture allocation", .cs = {alloc_cs}},
    [OIT_FIRSTK_SEGMENT] = {"first-k capture segment resolve",
                            .cs = {oit_glsl_composite, oit_glsl_state_io, segment_cs,
                                   oit_glsl_segment_composite, segment_main}},
    [OIT_FIRSTK_ROUTED_RESOLVE] = {"first-k capture routed resolve",
                                   .cs = {oit_glsl_composite, oit_glsl_state_io,
                                          routed_resolve_cs}},
    [OIT_FIRSTK_JUDGE] = {"first-k capture judge", .cs = {judge_cs}},
};

void oit_firstk_route(oit_firstk *k, oit_stencil_target *t, GLuint fill)
{
    k->routed = t;
    k->routed_fill = fill;
}

oit_status oit_firstk_init(oit_firstk *k, int K, oit_program_cache *pc,
                           void (*built)(void *built_ctx), void *built_ctx, oit_error *err)
{
    memset(k, 0, sizeof *k);
    k->K = K;
    k->budget = k->store_budget = UINT64_MAX;
    k->pc = pc;
    k->built = built;
    k->built_ctx = built_ctx;
    glCreateBuffers(1, &k->totals);
    glNamedBufferData(k->totals, TOTALS_BYTES, NULL, GL_DYNAMIC_COPY);
    oit_gl_poison_buffer(k->totals);
    return oit_gl_check("first-k capture: set-up", err);
}

/* Builds those of progs[0..n) not built yet, and tells the owner. */
static oit_status need(oit_firstk *k, const int *progs, int n, oit_error *err)
{
    int made = 0;
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++)
        if (!k->prog[progs[i]]) {
            s = oit_glsl_programs_build(k->pc, &programs[progs[i]], 1, &k->prog[progs[i]], err);
            made = 1;
        }
    if (made && s == OIT_OK && k->built)
        k->built(k->built_ctx);
    return s;
}

void oit_firstk_release(oit_firstk *k)
{
    oit_glsl_programs_delete(k->prog, OIT_FIRSTK_PROGS);
    GLuint bufs[3] = {k->store, k->table, k->totals};
    glDeleteBuffers(3, bufs);
    memset(k, 0, sizeof *k);
}

uint64_t oit_firstk_bytes(const oit_firstk *k)
{
    return k->store_cap + k->table_cap + TOTALS_BYTES;
}

static uint64_t rect_pixels(const int r[4])
{
    return (uint64_t)(r[2] - r[0]) * (uint64_t)(r[3] - r[1]);
}

int oit_firstk_slots(const oit_firstk *k, const int r[4])
{
    if (k->routed)
        return k->routed->K;
    uint64_t fit = k->budget / 16 / rect_pixels(r);
    int W = fit < (uint64_t)k->K ? (int)fit : k->K;
    return W >= 2 ? W : 0;
}

static void set_int(GLuint prog, const char *name, int v)
{
    glProgramUniform1i(prog, glGetUniformLocation(prog, name), v);
}

static void set_rect(GLuint prog, const char *name, const int r[4])
{
    glProgramUniform4i(prog, glGetUniformLocation(prog, name), r[0], r[1], r[2], r[3]);
}

static void dispatch_rect(GLuint prog, const int r[4])
{
    glUseProgram(prog);
    set_rect(prog, "u_rect", r);
    glDispatchCompute(oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                      oit_gl_groups((uint64_t)(r[3] - r[1]), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

static void bind_frame(const oit_firstk *k, const oit_counted_frame *f)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->store);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->table);
}

/* Zero counts, a closed gate, an empty box. */
static void clear_totals(const oit_firstk *k)
{
    static const GLuint start[8] = {0, 0, 0, 0, 0xffffffffu, 0xffffffffu, 0, 0};
    glNamedBufferSubData(k->totals, 0, sizeof start, start);
}

void oit_firstk_begin(oit_firstk *k)
{
    static const GLuint zero[4] = {0, 0, 0, 0};
    glNamedBufferSubData(k->totals, W_FRAME * 4, sizeof zero, zero);
    k->ended_short = 0;
    k->seen = 0;
}

void oit_firstk_ended(oit_firstk *k)
{
    uint64_t seen = k->seen;
    if (k->ahead) {
        /* after the final read-back: the GPU is done, nothing waits */
        GLuint w[4];
        oit_host_read(NULL, k->totals, W_FRAME * 4, sizeof w, w);
        k->ended_short = w[0] != 0;
        k->second_pixels = w[2];
        k->second_packs = w[3];
        seen = w[1];
    }
    /* room for the most a pack needed, and an eighth more, so that a view
     * that deepens a little does not draw its frames twice */
    uint64_t need = seen + seen / 8;
    k->need = need > k->need ? need : k->need;
    k->measured = 1;
}

/* Pass 1 over r with W slots a pixel, and its resolve; t receives the
 * totals (a read-back: whether pass 2 is needed, and where; NULL: none,
 * the GPU decides). */
static oit_status first_pass(oit_firstk *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4], int W,
                             GLuint t[8], oit_error *err)
{
    uint64_t bytes = rect_pixels(r) * 16 * (uint64_t)W;
    oit_status s = oit_gl_check_ssbo_size(bytes, "first-k capture: a pack's slots", err);
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->store, &k->store_cap, bytes, "first-k capture slots", err);
    if (s != OIT_OK)
        return s;
    clear_totals(k);
    bind_frame(k, f);
    set_int(k->prog[OIT_FIRSTK_FILL], "u_W", W);
    set_rect(k->prog[OIT_FIRSTK_FILL], "u_tile", r);
    set_int(k->prog[OIT_FIRSTK_RESOLVE], "u_W", W);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS1);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, k->prog[OIT_FIRSTK_FILL], f->draws,
                            meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_RESOLVE);
    if (k->counts_copy)
        glCopyNamedBufferSubData(f->counts, k->counts_copy, 0, 0,
                                 (GLsizeiptr)((uint64_t)f->width * f->height * 4));
    dispatch_rect(k->prog[OIT_FIRSTK_RESOLVE], r);
    if (t)
        oit_host_read(f->waits, k->totals, 0, 32, t);
    return oit_gl_check("first-k capture: pass 1", err);
}

/* Pass 1 routed by the stencil (oit_firstk_route): the target's fill over
 * r, then the resolve from its samples, which also finds the overflowed
 * pixels; t as first_pass's. */
static oit_status routed_first_pass(oit_firstk *k, const oit_counted_frame *f,
                                    const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                    int W, GLuint t[8], oit_error *err)
{
    clear_totals(k);
    bind_frame(k, f);
    oit_stencil_target_fill(k->routed, r, k->routed_fill, f->draws, meshes, n);
    glBindTextureUnit(OIT_TEX_SAMPLES, k->routed->colour);
    set_int(k->prog[OIT_FIRSTK_ROUTED_RESOLVE], "u_W", W);
    dispatch_rect(k->prog[OIT_FIRSTK_ROUTED_RESOLVE], r);
    if (t)
        oit_host_read(f->waits, k->totals, 0, 32, t);
    return oit_gl_check("first-k capture: routed pass 1", err);
}

/* Segments for the overflowed pixels of the band b; *frags receives their
 * fragments. */
static oit_status allocate(oit_firstk *k, const oit_counted_frame *f, const int b[4], int W,
                           uint64_t *frags, oit_error *err)
{
    oit_status s = oit_gl_buffer_reserve(&k->table, &k->table_cap, rect_pixels(b) * 8,
                                         "first-k capture segment table", err);
    if (s != OIT_OK)
        return s;
    /* the fragments' count from 0; the box stays, the store's draw tests it */
    static const GLuint zero[2] = {0, 0};
    glNamedBufferSubData(k->totals, W_SPILL_LO * 4, sizeof zero, zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->table);
    GLuint a = k->prog[OIT_FIRSTK_ALLOC];
    set_int(a, "u_W", W);
    set_int(a, "u_from_box", 0);
    glProgramUniform1ui(a, glGetUniformLocation(a, "u_cap"), 0xffffffffu);
    dispatch_rect(a, b);
    GLuint t[3];
    oit_host_read(f->waits, k->totals, 0, 12, t);
    *frags = (uint64_t)t[2] << 32 | t[1];
    k->seen = *frags > k->seen ? *frags : k->seen;
    if (*frags > UINT32_MAX)
        return oit_error_set(err, OIT_ERR_NOMEM, "first-k capture: %llu fragments in one "
                             "band, more than 32-bit offsets address",
                             (unsigned long long)*frags);
    return oit_gl_check("first-k capture: allocation", err);
}

/* Pass 2 over the band b whose segments are allocated: store, then sort
 * and composite each segment. */
static oit_status second_pass(oit_firstk *k, const oit_counted_frame *f,
                              const oit_gpu_mesh *const *meshes, int n, const int b[4],
                              uint64_t frags, oit_error *err)
{
    oit_status s = oit_gl_check_ssbo_size(frags * 16, "first-k capture: a band's overflowed "
                                          "fragments", err);
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->store, &k->store_cap, frags * 16,
                                  "first-k capture fragments", err);
    if (s != OIT_OK)
        return s;
    bind_frame(k, f);
    set_rect(k->prog[OIT_FIRSTK_STORE], "u_tile", b);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS2);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, k->prog[OIT_FIRSTK_STORE], f->draws,
                            meshes, n, b);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_RESOLVE);
    set_int(k->prog[OIT_FIRSTK_SEGMENT], "u_from_box", 0);
    dispatch_rect(k->prog[OIT_FIRSTK_SEGMENT], b);
    k->second_draws++;
    return oit_gl_check("first-k capture: pass 2", err);
}

/* Pass 2 over r in bands of rows whose overflowed fragments fit the store
 * (the store budget, or what the store already holds, within one storage
 * binding); a band is halved
 * while it does not, down to one row, which gets what it needs. */
static oit_status second_passes(oit_firstk *k, const oit_counted_frame *f,
                                const oit_gpu_mesh *const *meshes, int n, const int r[4], int W,
                                oit_error *err)
{
    uint64_t room = k->store_budget > k->store_cap ? k->store_budget : k->store_cap;
    room = room < f->bind ? room : f->bind;
    int rows = r[3] - r[1];
    oit_status s = OIT_OK;
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS2);
    for (int y = r[1]; y < r[3] && s == OIT_OK;) {
        rows = rows < r[3] - y ? rows : r[3] - y;
        int b[4] = {r[0], y, r[2], y + rows};
        uint64_t frags = 0;
        s = allocate(k, f, b, W, &frags, err);
        if (s == OIT_OK && frags * 16 > room && rows > 1) {
            rows = (rows + 1) / 2;
            continue;
        }
        if (s == OIT_OK && frags > 0)
            s = second_pass(k, f, meshes, n, b, frags, err);
        y += rows;
    }
    return s;
}

/* One step of the judge (judge_cs) over the store's cap fragments. */
static void judge(const oit_firstk *k, int step, uint64_t cap)
{
    GLuint j = k->prog[OIT_FIRSTK_JUDGE];
    set_int(j, "u_step", step);
    glProgramUniform1ui(j, glGetUniformLocation(j, "u_cap"), (GLuint)cap);
    glUseProgram(j);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

/* prog dispatched over the overflow box, as the judge sized it. */
static void dispatch_box(const oit_firstk *k, GLuint prog, const int r[4])
{
    glUseProgram(prog);
    set_rect(prog, "u_rect", r);
    set_int(prog, "u_from_box", 1);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, k->totals);
    glDispatchComputeIndirect(W_GROUPS * 4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Pass 2 over r without the host: segments allocated over the overflow
 * box in a store sized ahead (the need of earlier frames, at least what
 * the slots took), the store's draw gated and the segments resolved by
 * what the GPU found; a pack whose overflow outgrows the store leaves it
 * out and flags the frame short (oit_firstk_ended). */
static oit_status ahead_pass(oit_firstk *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4], int W,
                             oit_error *err)
{
    uint64_t cap = k->store_cap / 16 > k->need ? k->store_cap / 16 : k->need;
    cap = cap < f->bind / 16 ? cap : f->bind / 16;
    cap = cap < UINT32_MAX ? cap : UINT32_MAX;
    oit_status s = oit_gl_buffer_reserve(&k->store, &k->store_cap, cap * 16,
                                         "first-k capture fragments", err);
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->table, &k->table_cap, rect_pixels(r) * 8,
                                  "first-k capture segment table", err);
    if (s != OIT_OK)
        return s;
    bind_frame(k, f);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS2);
    judge(k, 0, cap);
    GLuint a = k->prog[OIT_FIRSTK_ALLOC];
    set_int(a, "u_W", W);
    glProgramUniform1ui(a, glGetUniformLocation(a, "u_cap"), (GLuint)cap);
    dispatch_box(k, a, r);
    judge(k, 1, cap);
    GLuint st = k->prog[OIT_FIRSTK_STORE];
    set_rect(st, "u_tile", r);
    oit_glsl_draw_scissored_gated(f->fbo, f->width, f->height, st, f->draws, meshes, n, r,
                                  k->totals, W_GATE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_RESOLVE);
    dispatch_box(k, k->prog[OIT_FIRSTK_SEGMENT], r);
    return oit_gl_check("first-k capture: pass 2 ahead", err);
}

oit_status oit_firstk_batch(oit_firstk *k, const oit_counted_frame *f,
                            const oit_gpu_mesh *const *meshes, int n, const int r[4],
                            oit_error *err)
{
    int W = oit_firstk_slots(k, r);
    if (W < 2)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "first-k capture: a %dx%d rectangle "
                             "leaves fewer than 2 slots a pixel in the slot budget",
                             r[2] - r[0], r[3] - r[1]);
    static const int routed[] = {OIT_FIRSTK_ROUTED_RESOLVE},
                     array[] = {OIT_FIRSTK_FILL, OIT_FIRSTK_RESOLVE},
                     second[] = {OIT_FIRSTK_ALLOC, OIT_FIRSTK_STORE, OIT_FIRSTK_SEGMENT},
                     ahead[] = {OIT_FIRSTK_ALLOC, OIT_FIRSTK_STORE, OIT_FIRSTK_SEGMENT,
                                OIT_FIRSTK_JUDGE};
    if (k->ahead) {
        /* every program before the first pass: none is built between the
         * passes of a pack */
        oit_status s = k->routed ? need(k, routed, 1, err) : need(k, array, 2, err);
        if (s == OIT_OK)
            s = need(k, ahead, 4, err);
        if (s == OIT_OK)
            s = k->routed ? routed_first_pass(k, f, meshes, n, r, W, NULL, err)
                          : first_pass(k, f, meshes, n, r, W, NULL, err);
        return s == OIT_OK ? ahead_pass(k, f, meshes, n, r, W, err) : s;
    }
    GLuint t[8] = {0};
    oit_status s = k->routed ? need(k, routed, 1, err) : need(k, array, 2, err);
    if (s == OIT_OK)
        s = k->routed ? routed_first_pass(k, f, meshes, n, r, W, t, err)
                      : first_pass(k, f, meshes, n, r, W, t, err);
    if (s != OIT_OK || t[0] == 0)
        return s;
    k->second_pixels += t[0];
    k->second_packs++;
    /* the overflowed pixels' box, within r (it is, unless GL misbehaved) */
    int box[4] = {(int)t[4] > r[0] ? (int)t[4] : r[0], (int)t[5] > r[1] ? (int)t[5] : r[1],
                  (int)t[6] < r[2] ? (int)t[6] : r[2], (int)t[7] < r[3] ? (int)t[7] : r[3]};
    if (box[2] <= box[0] || box[3] <= box[1])
        return oit_error_set(err, OIT_ERR_GL, "first-k capture: %u overflowed pixels outside "
                             "the pack's rectangle", t[0]);
    s = need(k, second, 3, err);
    return s == OIT_OK ? second_passes(k, f, meshes, n, box, W, err) : s;
}
