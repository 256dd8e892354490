/* The first-K capture (capture_firstk.h). Buffers in GL row order; the
 * slots and the pass-2 table are indexed relative to their rectangle (the
 * pack's, a band's), so they scale with what a pack covers, not the frame.
 * Slot c of the rectangle's pixel q is slots[c * P + q] (P: its pixels):
 * neighbouring pixels' c-th fragments are neighbours in memory, the layout
 * a GPU's adjacent threads write and read together (on llvmpipe the same
 * speed as q * W + c within its noise: engine, 1024x1024, W = 2 and 8). */
#include "view/render/capture/capture_firstk.h"

#include "view/render/capture/capture_glsl.h"
#include "view/render/capture/capture_stencil.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_timer.h"

#include <string.h>

/* The programs' stages, glsl/firstk_*.glsl (CMakeLists.txt: with
 * glsl/firstk_totals.glsl, the pass-2 totals, and glsl/rect_index.glsl);
 * pass 1's resolves are the slot captures' (glsl/resolve.glsl, OIT_FIRSTK). */
extern const char oit_firstk_fill_fs[], oit_firstk_store_fs[], oit_firstk_resolve_cs[],
    oit_firstk_alloc_cs[], oit_firstk_segment_cs[], oit_firstk_segment_main[],
    oit_firstk_routed_resolve_cs[], oit_firstk_judge_cs[];

/* glsl/firstk_totals.glsl's bytes, and its words the host names */
#define TOTALS_BYTES 64
enum { W_SPILL_LO = 1, W_GATE = 3, W_FRAME = 8, W_GROUPS = 12 };

static const oit_glsl_program programs[OIT_FIRSTK_PROGS] = {
    [OIT_FIRSTK_FILL] = {"first-k capture fill",
                         .fs = {oit_glsl_state_io, oit_capture_saturated, oit_firstk_fill_fs}},
    [OIT_FIRSTK_STORE] = {"first-k capture store",
                          .fs = {oit_glsl_state_io, oit_capture_saturated, oit_firstk_store_fs}},
    [OIT_FIRSTK_RESOLVE] = {"first-k capture resolve",
                            .cs = {"#define OIT_FIRSTK 1\n", oit_glsl_composite, oit_glsl_state_io,
                                   oit_firstk_resolve_cs}},
    [OIT_FIRSTK_ALLOC] = {"first-k capture allocation", .cs = {oit_firstk_alloc_cs}},
    [OIT_FIRSTK_SEGMENT] = {"first-k capture segment resolve",
                            .cs = {oit_glsl_composite, oit_glsl_state_io, oit_firstk_segment_cs,
                                   oit_glsl_segment_composite, oit_firstk_segment_main}},
    [OIT_FIRSTK_ROUTED_RESOLVE] = {"first-k capture routed resolve",
                                   .cs = {"#define OIT_FIRSTK 1\n#define OIT_STENCIL 1\n",
                                          oit_glsl_composite, oit_glsl_state_io,
                                          oit_firstk_routed_resolve_cs}},
    [OIT_FIRSTK_JUDGE] = {"first-k capture judge", .cs = {oit_firstk_judge_cs}},
};

void oit_firstk_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int i = 0; i < OIT_FIRSTK_PROGS; i++)
        visit(user, &programs[i]);
}

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
