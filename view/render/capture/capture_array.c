/* The array backend (OIT_CAPTURE_ARRAY, capture.h): K slots a pixel filled
 * through an atomic counter, then a resolve over the batch's rect that
 * sorts each pixel's <= K fragments and composites them into the state the
 * frame carries; and the tiled batches (wide parts, or a slot budget below
 * the full frame), which the stencil backend takes for its wide parts too. */
#include "view/render/capture/capture_backend.h"

#include "view/render/capture/capture_glsl.h"

enum { SLOTS_FILL, SLOTS_RESOLVE, SLOTS_PROGS };

oit_status oit_capture_slots_init(oit_capture_slots *s, oit_program_cache *pc,
                                  const oit_glsl_program programs[2], oit_error *err)
{
    GLuint progs[SLOTS_PROGS] = {0};
    oit_status st = oit_glsl_programs_build(pc, programs, SLOTS_PROGS, progs, err);
    s->fill = progs[SLOTS_FILL];
    s->resolve = progs[SLOTS_RESOLVE];
    return st;
}

void oit_capture_slots_release(oit_capture_slots *s)
{
    GLuint progs[SLOTS_PROGS] = {s->fill, s->resolve};
    oit_glsl_programs_delete(progs, SLOTS_PROGS);
    for (int i = 0; i < 2; i++)
        oit_glsl_programs_delete(s->tile_prog[i], 2);
    glDeleteBuffers(1, &s->buf);
}

void oit_capture_slots_uniforms(const oit_capture *c, oit_capture_slots *s)
{
    GLuint progs[SLOTS_PROGS] = {s->fill, s->resolve};
    oit_capture_set_frame_uniforms(c, progs, SLOTS_PROGS);
}

void oit_capture_slots_epsilon(oit_capture_slots *s, float e)
{
    oit_glsl_set_epsilon_all(&s->fill, 1, e);
    for (int i = 0; i < 2; i++)
        if (s->tile_prog[i][0])
            oit_glsl_set_epsilon_all(&s->tile_prog[i][0], 1, e); /* its fill */
}

/* ---- tiled batches ----------------------------------------------------------- */

/* The fragments a pixel that tiled pair 0 sorts: more take pair 1. */
#define WIDE_SHORT 16

/* Program pair i: the fill, and the resolve that sorts up to WIDE_SHORT
 * fragments a pixel (0) or up to OIT_CAPTURE_MAX_LAYERS (1: registers a
 * GPU would rather not spend on K). */
static void tiled_pair(int i, oit_glsl_program pair[2])
{
    static const char *const wide[2] = {
        "#define OIT_WIDE " OIT_GLSL_STR(WIDE_SHORT) "\n",
        "#define OIT_WIDE " OIT_GLSL_STR(OIT_CAPTURE_MAX_LAYERS) "\n"};
    pair[0] = (oit_glsl_program){"capture tiled fill",
                                 .fs = {oit_glsl_state_io, oit_capture_wide_fs}};
    pair[1] = (oit_glsl_program){"capture tiled resolve",
                                 .cs = {wide[i], oit_glsl_composite, oit_glsl_state_io,
                                        oit_capture_resolve_cs}};
}

static oit_status tiled_programs(const oit_capture *c, oit_capture_slots *s, int i,
                                 oit_error *err)
{
    GLuint *progs = s->tile_prog[i];
    if (!progs[0]) {
        oit_glsl_program pair[2];
        tiled_pair(i, pair);
        oit_status st = oit_glsl_programs_build(c->programs, pair, 2, progs, err);
        if (st != OIT_OK)
            return st;
    }
    for (int k = 0; k < 2; k++) {
        oit_glsl_set_view(progs[k], &c->view);
        oit_glsl_set_opaque(progs[k], &c->opaque);
        glProgramUniform1i(progs[k], glGetUniformLocation(progs[k], "u_K"), c->K);
    }
    glProgramUniform1f(progs[0], glGetUniformLocation(progs[0], "u_epsilon"), c->frame.applied);
    return OIT_OK;
}

/* One tile: fill its pixels' W slots, then resolve them. */
static void tile_pass(oit_capture *c, const oit_capture_slots *s,
                      const oit_gpu_mesh *const *meshes, int n, int W, int i, const int t[4])
{
    GLuint fp = s->tile_prog[i][0], rp = s->tile_prog[i][1];
    glProgramUniform1i(fp, glGetUniformLocation(fp, "u_W"), W);
    glProgramUniform1i(rp, glGetUniformLocation(rp, "u_W"), W);
    glProgramUniform4i(fp, glGetUniformLocation(fp, "u_tile"), t[0], t[1], t[2], t[3]);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_PASS1);
    oit_capture_draw_scissored(c, fp, meshes, n, t);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_RESOLVE);
    oit_capture_resolve(rp, t);
}

/* The batch over tiles of the GL rect r small enough that W slots a pixel
 * fit the slots buffer: one draw of the batch per tile. */
static oit_status tiled_batch(oit_capture *c, oit_capture_slots *s,
                              const oit_gpu_mesh *const *meshes, int n, const int r[4], int W,
                              oit_error *err)
{
    uint64_t slots = s->tiled ? s->cap / 16
                              : (uint64_t)c->view.width * c->view.height * (uint64_t)c->K;
    slots = slots > (uint64_t)W ? slots : (uint64_t)W;
    int i = W > WIDE_SHORT;
    oit_status st = oit_capture_reserve(c, &s->buf, &s->cap, slots * 16, "capture slots", err);
    if (st == OIT_OK)
        st = tiled_programs(c, s, i, err);
    if (st != OIT_OK)
        return st;
    oit_capture_bind_buffers(c);
    uint64_t tile_pixels = s->cap / 16 / (uint64_t)W;
    int rw = r[2] - r[0];
    int tw = (uint64_t)rw < tile_pixels ? rw : (int)tile_pixels;
    uint64_t rows = tile_pixels / (uint64_t)tw;
    int th = rows < (uint64_t)(r[3] - r[1]) ? (int)rows : r[3] - r[1];
    for (int y = r[1]; y < r[3]; y += th)
        for (int x = r[0]; x < r[2]; x += tw) {
            int t[4] = {x, y, x + tw < r[2] ? x + tw : r[2], y + th < r[3] ? y + th : r[3]};
            tile_pass(c, s, meshes, n, W, i, t);
        }
    return oit_gl_check("capture: tiled batch", err);
}

oit_status oit_capture_slots_tiled(oit_capture *c, oit_capture_slots *s,
                                   const oit_gpu_mesh *const *meshes, int n, const int rect[4],
                                   int layers, oit_error *err)
{
    if (layers > OIT_CAPTURE_MAX_LAYERS)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: a batch of %d layers, more than "
                             "%d", layers, OIT_CAPTURE_MAX_LAYERS);
    int r[4] = {0}, empty = 1;
    oit_status st = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (st != OIT_OK || empty)
        return st;
    return tiled_batch(c, s, meshes, n, r, layers > c->K ? layers : c->K, err);
}

/* ---- the array backend ------------------------------------------------------- */

/* Its K-slot fill and resolve. */
static void array_programs(oit_glsl_program programs[2])
{
    programs[0] =
        (oit_glsl_program){"capture fill", .fs = {oit_glsl_state_io, oit_capture_array_fs}};
    programs[1] = (oit_glsl_program){
        "capture resolve", .cs = {oit_glsl_composite, oit_glsl_state_io, oit_capture_resolve_cs}};
}

void oit_capture_array_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_glsl_program p[2];
    array_programs(p);
    visit(user, &p[0]);
    visit(user, &p[1]);
    for (int i = 0; i < 2; i++) {
        tiled_pair(i, p);
        if (i == 0)
            visit(user, &p[0]); /* the same fill for both */
        visit(user, &p[1]);
    }
}

static oit_status array_create(oit_capture *c, int stencil_k, oit_error *err)
{
    oit_glsl_program programs[2];
    array_programs(programs);
    return oit_capture_slots_init(c->be, c->programs, programs, err);
}

static void array_destroy(void *be)
{
    oit_capture_slots_release(be);
}

/* The slots are local to each batch's rectangle and grow to the largest
 * rectangle's K slots a pixel (array_batch), at most K for every pixel;
 * under a slot budget smaller than that they hold the budget's worth (at
 * least one row) and every batch goes through tiles. The output, needed
 * only at the frame's end, passes through the idle slots, in bands of rows
 * when they hold less. */
static oit_status array_begin(oit_capture *c, oit_error *err)
{
    oit_capture_slots *s = c->be;
    const oit_view *v = &c->view;
    uint64_t full = (uint64_t)v->width * v->height * (uint64_t)c->K * 16;
    uint64_t row = (uint64_t)v->width * c->K * 16;
    /* One storage binding is a slot budget too: slots past it would be
     * written where the shader cannot address them. */
    uint64_t bind = c->frame.bind, sb = c->set.slot_budget;
    uint64_t budget = sb && sb < bind ? sb : bind;
    s->tiled = full > budget;
    uint64_t slots = !s->tiled ? row : budget > row ? budget : row;
    oit_status st = oit_gl_check_ssbo_size(slots, "capture: the frame's largest buffer", err);
    if (st == OIT_OK)
        st = oit_capture_reserve(c, &s->buf, &s->cap, slots, "capture slots", err);
    return st;
}

static void array_uniforms(oit_capture *c)
{
    oit_capture_slots_uniforms(c, c->be);
}

static void array_epsilon(oit_capture *c, float e)
{
    oit_capture_slots_epsilon(c->be, e);
}

/* The slots are also the frame's output (read_output in capture.c). */
static void array_bind(const oit_capture *c)
{
    const oit_capture_slots *s = c->be;
    oit_capture_bind_within(c, OIT_BIND_OUT, s->buf, s->cap);
    if (s->buf)
        oit_capture_bind_within(c, OIT_BIND_FRAGS, s->buf, s->cap);
}

/* K slots a pixel of the GL rect r, indexed from its corner: a batch pays
 * for what it covers, not the frame. */
static oit_status array_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                              const int rect[4], int layers, oit_error *err)
{
    oit_capture_slots *s = c->be;
    if (layers > c->K || s->tiled)
        return oit_capture_slots_tiled(c, s, meshes, n, rect, layers, err);
    int r[4] = {0}, empty = 1;
    oit_status st = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (st != OIT_OK || empty)
        return st;
    uint64_t pixels = (uint64_t)(r[2] - r[0]) * (uint64_t)(r[3] - r[1]);
    st = oit_capture_reserve(c, &s->buf, &s->cap, pixels * (uint64_t)c->K * 16,
                             "capture slots", err);
    glProgramUniform4i(s->fill, glGetUniformLocation(s->fill, "u_tile"), r[0], r[1], r[2], r[3]);
    if (st != OIT_OK)
        return st;
    oit_capture_bind_buffers(c);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_PASS1);
    oit_capture_draw_scissored(c, s->fill, meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_RESOLVE);
    oit_capture_resolve(s->resolve, r);
    return oit_gl_check("capture: batch", err);
}

/* Untiled, the frame's output fits where K slots a pixel would: one band,
 * one pass. */
static oit_status array_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                            oit_error *err)
{
    oit_capture_slots *s = c->be;
    oit_status st = OIT_OK;
    if (!s->tiled)
        st = oit_capture_reserve(c, &s->buf, &s->cap, oit_capture_within_binding(c, want, row),
                                 "capture slots", err);
    *out = (oit_capture_out){s->buf, s->cap};
    return st;
}

static uint64_t array_bytes(const void *be)
{
    return ((const oit_capture_slots *)be)->cap;
}

static void array_stats(const oit_capture *c, oit_frame_stats *stats)
{
    stats->capture = c->ops->name;
    stats->capture_slots = "array";
}

OIT_CAPTURE_OPS(array, OIT_CAPTURE_ARRAY, "array", oit_capture_slots, NULL, NULL, NULL);
