/* Stencil-routed K-sample target (capture_stencil.h). The routing draw runs
 * with multisampling off, as in the paper: each fragment then covers every
 * sample, and only the per-sample stencil test decides where it lands. That
 * holds only where the fill shader runs once a pixel and the per-sample
 * tests run per sample: the sample mode and the self-test check both. */
#include "view/render/capture/capture_stencil.h"

#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/glsl_bindings.h"

#include <EGL/egl.h>
#include <stdlib.h>
#include <string.h>

/* ---- the sample mode ------------------------------------------------------ */

static oit_status check_limits(int K, oit_error *err)
{
    GLint color = 0, integer = 0, depth = 0, fbo = 0;
    glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &color);
    glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &integer);
    glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depth);
    glGetIntegerv(GL_MAX_SAMPLES, &fbo);
    int limit = integer;
    limit = color < limit ? color : limit;
    limit = depth < limit ? depth : limit;
    limit = fbo < limit ? fbo : limit;
    if (K > limit)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "stencil capture: K=%d exceeds the multisample limit %d "
                             "(GL_MAX_INTEGER_SAMPLES=%d, GL_MAX_SAMPLES=%d)",
                             K, limit, integer, fbo);
    return OIT_OK;
}

static int has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const GLubyte *e = glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && !strcmp((const char *)e, name))
            return 1;
    }
    return 0;
}

/* The driver's sample query, or NULL where it has none. Through EGL: an
 * extension's entry point is not a symbol of the GL library. */
static PFNGLGETINTERNALFORMATSAMPLEIVNVPROC sample_query(void)
{
    if (!has_extension("GL_NV_internalformat_sample_query"))
        return NULL;
    return (PFNGLGETINTERNALFORMATSAMPLEIVNVPROC)eglGetProcAddress(
        "glGetInternalformatSampleivNV");
}

/* The counts GL offers format at target; each a true multisample count
 * unless the query (when there is one) says otherwise. */
static void query_modes(GLenum target, GLenum format, PFNGLGETINTERNALFORMATSAMPLEIVNVPROC nv,
                        oit_sample_modes *m)
{
    GLint n = 0, counts[OIT_SAMPLE_MODES_MAX] = {0};
    glGetInternalformativ(target, format, GL_NUM_SAMPLE_COUNTS, 1, &n);
    n = n < OIT_SAMPLE_MODES_MAX ? n : OIT_SAMPLE_MODES_MAX;
    if (n > 0)
        glGetInternalformativ(target, format, GL_SAMPLES, n, counts);
    m->n = n > 0 ? n : 0;
    for (int i = 0; i < m->n; i++) {
        oit_sample_mode *o = &m->mode[i];
        *o = (oit_sample_mode){counts[i], counts[i], 1, 1, 1};
        if (!nv)
            continue;
        nv(target, format, counts[i], GL_MULTISAMPLES_NV, 1, &o->multisamples);
        nv(target, format, counts[i], GL_SUPERSAMPLE_SCALE_X_NV, 1, &o->scale_x);
        nv(target, format, counts[i], GL_SUPERSAMPLE_SCALE_Y_NV, 1, &o->scale_y);
        nv(target, format, counts[i], GL_CONFORMANT_NV, 1, &o->conformant);
    }
}

oit_status oit_stencil_choose_samples(int K, int *samples, oit_error *err)
{
    oit_status s = check_limits(K, err);
    if (s != OIT_OK)
        return s;
    PFNGLGETINTERNALFORMATSAMPLEIVNVPROC nv = sample_query();
    oit_sample_modes colour = {.what = "GL_RGBA32UI texture"};
    oit_sample_modes ds = {.what = "GL_DEPTH24_STENCIL8 renderbuffer"};
    query_modes(GL_TEXTURE_2D_MULTISAMPLE, GL_RGBA32UI, nv, &colour);
    query_modes(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, nv, &ds);
    s = oit_gl_check("stencil capture: sample counts", err);
    if (s == OIT_OK)
        s = oit_stencil_pick_samples(K, &colour, &ds, samples, err);
    return s;
}

/* ---- the target ------------------------------------------------------------ */

/* The target's programs: the routing set-up's and routing by copies'
 * full-screen passes, and the self-test's read-back
 * (glsl/stencil_dump.glsl). */
enum { PROG_SETUP, PROG_COPY, PROG_DUMP, PROGS };
extern const char oit_stencil_dump_cs[]; /* glsl/stencil_dump.glsl */
static const oit_glsl_program programs[PROGS] = {
    [PROG_SETUP] = {"stencil routing set-up",
                    .vs = {oit_capture_fullscreen_vs}, .fs = {oit_capture_route_setup_fs}},
    [PROG_COPY] = {"stencil routing by copies",
                   .vs = {oit_capture_fullscreen_vs}, .fs = {oit_capture_route_copy_fs}},
    [PROG_DUMP] = {"stencil self-test: read-back", .cs = {oit_stencil_dump_cs}},
};

oit_status oit_stencil_target_init(oit_stencil_target *t, int K, int samples,
                                   oit_program_cache *pc, oit_error *err)
{
    memset(t, 0, sizeof *t);
    t->pc = pc;
    t->K = K;
    t->samples = samples;
    oit_status s = oit_glsl_programs_build(pc, &programs[PROG_SETUP], 1, &t->init_prog, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &t->fbo);
        glCreateVertexArrays(1, &t->vao);
    }
    return s;
}

oit_status oit_stencil_target_by_copy(oit_stencil_target *t, oit_error *err)
{
    t->by_copy = 1;
    return oit_glsl_programs_build(t->pc, &programs[PROG_COPY], 1, &t->copy_prog, err);
}

void oit_stencil_target_release(oit_stencil_target *t)
{
    glDeleteProgram(t->init_prog);
    glDeleteProgram(t->copy_prog);
    glDeleteBuffers(1, &t->routed);
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteVertexArrays(1, &t->vao);
    glDeleteTextures(1, &t->colour);
    glDeleteRenderbuffers(1, &t->depth_stencil);
    memset(t, 0, sizeof *t);
}

oit_status oit_stencil_target_resize(oit_stencil_target *t, int w, int h, oit_error *err)
{
    if (t->colour && t->width == w && t->height == h)
        return OIT_OK;
    glDeleteTextures(1, &t->colour);
    glDeleteRenderbuffers(1, &t->depth_stencil);
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &t->colour);
    glTextureStorage2DMultisample(t->colour, t->samples, GL_RGBA32UI, w, h, GL_TRUE);
    oit_gl_poison_texture(t->colour, GL_RGBA32UI);
    glCreateRenderbuffers(1, &t->depth_stencil);
    glNamedRenderbufferStorageMultisample(t->depth_stencil, t->samples, GL_DEPTH24_STENCIL8, w, h);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->colour, 0);
    glNamedFramebufferRenderbuffer(t->fbo, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                   t->depth_stencil);
    GLenum status = glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER);
    t->width = w;
    t->height = h;
    oit_status s = OIT_OK;
    if (t->by_copy)
        s = oit_gl_buffer_reserve(&t->routed, &t->routed_cap,
                                  (uint64_t)w * h * (uint64_t)t->K * 16,
                                  "stencil routing by copies", err);
    if (s == OIT_OK)
        s = oit_gl_check("stencil capture: multisample target", err);
    if (s == OIT_OK && status != GL_FRAMEBUFFER_COMPLETE)
        s = oit_error_set(err, OIT_ERR_UNSUPPORTED, "stencil capture: a %dx%d target with %d "
                          "rgba32ui samples is incomplete (status 0x%x)", w, h, t->samples, status);
    return s;
}

/* The target bound, scissored to rect, with the stencil test on, depth off
 * and colour writes as given: what routing and drawing both start with. */
static void bind(oit_stencil_target *t, const int rect[4], GLboolean colour)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->width, t->height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect[0], rect[1], rect[2] - rect[0], rect[3] - rect[1]);
    glColorMask(colour, colour, colour, colour);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
}

/* Sets sample i's stencil to i + 1 inside rect (GL rows), and to 0 in the
 * samples past K a larger target has, so that drawing with EQUAL 1 and DECR
 * each fragment lands in the next free sample. */
static void route(oit_stencil_target *t, const int rect[4])
{
    bind(t, rect, GL_FALSE);
    glStencilMask(0xff);
    glStencilOp(GL_REPLACE, GL_REPLACE, GL_REPLACE);
    /* One full-screen draw per sample, masked to that sample. */
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_SAMPLE_MASK);
    glUseProgram(t->init_prog);
    glBindVertexArray(t->vao);
    for (int i = 0; i <= t->K; i++) {
        glSampleMaski(0, i < t->K ? 1u << i : ~0u << t->K);
        glStencilFunc(GL_ALWAYS, i < t->K ? i + 1 : 0, 0xff);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glSampleMaski(0, ~0u);
    glDisable(GL_SAMPLE_MASK);
}

/* The target and the routing state for the fill in rect. */
static void begin_draw(oit_stencil_target *t, const int rect[4])
{
    bind(t, rect, GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    if (t->sample_shading) {
        /* sample shading needs multisampling on (GL 4.5, 14.3.1.1) */
        glEnable(GL_MULTISAMPLE);
        glEnable(GL_SAMPLE_SHADING);
        glMinSampleShading(1.0f);
    } else {
        glDisable(GL_MULTISAMPLE);
    }
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_DECR, GL_DECR, GL_DECR);
}

static void end_draw(void)
{
    glDisable(GL_SAMPLE_SHADING);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

/* Routing by copies: sample i of each pixel in rect takes its slot i. */
static void copy_samples(oit_stencil_target *t, const int rect[4])
{
    bind(t, rect, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_SAMPLE_MASK);
    glUseProgram(t->copy_prog);
    glBindVertexArray(t->vao);
    glProgramUniform1i(t->copy_prog, glGetUniformLocation(t->copy_prog, "u_K"), t->K);
    glProgramUniform1i(t->copy_prog, glGetUniformLocation(t->copy_prog, "u_width"), t->width);
    for (int i = 0; i < t->K; i++) {
        glSampleMaski(0, 1u << i);
        glProgramUniform1i(t->copy_prog, glGetUniformLocation(t->copy_prog, "u_sample"), i);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glSampleMaski(0, ~0u);
    glDisable(GL_SAMPLE_MASK);
}

void oit_stencil_target_fill(oit_stencil_target *t, const int rect[4], GLuint prog,
                             oit_gpu_draws *draws, const oit_gpu_mesh *const *meshes, int n)
{
    if (t->by_copy) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, t->routed);
        bind(t, rect, GL_FALSE);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_MULTISAMPLE);
        glUseProgram(prog);
        oit_gpu_mesh_draw_many(draws, meshes, n);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        copy_samples(t, rect);
        end_draw();
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        return;
    }
    route(t, rect);
    begin_draw(t, rect);
    glUseProgram(prog);
    oit_gpu_mesh_draw_many(draws, meshes, n);
    end_draw();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

uint64_t oit_stencil_target_bytes(const oit_stencil_target *t)
{
    return (uint64_t)t->width * t->height * t->samples * (16 + 4) + t->routed_cap;
}

/* ---- the self-test -------------------------------------------------------- */

/* Every sample of the target OIT_STENCIL_UNWRITTEN, so that one no fragment
 * reached reads as lost rather than as whatever the memory held. */
static void clear_samples(oit_stencil_target *t)
{
    static const GLuint unwritten[4] = {~0u, ~0u, ~0u, ~0u};
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferuiv(t->fbo, GL_COLOR, 0, unwritten);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

/* The probe's fill, the same draw a batch makes. */
static oit_status fill_probe(oit_stencil_target *t, const oit_stencil_probe *p,
                             const oit_stencil_fill *f, oit_error *err)
{
    oit_gpu_mesh *mesh = NULL;
    oit_status s = oit_gpu_mesh_create(p->tris, (size_t)p->K, 0, &mesh, err);
    if (s != OIT_OK)
        return s;
    const int rect[4] = {0, 0, p->width, p->height};
    const oit_gpu_mesh *list[1] = {mesh};
    clear_samples(t);
    oit_stencil_target_fill(t, rect, f->prog, f->draws, list, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    oit_gpu_mesh_destroy(mesh);
    return oit_gl_check("stencil self-test: fill", err);
}

/* Every pixel's K samples' primitives into prims (pixel * K + i). */
static oit_status read_samples(oit_stencil_target *t, const oit_stencil_probe *p,
                               uint32_t *prims, oit_error *err)
{
    GLuint prog = 0, buf = 0;
    oit_status s = oit_glsl_programs_build(t->pc, &programs[PROG_DUMP], 1, &prog, err);
    if (s != OIT_OK)
        return s;
    GLsizeiptr bytes = (GLsizeiptr)sizeof *prims * p->width * p->height * p->K;
    glCreateBuffers(1, &buf);
    glNamedBufferData(buf, bytes, NULL, GL_STREAM_READ);
    oit_gl_poison_buffer(buf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, buf);
    glUseProgram(prog);
    glProgramUniform1i(prog, OIT_LOC_K, p->K);
    glBindTextureUnit(OIT_TEX_SAMPLES, t->colour);
    glDispatchCompute((GLuint)p->width, (GLuint)p->height, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf, 0, bytes, prims);
    glDeleteBuffers(1, &buf);
    glDeleteProgram(prog);
    return oit_gl_check("stencil self-test: read-back", err);
}

oit_status oit_stencil_self_test(oit_stencil_target *t, const oit_stencil_probe *p,
                                 const oit_stencil_fill *f, oit_error *err)
{
    size_t pixels = (size_t)p->width * (size_t)p->height;
    uint32_t counts[OIT_PROBE_MAX_COLS * OIT_PROBE_ROWS];
    uint32_t *prims = malloc(sizeof *prims * pixels * (size_t)p->K);
    if (!prims)
        return oit_error_set(err, OIT_ERR_NOMEM, "stencil self-test: out of memory");
    oit_status s = fill_probe(t, p, f, err);
    if (s == OIT_OK)
        s = read_samples(t, p, prims, err);
    if (s == OIT_OK) {
        glGetNamedBufferSubData(f->counts, 0, (GLsizeiptr)(sizeof *counts * pixels), counts);
        s = oit_gl_check("stencil self-test: counts", err);
    }
    if (s == OIT_OK)
        s = oit_stencil_probe_verdict(p, prims, counts, err);
    free(prims);
    return s;
}

/* The self-test through a capture: a frame of the probe's view begun, so
 * that its counts are zero and the target has the probe's size. */
oit_status oit_capture_stencil_self_test(oit_capture *c, oit_stencil_target *t, GLuint fill,
                                         oit_error *err)
{
    oit_stencil_probe probe;
    oit_stencil_probe_build(&probe, t->K);
    oit_status s = oit_capture_begin(c, &probe.view, err);
    if (s == OIT_OK) {
        const oit_stencil_fill f = {fill, c->buf[OIT_CAPTURE_COUNTS], c->draws};
        s = oit_stencil_self_test(t, &probe, &f, err);
    }
    c->frame.in_frame = 0;
    return s;
}

oit_status oit_capture_route_init(const oit_capture *c, oit_stencil_target *t, int stencil_k,
                                  oit_error *err)
{
    int samples = 0;
    oit_status s = oit_stencil_choose_samples(stencil_k, &samples, err);
    if (s == OIT_OK)
        s = oit_stencil_target_init(t, stencil_k, samples, c->programs, err);
    t->sample_shading = (c->faults & OIT_CAPTURE_FAULT_SAMPLE_SHADING) != 0;
    if (s == OIT_OK && (c->faults & OIT_CAPTURE_TEST_ROUTE_BY_COPY))
        s = oit_stencil_target_by_copy(t, err);
    return s;
}

oit_glsl_program oit_capture_routed_fill(int firstk_pass, int by_copy)
{
    static const char *const defines[2][2] = {
        {"", "#define OIT_ROUTE_BY_COPY 1\n"},
        {"#define OIT_FIRSTK_PASS 1\n",
         "#define OIT_FIRSTK_PASS 1\n#define OIT_ROUTE_BY_COPY 1\n"}};
    return (oit_glsl_program){"capture fill", .fs = {defines[firstk_pass != 0][by_copy != 0],
                                                     oit_glsl_state_io, oit_capture_stencil_fs}};
}

/* ---- the stencil backend (OIT_CAPTURE_STENCIL) ------------------------------ */

/* Its K-slot fills routed into the target; wide batches in tiles of array
 * slots; the output through a buffer of its own (the target is no
 * storage buffer). */
typedef struct stencil_backend {
    oit_capture_slots slots;
    oit_stencil_target target;
    GLuint out;
    uint64_t out_cap;
} stencil_backend;

/* Its K-slot fill, routed (by copies where by_copy), and the resolve of
 * the samples. */
static void stencil_programs(int by_copy, oit_glsl_program programs[2])
{
    programs[0] = oit_capture_routed_fill(0, by_copy);
    programs[1] = (oit_glsl_program){"capture resolve",
                                     .cs = {"#define OIT_STENCIL 1\n", oit_glsl_composite,
                                            oit_glsl_state_io, oit_capture_resolve_cs}};
}

void oit_capture_stencil_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int i = 0; i < PROGS; i++)
        visit(user, &programs[i]);
    oit_glsl_program p[2];
    stencil_programs(0, p);
    visit(user, &p[1]); /* the same resolve either way */
    for (int by_copy = 0; by_copy < 2; by_copy++)
        for (int firstk_pass = 0; firstk_pass < 2; firstk_pass++) {
            oit_glsl_program fill = oit_capture_routed_fill(firstk_pass, by_copy);
            visit(user, &fill);
        }
}

static oit_status stencil_create(oit_capture *c, int stencil_k, oit_error *err)
{
    stencil_backend *b = c->be;
    oit_status s = oit_capture_route_init(c, &b->target, stencil_k, err);
    oit_glsl_program slots[2];
    stencil_programs(b->target.by_copy, slots);
    if (s == OIT_OK)
        s = oit_capture_slots_init(&b->slots, c->programs, slots, err);
    c->routed_k = stencil_k;
    if (s == OIT_OK)
        s = oit_capture_stencil_self_test(c, &b->target, b->slots.fill, err);
    return s;
}

static void stencil_destroy(void *be)
{
    stencil_backend *b = be;
    oit_capture_slots_release(&b->slots);
    if (b->target.fbo)
        oit_stencil_target_release(&b->target);
    glDeleteBuffers(1, &b->out);
}

static oit_status stencil_begin(oit_capture *c, oit_error *err)
{
    stencil_backend *b = c->be;
    int w = c->view.width, h = c->view.height;
    uint64_t bytes = oit_capture_within_binding(c, (uint64_t)w * h * 16, (uint64_t)w * 16);
    oit_status s = oit_capture_reserve(c, &b->out, &b->out_cap, bytes, "capture output", err);
    if (s == OIT_OK)
        s = oit_stencil_target_resize(&b->target, w, h, err);
    return s;
}

static void stencil_uniforms(oit_capture *c)
{
    oit_capture_slots_uniforms(c, &((stencil_backend *)c->be)->slots);
}

static void stencil_epsilon(oit_capture *c, float e)
{
    oit_capture_slots_epsilon(&((stencil_backend *)c->be)->slots, e);
}

static void stencil_bind(const oit_capture *c)
{
    const stencil_backend *b = c->be;
    oit_capture_bind_within(c, OIT_BIND_OUT, b->out, b->out_cap);
    if (b->slots.buf)
        oit_capture_bind_within(c, OIT_BIND_FRAGS, b->slots.buf, b->slots.cap);
}

/* Wide batches in tiles of array slots (the target holds K a pixel). */
static oit_status stencil_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int rect[4], int layers, oit_error *err)
{
    stencil_backend *b = c->be;
    if (layers > c->K || b->slots.tiled)
        return oit_capture_slots_tiled(c, &b->slots, meshes, n, rect, layers, err);
    int r[4] = {0}, empty = 1;
    oit_status s = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    oit_capture_bind_buffers(c);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_PASS1);
    oit_stencil_target_fill(&b->target, r, b->slots.fill, c->draws, meshes, n);
    glBindTextureUnit(OIT_TEX_SAMPLES, b->target.colour);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_RESOLVE);
    oit_capture_resolve(b->slots.resolve, r);
    return oit_gl_check("capture: batch", err);
}

static oit_status stencil_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                              oit_error *err)
{
    const stencil_backend *b = c->be;
    *out = (oit_capture_out){b->out, b->out_cap};
    return OIT_OK;
}

static uint64_t stencil_bytes(const void *be)
{
    const stencil_backend *b = be;
    return oit_stencil_target_bytes(&b->target) + b->slots.cap + b->out_cap;
}

static void stencil_stats(const oit_capture *c, oit_frame_stats *stats)
{
    stats->capture = c->ops->name;
    stats->capture_slots = "stencil";
    stats->capture_slots_k = (uint32_t)c->routed_k;
}

OIT_CAPTURE_OPS(stencil, OIT_CAPTURE_STENCIL, "stencil", stencil_backend, NULL, NULL,
                NULL);
