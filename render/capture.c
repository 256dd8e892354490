/* Batch capture into a K-fragment A-buffer (capture.h). Per batch: draw
 * (scissored to the batch rect) into the backend's K slots while counting
 * fragments per pixel, then a compute resolve over the rect sorts each
 * pixel's <= K fragments and composites them into the per-pixel state of
 * shade.h that the frame carries across batches; it also resets the counts.
 * Buffers are in GL row order (bottom first); the rect and the output image
 * are flipped at the interface. */
#include "render/capture.h"

#include "base/clock.h"
#include "render/capture_compute.h"
#include "render/capture_counted.h"
#include "render/capture_firstk.h"
#include "render/capture_glsl.h"
#include "render/capture_stencil.h"
#include "render/frag_glsl.h"
#include "render/gpu_timer.h"
#include "render/image.h"
#include "render/opaque_keys.h"
#include "render/rect.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { BUF_COUNTS, BUF_SLOTS, BUF_STATE, BUF_OUT, BUF_TOTALS, BUF_N };
enum { PROG_FILL, PROG_RESOLVE, PROG_END, PROG_N };

struct oit_capture {
    oit_capture_kind backend;
    oit_gpu_timer *timer; /* phases marked (oit_capture_set_gpu_timer); NULL: none */
    int K;
    /* the K-slot fills go through the stencil target: STENCIL's batches,
     * or FIRSTK's first passes (oit_capture_create_routed) */
    int routed;
    unsigned faults;
    float epsilon; /* early termination threshold; 0: exact */
    float applied; /* what the programs test now: epsilon, or 0 (gate_epsilon) */
    int touched[4]; /* GL box of the frame's batches so far; empty: x0 >= x1 */
    oit_opaque_depth opaque; /* the caller's depth (oit_capture_set_opaque);
                                keyed: this frame's opaque triangles */
    oit_opaque_keys *keys;   /* the opaque pre-pass, made on first need */
    GLuint prog[PROG_N];
    /* Tiled batches (tile-local slots: wide parts, or a slot budget below
     * the full frame), built on first use: [0] sorts up to 16, [1] up to
     * OIT_CAPTURE_MAX_LAYERS; each its fill, then its resolve. */
    GLuint tile_prog[2][2];
    uint64_t slot_budget; /* bytes; 0: K slots for every pixel of the frame */
    uint64_t store_limit; /* oit_capture_set_store_limit; 0: the driver's */
    uint64_t bind;        /* this frame's: the least of the two */
    int tiled;            /* this frame: every batch goes through tiles */
    GLuint out_buf;       /* this frame's output: BUF_OUT, or the idle slots */
    GLuint fbo; /* attachment-less, for the array backend */
    GLuint buf[BUF_N];
    uint64_t cap[BUF_N];
    oit_stencil_target stencil;
    oit_counted counted; /* OIT_CAPTURE_COUNTED, and FIRSTK's packs too wide for it */
    oit_firstk firstk;   /* OIT_CAPTURE_FIRSTK */
    int firstk_off;      /* FIRSTK capturing as COUNTED (oit_capture_set_first_k) */
    oit_compute compute; /* OIT_CAPTURE_COMPUTE */
    GLuint max_groups;    /* GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] */
    oit_gpu_draws *draws; /* every geometry draw goes through it */
    uint64_t calls0;      /* its draw calls at the frame's begin */
    oit_view view;
    int in_frame;
    uint32_t batches;
    uint64_t bytes_peak;
    double t0;
};

/* The backends whose packs are counted and stored (capture_counted.h), in
 * every pack or in the packs too wide for first-K slots. */
static int uses_counted(const oit_capture *c)
{
    return c->backend == OIT_CAPTURE_COUNTED || c->backend == OIT_CAPTURE_FIRSTK;
}

static oit_status build_programs(oit_capture *c, oit_error *err)
{
    int stencil = c->backend == OIT_CAPTURE_STENCIL;
    char defines[96];
    snprintf(defines, sizeof defines, "%s%s",
             c->backend == OIT_CAPTURE_FIRSTK ? "#define OIT_FIRSTK_PASS 1\n" : "",
             c->stencil.by_copy ? "#define OIT_ROUTE_BY_COPY 1\n" : "");
    const oit_glsl_program programs[PROG_N] = {
        [PROG_FILL] = {"capture fill",
                       .fs = {defines, oit_glsl_state_io,
                              c->routed ? oit_capture_stencil_fs : oit_capture_array_fs}},
        [PROG_RESOLVE] = {"capture resolve",
                          .cs = {stencil ? "#define OIT_STENCIL 1\n" : "", oit_glsl_composite,
                                 oit_glsl_state_io, oit_capture_resolve_cs}},
        [PROG_END] = {"capture end",
                      .cs = {oit_glsl_composite, oit_glsl_state_io, oit_capture_end_cs}},
    };
    return oit_glsl_programs_build(programs, PROG_N, c->prog, err);
}

static void release(oit_capture *c)
{
    oit_glsl_programs_delete(c->prog, PROG_N);
    for (int i = 0; i < 2; i++)
        oit_glsl_programs_delete(c->tile_prog[i], 2);
    glDeleteFramebuffers(1, &c->fbo);
    glDeleteBuffers(BUF_N, c->buf);
    if (c->stencil.fbo)
        oit_stencil_target_release(&c->stencil);
    if (uses_counted(c))
        oit_counted_release(&c->counted);
    if (c->backend == OIT_CAPTURE_FIRSTK)
        oit_firstk_release(&c->firstk);
    if (c->backend == OIT_CAPTURE_COMPUTE)
        oit_compute_release(&c->compute);
    oit_gpu_draws_destroy(c->draws);
    oit_opaque_keys_destroy(c->keys);
    free(c);
}

void oit_capture_destroy(oit_capture *c)
{
    if (c)
        release(c);
}

oit_capture_kind oit_capture_backend(const oit_capture *c)
{
    return c->backend;
}

const char *oit_capture_kind_name(oit_capture_kind kind)
{
    switch (kind) {
    case OIT_CAPTURE_ARRAY: return "array";
    case OIT_CAPTURE_STENCIL: return "stencil";
    case OIT_CAPTURE_COUNTED: return "counted";
    case OIT_CAPTURE_FIRSTK: return "first-k";
    case OIT_CAPTURE_COMPUTE: return "compute";
    default: return NULL;
    }
}

/* stencil_k: the samples of the routed fills (STENCIL: K; FIRSTK: its
 * first pass's slots), 0 for none. */
static oit_status make(oit_capture_kind backend, int K, int stencil_k, unsigned faults,
                       oit_capture **out, oit_error *err)
{
    oit_capture *c = calloc(1, sizeof *c);
    if (!c)
        return oit_error_set(err, OIT_ERR_NOMEM, "capture: out of memory");
    c->backend = backend;
    c->K = K;
    c->routed = stencil_k > 0;
    c->faults = faults;
    oit_status s = OIT_OK;
    if (c->routed) {
        int samples = 0;
        s = oit_stencil_choose_samples(stencil_k, &samples, err);
        if (s == OIT_OK)
            s = oit_stencil_target_init(&c->stencil, stencil_k, samples, err);
        c->stencil.sample_shading = (faults & OIT_CAPTURE_FAULT_SAMPLE_SHADING) != 0;
        if (s == OIT_OK && (faults & OIT_CAPTURE_TEST_ROUTE_BY_COPY))
            s = oit_stencil_target_by_copy(&c->stencil, err);
    }
    if (s == OIT_OK)
        s = build_programs(c, err);
    if (s == OIT_OK)
        s = oit_gpu_draws_create(&c->draws, err);
    if (s == OIT_OK && uses_counted(c))
        s = oit_counted_init(&c->counted, err);
    if (s == OIT_OK && backend == OIT_CAPTURE_COMPUTE)
        s = oit_compute_init(&c->compute, err);
    if (s == OIT_OK && backend == OIT_CAPTURE_FIRSTK)
        s = oit_firstk_init(&c->firstk, K, err);
    if (s == OIT_OK && backend == OIT_CAPTURE_FIRSTK && c->routed)
        oit_firstk_route(&c->firstk, &c->stencil, c->prog[PROG_FILL]);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &c->fbo);
        c->max_groups = oit_gl_max_groups_x();
        s = oit_gl_check("capture: set-up", err);
    }
    if (s != OIT_OK) {
        release(c);
        return s;
    }
    *out = c;
    return OIT_OK;
}

static oit_status stencil_self_test(oit_capture *c, oit_error *err);

oit_status oit_capture_create(oit_capture_kind kind, int K, oit_capture **out,
                              oit_error *err)
{
    return oit_capture_create_faulty(kind, K, 0, out, err);
}

/* AUTO keeps the caller's K and takes the array backend where stencil
 * routing is refused; STENCIL refuses with the reason: the caller asked for
 * that method, and a lower K would lose fragments (an inexact image). */
oit_status oit_capture_create_faulty(oit_capture_kind kind, int K, unsigned faults,
                                     oit_capture **out, oit_error *err)
{
    *out = NULL;
    if (K < 2 || K > 16)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: K=%d is outside [2, 16]", K);
    if (kind == OIT_CAPTURE_ARRAY || kind == OIT_CAPTURE_COUNTED || kind == OIT_CAPTURE_FIRSTK ||
        kind == OIT_CAPTURE_COMPUTE)
        return make(kind, K, 0, faults, out, err);
    oit_status s = oit_capture_create_routed(OIT_CAPTURE_STENCIL, K, K, faults, out, err);
    if (s != OIT_OK && kind == OIT_CAPTURE_AUTO)
        return make(OIT_CAPTURE_ARRAY, K, 0, faults, out, err);
    return s;
}

oit_status oit_capture_create_routed(oit_capture_kind kind, int K, int stencil_k,
                                     unsigned faults, oit_capture **out, oit_error *err)
{
    *out = NULL;
    if (K < 2 || K > 16)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: K=%d is outside [2, 16]", K);
    if (kind != OIT_CAPTURE_STENCIL && kind != OIT_CAPTURE_FIRSTK)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: only the stencil and first-k "
                             "captures are routed, not %s",
                             oit_capture_kind_name(kind) ? oit_capture_kind_name(kind) : "auto");
    if (stencil_k < 2 || stencil_k > K || (kind == OIT_CAPTURE_STENCIL && stencil_k != K))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: %d routed samples for %s at "
                             "K=%d (2..K; the stencil capture's own K)", stencil_k,
                             oit_capture_kind_name(kind), K);
    oit_capture *c = NULL;
    oit_status s = make(kind, K, stencil_k, faults, &c, err);
    if (s == OIT_OK) {
        s = stencil_self_test(c, err);
        if (s != OIT_OK) {
            release(c);
            c = NULL;
        }
    }
    if (s == OIT_OK) {
        *out = c;
        return OIT_OK;
    }
    /* A driver error while setting stencil routing up means it is not
     * offered here, which the caller reads as UNSUPPORTED. */
    if (s == OIT_ERR_GL && err) {
        char why[sizeof err->message];
        memcpy(why, err->message, sizeof why);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s", why);
    }
    return s == OIT_ERR_GL ? OIT_ERR_UNSUPPORTED : s;
}

int oit_capture_routed_k(const oit_capture *c)
{
    return c->routed ? c->stencil.K : 0;
}

static uint64_t held_bytes(const oit_capture *c)
{
    uint64_t b = oit_stencil_target_bytes(&c->stencil) + oit_gpu_draws_bytes(c->draws);
    if (uses_counted(c))
        b += oit_counted_bytes(&c->counted);
    if (c->backend == OIT_CAPTURE_FIRSTK)
        b += oit_firstk_bytes(&c->firstk);
    if (c->backend == OIT_CAPTURE_COMPUTE)
        b += oit_compute_bytes(&c->compute);
    for (int i = 0; i < BUF_N; i++)
        b += c->cap[i];
    return b + oit_opaque_keys_gpu_bytes(c->keys);
}

static void note_peak(oit_capture *c)
{
    uint64_t held = held_bytes(c);
    c->bytes_peak = held > c->bytes_peak ? held : c->bytes_peak;
}

static oit_status reserve(oit_capture *c, int which, uint64_t bytes, oit_error *err)
{
    static const char *names[BUF_N] = {"capture counts", "capture slots", "capture state",
                                       "capture output", "capture totals"};
    oit_status s = oit_gl_buffer_reserve(&c->buf[which], &c->cap[which], bytes, names[which], err);
    note_peak(c);
    return s;
}

uint64_t oit_capture_pixel_bytes(const oit_view *v)
{
    return oit_state_bytes(v->shading.mode == OIT_SHADING_TRANSLUCENT);
}

/* The state buffer's bytes for the frame v: its layout follows the shading. */
static uint64_t state_bytes(const oit_view *v)
{
    return (uint64_t)v->width * v->height * oit_capture_pixel_bytes(v);
}

/* bytes, or less where one storage binding (at least one row of `row`
 * bytes) spans less: what an output buffer read in bands of rows holds. */
static uint64_t within_binding(const oit_capture *c, uint64_t bytes, uint64_t row)
{
    uint64_t most = c->bind > row ? c->bind : row;
    return bytes < most ? bytes : most;
}

/* The array backend's slots are local to each batch's rectangle and grow
 * to the largest rectangle's K slots a pixel (batch_slots), at most K for
 * every pixel; under a slot budget smaller than that they hold the budget's
 * worth (at least one row) and every batch goes through tiles. The output,
 * needed only at the frame's end, passes through the idle slots, in bands
 * of rows when they hold less. */
static oit_status allocate(oit_capture *c, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    int array = c->backend == OIT_CAPTURE_ARRAY;
    /* the backends with an output buffer of their own */
    int stencil = c->backend == OIT_CAPTURE_STENCIL || c->backend == OIT_CAPTURE_COMPUTE;
    uint64_t full = pixels * (uint64_t)c->K * 16, row = (uint64_t)v->width * c->K * 16;
    /* One storage binding is a slot budget too: slots past it would be
     * written where the shader cannot address them. */
    uint64_t budget = c->slot_budget && c->slot_budget < c->bind ? c->slot_budget : c->bind;
    c->tiled = array && full > budget;
    uint64_t slots = !c->tiled ? row : budget > row ? budget : row;
    uint64_t state = state_bytes(v);
    oit_status s = oit_gl_check_ssbo_size(array && slots > state ? slots : state,
                                          "capture: the frame's largest buffer", err);
    if (s == OIT_OK)
        s = reserve(c, BUF_COUNTS, pixels * 4, err);
    if (s == OIT_OK && array)
        s = reserve(c, BUF_SLOTS, slots, err);
    if (s == OIT_OK)
        s = reserve(c, BUF_STATE, state, err);
    /* The counted and first-K backends' output passes through their
     * fragment store, idle at the frame's end (read_output), as the tiled
     * slots do. */
    if (s == OIT_OK && stencil)
        s = reserve(c, BUF_OUT, within_binding(c, pixels * 16, (uint64_t)v->width * 16), err);
    c->out_buf = array ? c->buf[BUF_SLOTS] : c->buf[BUF_OUT];
    if (s == OIT_OK)
        s = reserve(c, BUF_TOTALS, 16, err);
    if (s == OIT_OK && c->routed)
        s = oit_stencil_target_resize(&c->stencil, v->width, v->height, err);
    if (s == OIT_OK && !array)
        note_peak(c);
    return s;
}

/* The capture switched away from keeps nothing: a frame holds one
 * capture's store, not both (12M plant at 1024x1024: 68 MB beyond the ring
 * and cache with both, 55 with one). */
void oit_capture_set_first_k(oit_capture *c, int on)
{
    if (c->backend != OIT_CAPTURE_FIRSTK || (on == 0) == c->firstk_off)
        return;
    if (on)
        oit_gl_buffer_release(&c->counted.frags, &c->counted.frags_cap);
    else
        oit_gl_buffer_release(&c->firstk.store, &c->firstk.store_cap);
    c->firstk_off = !on;
}

void oit_capture_set_store_limit(oit_capture *c, uint64_t bytes)
{
    c->store_limit = bytes;
}

void oit_capture_set_slot_budget(oit_capture *c, uint64_t bytes)
{
    c->slot_budget = bytes;
}

/* The program arrays of the captures this one drives (the counted
 * capture's, and the first-K capture's), each with its length; in both the
 * two geometry passes come first. */
static int backend_programs(oit_capture *c, GLuint *progs[2], int n[2])
{
    int k = 0;
    if (uses_counted(c)) {
        progs[k] = c->counted.prog;
        n[k++] = OIT_COUNTED_PROGS;
    }
    if (c->backend == OIT_CAPTURE_FIRSTK) {
        progs[k] = c->firstk.prog;
        n[k++] = OIT_FIRSTK_PROGS;
    }
    if (c->backend == OIT_CAPTURE_COMPUTE) {
        progs[k] = c->compute.prog;
        n[k++] = OIT_COMPUTE_PROGS;
    }
    return k;
}

/* The threshold in every program that tests it, effective from the next
 * batch on. */
static void apply_epsilon(oit_capture *c, float e)
{
    c->applied = e;
    oit_glsl_set_epsilon_all(&c->prog[PROG_FILL], 1, e);
    for (int i = 0; i < 2; i++)
        if (c->tile_prog[i][0])
            oit_glsl_set_epsilon_all(&c->tile_prog[i][0], 1, e); /* its fill */
    GLuint *sub[2];
    int n[2];
    for (int i = 0, m = backend_programs(c, sub, n); i < m; i++)
        oit_glsl_set_epsilon_all(sub[i], 2, e); /* the geometry passes */
}

/* Pixels no earlier batch of the frame composited carry T = 1, where the
 * per-fragment saturation test can drop nothing: a batch wholly outside
 * the box of the earlier ones runs without it. Reading the state at every
 * fragment costs (15% of a frame of the 2CylinderEngine in one pack on
 * llvmpipe), and a frame's first pack is often its only one. */
static void gate_epsilon(oit_capture *c, const int r[4])
{
    int *b = c->touched;
    int first = b[0] >= b[2];
    float want = first || !oit_rect_overlaps(b, r) ? 0.0f : c->epsilon;
    if (want != c->applied)
        apply_epsilon(c, want);
    if (first)
        memcpy(b, r, sizeof c->touched);
    else
        oit_rect_grow(b, r);
}

static void set_uniforms(oit_capture *c)
{
    GLuint *progs = c->prog;
    for (int i = 0; i < PROG_N; i++) {
        oit_glsl_set_view(progs[i], &c->view);
        glProgramUniform1i(progs[i], glGetUniformLocation(progs[i], "u_K"), c->K);
        glProgramUniform1ui(progs[i], glGetUniformLocation(progs[i], "u_count"),
                            (GLuint)((uint64_t)c->view.width * c->view.height));
    }
    /* first-K's routed pass 1 keeps as many fragments as the target has samples */
    if (c->routed)
        glProgramUniform1i(progs[PROG_FILL], glGetUniformLocation(progs[PROG_FILL], "u_K"),
                           c->stencil.K);
    GLuint *sub[2];
    int n[2], m = backend_programs(c, sub, n);
    for (int i = 0; i < m; i++)
        oit_glsl_set_view_all(sub[i], n[i], &c->view);
    /* the opaque depth's projection replaces the view's */
    oit_glsl_set_opaque_all(progs, PROG_N, &c->opaque);
    for (int i = 0; i < m; i++)
        oit_glsl_set_opaque_all(sub[i], n[i], &c->opaque);
    apply_epsilon(c, c->epsilon);
}

void oit_capture_set_opaque(oit_capture *c, const oit_opaque_depth *o)
{
    memset(&c->opaque, 0, sizeof c->opaque);
    if (o && o->enabled)
        c->opaque = *o;
    c->opaque.keyed = 0; /* each frame's own (opaque_begin) */
}

/* The frame's opaque pre-pass (opaque_keys.h), when its shading has opaque
 * triangles; before set_uniforms, which passes keyed to the programs. */
static oit_status opaque_begin(oit_capture *c, oit_error *err)
{
    c->opaque.keyed = 0;
    if (!oit_shading_opaque(&c->view.shading))
        return OIT_OK;
    oit_status s = c->keys ? OIT_OK : oit_opaque_keys_create(&c->keys, err);
    int on = 0;
    if (s == OIT_OK)
        s = oit_opaque_keys_begin(c->keys, &c->view, c->opaque.enabled ? &c->opaque : NULL, &on,
                                  err);
    c->opaque.keyed = on;
    note_peak(c);
    return s;
}

void oit_capture_set_epsilon(oit_capture *c, float epsilon)
{
    c->epsilon = epsilon > 0.0f ? epsilon : 0.0f;
    apply_epsilon(c, c->epsilon);
}

/* Binds buf (cap bytes) at binding, no more of it than one binding spans
 * (c->bind): a driver need address no more, so an index past it reads 0
 * and writes nothing here too, where it would go unnoticed elsewhere. */
static void bind_within(const oit_capture *c, GLuint binding, GLuint buf, uint64_t cap)
{
    uint64_t size = cap < c->bind ? cap : c->bind;
    if (buf && size)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buf, 0, (GLsizeiptr)size);
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buf);
}

/* The bytes of out_buf, whichever buffer it is. */
static uint64_t out_cap(const oit_capture *c)
{
    return c->out_buf == c->buf[BUF_SLOTS] ? c->cap[BUF_SLOTS]
           : c->out_buf == c->buf[BUF_OUT] ? c->cap[BUF_OUT]
           : c->out_buf == c->firstk.store ? c->firstk.store_cap
                                           : c->counted.frags_cap;
}

static void bind_buffers(const oit_capture *c)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, c->buf[BUF_COUNTS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, c->buf[BUF_TOTALS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, c->buf[BUF_STATE]);
    bind_within(c, OIT_BIND_OUT, c->out_buf, out_cap(c));
    if (c->buf[BUF_SLOTS])
        bind_within(c, OIT_BIND_FRAGS, c->buf[BUF_SLOTS], c->cap[BUF_SLOTS]);
}

void oit_capture_set_gpu_timer(oit_capture *c, struct oit_gpu_timer *t)
{
    c->timer = t;
}

unsigned oit_capture_state_buffer(const oit_capture *c)
{
    return c->buf[BUF_STATE];
}

uint64_t oit_capture_draw_calls(const oit_capture *c)
{
    return oit_gpu_draws_calls(c->draws) - c->calls0;
}

oit_status oit_capture_begin(oit_capture *c, const oit_view *view, oit_error *err)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_size);
    if (view->width <= 0 || view->height <= 0 || view->width > max_size ||
        view->height > max_size)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: frame %dx%d is not renderable "
                             "(at most %d pixels a side)", view->width, view->height, max_size);
    c->t0 = oit_time_ms();
    c->view = *view;
    uint64_t driver = oit_gl_ssbo_max_bytes();
    c->bind = c->store_limit && c->store_limit < driver ? c->store_limit : driver;
    oit_shading_resolve_defaults(&c->view.shading);
    c->batches = 0;
    memset(c->touched, 0, sizeof c->touched);
    c->counted.splits = 0;
    c->firstk.second_pixels = 0;
    c->firstk.second_packs = c->firstk.second_draws = 0;
    c->calls0 = oit_gpu_draws_calls(c->draws);
    c->in_frame = 0;
    c->bytes_peak = held_bytes(c); /* this frame's peak: buffers may have been released */
    oit_status s = allocate(c, &c->view, err);
    if (s != OIT_OK)
        return s;
    static const GLuint zero = 0;
    glClearNamedBufferData(c->buf[BUF_COUNTS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(c->buf[BUF_TOTALS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glNamedFramebufferParameteri(c->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, view->width);
    glNamedFramebufferParameteri(c->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, view->height);
    if ((s = opaque_begin(c, err)) != OIT_OK)
        return s;
    set_uniforms(c);
    bind_buffers(c);
    /* The state buffer of the frame before may still be read by a pass the
     * caller issued after oit_capture_end_gpu (liboit's blend): order those
     * reads before this frame's first shader write to it. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    /* All zero is the state of a pixel nothing has reached (frag_glsl.h). */
    glClearNamedBufferSubData(c->buf[BUF_STATE], GL_R32UI, 0, (GLsizeiptr)state_bytes(&c->view),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    s = oit_gl_check("capture: begin", err);
    c->in_frame = s == OIT_OK;
    return s;
}

/* The caller's rect (top rows first, exclusive ends) clamped to the frame
 * and turned into GL rows; returns 0 when it is empty. */
static int gl_rect(const oit_capture *c, const int rect[4], int out[4])
{
    int w = c->view.width, h = c->view.height;
    int r[4] = {0, 0, w, h};
    if (rect)
        memcpy(r, rect, sizeof r);
    r[0] = r[0] < 0 ? 0 : r[0];
    r[1] = r[1] < 0 ? 0 : r[1];
    r[2] = r[2] > w ? w : r[2];
    r[3] = r[3] > h ? h : r[3];
    out[0] = r[0];
    out[1] = h - r[3];
    out[2] = r[2];
    out[3] = h - r[1];
    return r[2] > r[0] && r[3] > r[1];
}

/* Draws the meshes with prog into the attachment-less framebuffer, clipped
 * to the GL rect r (array slots: the fill shader writes the buffers). */
static void draw_scissored(oit_capture *c, GLuint prog, const oit_gpu_mesh *const *meshes, int n,
                           const int r[4])
{
    oit_glsl_draw_scissored(c->fbo, c->view.width, c->view.height, prog, c->draws, meshes, n, r);
}

static void fill(oit_capture *c, const oit_gpu_mesh *const *meshes, int n, const int r[4])
{
    oit_gpu_timer_mark(c->timer, OIT_GPU_PASS1);
    if (c->backend == OIT_CAPTURE_STENCIL) {
        oit_stencil_target_fill(&c->stencil, r, c->prog[PROG_FILL], c->draws, meshes, n);
        return;
    }
    draw_scissored(c, c->prog[PROG_FILL], meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* The stencil self-test (capture_stencil.h) in a frame of the probe's view,
 * through this capture's own fill program and counts. */
static oit_status stencil_self_test(oit_capture *c, oit_error *err)
{
    oit_stencil_probe probe;
    oit_stencil_probe_build(&probe, c->stencil.K);
    oit_status s = oit_capture_begin(c, &probe.view, err);
    if (s == OIT_OK) {
        const oit_stencil_fill f = {c->prog[PROG_FILL], c->buf[BUF_COUNTS], c->draws};
        s = oit_stencil_self_test(&c->stencil, &probe, &f, err);
    }
    c->in_frame = 0;
    return s;
}

/* Sorts and composites the GL rect r with a resolve program. */
static void resolve(GLuint prog, const int r[4])
{
    glUseProgram(prog);
    glProgramUniform4i(prog, glGetUniformLocation(prog, "u_rect"), r[0], r[1], r[2], r[3]);
    glDispatchCompute(oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                      oit_gl_groups((uint64_t)(r[3] - r[1]), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The start every batch shares: it must be inside a frame, it counts, and
 * its rect is clamped into GL rows in r; *empty when nothing is drawn.
 * With opaque triangles it draws the batch's into the keys first, so that
 * the batch's own fragments behind them are discarded too. */
static oit_status batch_start(oit_capture *c, const oit_gpu_mesh *const *meshes, const int rect[4],
                              int n, int r[4], int *empty, oit_error *err)
{
    if (!c->in_frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: batch outside "
                             "oit_capture_begin/oit_capture_end");
    c->batches++;
    *empty = !gl_rect(c, rect, r) || n <= 0;
    if (!*empty)
        gate_epsilon(c, r);
    if (!*empty && c->opaque.keyed)
        oit_opaque_keys_draw(c->keys, c->draws, meshes, n, r);
    return OIT_OK;
}

/* K slots a pixel of the GL rect r, indexed from its corner, for an untiled
 * array batch: a batch pays for what it covers, not the frame. */
static oit_status batch_slots(oit_capture *c, const int r[4], oit_error *err)
{
    uint64_t pixels = (uint64_t)(r[2] - r[0]) * (uint64_t)(r[3] - r[1]);
    oit_status s = reserve(c, BUF_SLOTS, pixels * (uint64_t)c->K * 16, err);
    GLuint fill = c->prog[PROG_FILL];
    glProgramUniform4i(fill, glGetUniformLocation(fill, "u_tile"), r[0], r[1], r[2], r[3]);
    return s;
}

/* What the counted and first-K batches share of the frame. */
static oit_counted_frame counted_frame(const oit_capture *c)
{
    return (oit_counted_frame){.fbo = c->fbo,
                               .counts = c->buf[BUF_COUNTS],
                               .state = c->buf[BUF_STATE],
                               .width = c->view.width,
                               .height = c->view.height,
                               .draws = c->draws,
                               .bind = c->bind,
                               .timer = c->timer};
}

/* The counted backend's batch: the slot budget bounds its fragment store. */
static oit_status counted_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int r[4], oit_error *err)
{
    oit_counted_frame f = counted_frame(c);
    c->counted.budget = c->slot_budget ? c->slot_budget : UINT64_MAX;
    /* count, store, sort and composite: not split into phases */
    oit_gpu_timer_mark(c->timer, OIT_GPU_PASS1);
    oit_status s = oit_counted_batch(&c->counted, &f, meshes, n, r, err);
    note_peak(c);
    bind_buffers(c);
    return s;
}

/* The first-K backend's batch: W slots a pixel within the slot budget, or,
 * where fewer than 2 fit, the counted capture's batch. */
static oit_status firstk_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                               const int r[4], oit_error *err)
{
    c->firstk.budget = c->slot_budget && c->slot_budget < c->bind ? c->slot_budget : c->bind;
    if (c->firstk_off || oit_firstk_slots(&c->firstk, r) == 0)
        return counted_batch(c, meshes, n, r, err);
    oit_counted_frame f = counted_frame(c);
    oit_status s = oit_firstk_batch(&c->firstk, &f, meshes, n, r, err);
    note_peak(c);
    bind_buffers(c);
    return s;
}

/* The compute capture's batch (capture_compute.h), at the epsilon this
 * batch tests (gate_epsilon). */
static oit_status compute_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int r[4], oit_error *err)
{
    const oit_compute_frame f = {.state = c->buf[BUF_STATE],
                                 .width = c->view.width,
                                 .height = c->view.height,
                                 .bind = c->bind,
                                 .epsilon = c->applied,
                                 .timer = c->timer};
    oit_status s = oit_compute_batch(&c->compute, &f, meshes, n, r, err);
    note_peak(c);
    bind_buffers(c);
    return s;
}

oit_status oit_capture_batch(oit_capture *c, const oit_gpu_mesh *const *meshes,
                             int n, const int rect[4], oit_error *err)
{
    if (uses_counted(c) || c->backend == OIT_CAPTURE_COMPUTE) {
        int r[4] = {0}, empty = 1;
        oit_status s = batch_start(c, meshes, rect, n, r, &empty, err);
        if (s != OIT_OK || empty)
            return s;
        return c->backend == OIT_CAPTURE_FIRSTK    ? firstk_batch(c, meshes, n, r, err)
               : c->backend == OIT_CAPTURE_COMPUTE ? compute_batch(c, meshes, n, r, err)
                                                   : counted_batch(c, meshes, n, r, err);
    }
    if (c->tiled)
        return oit_capture_batch_layers(c, meshes, n, rect, c->K, err);
    int r[4] = {0}, empty = 1;
    oit_status s = batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    if (c->backend == OIT_CAPTURE_ARRAY)
        s = batch_slots(c, r, err);
    if (s != OIT_OK)
        return s;
    bind_buffers(c);
    fill(c, meshes, n, r);
    if (c->backend == OIT_CAPTURE_STENCIL)
        glBindTextureUnit(OIT_TEX_SAMPLES, c->stencil.colour);
    oit_gpu_timer_mark(c->timer, OIT_GPU_RESOLVE);
    resolve(c->prog[PROG_RESOLVE], r);
    return oit_gl_check("capture: batch", err);
}

/* ---- tiled batches ----------------------------------------------------------- */

/* Program pair i: 0 sorts up to 16 fragments a pixel, 1 up to
 * OIT_CAPTURE_MAX_LAYERS (registers a GPU would rather not spend on K). */
static oit_status tiled_programs(oit_capture *c, int i, oit_error *err)
{
    GLuint *progs = c->tile_prog[i];
    if (!progs[0]) {
        const oit_glsl_program pair[2] = {
            {"capture tiled fill", .fs = {oit_glsl_state_io, oit_capture_wide_fs}},
            {"capture tiled resolve",
             .cs = {i ? "#define OIT_WIDE " OIT_GLSL_STR(OIT_CAPTURE_MAX_LAYERS) "\n"
                      : "#define OIT_WIDE 16\n",
                    oit_glsl_composite, oit_glsl_state_io, oit_capture_resolve_cs}},
        };
        oit_status s = oit_glsl_programs_build(pair, 2, progs, err);
        if (s != OIT_OK)
            return s;
    }
    for (int k = 0; k < 2; k++) {
        oit_glsl_set_view(progs[k], &c->view);
        oit_glsl_set_opaque(progs[k], &c->opaque);
        glProgramUniform1i(progs[k], glGetUniformLocation(progs[k], "u_K"), c->K);
    }
    glProgramUniform1f(progs[0], glGetUniformLocation(progs[0], "u_epsilon"), c->applied);
    return OIT_OK;
}

/* One tile: fill its pixels' W slots, then resolve them. */
static void tile_pass(oit_capture *c, const oit_gpu_mesh *const *meshes, int n, int W, int i,
                      const int t[4])
{
    GLuint fp = c->tile_prog[i][0], rp = c->tile_prog[i][1];
    glProgramUniform1i(fp, glGetUniformLocation(fp, "u_W"), W);
    glProgramUniform1i(rp, glGetUniformLocation(rp, "u_W"), W);
    glProgramUniform4i(fp, glGetUniformLocation(fp, "u_tile"), t[0], t[1], t[2], t[3]);
    oit_gpu_timer_mark(c->timer, OIT_GPU_PASS1);
    draw_scissored(c, fp, meshes, n, t);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(c->timer, OIT_GPU_RESOLVE);
    resolve(rp, t);
}

/* The batch over tiles of the GL rect r small enough that W slots a pixel
 * fit the slots buffer: one draw of the batch per tile. */
static oit_status tiled_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                              const int r[4], int W, oit_error *err)
{
    uint64_t slots = c->tiled ? c->cap[BUF_SLOTS] / 16
                              : (uint64_t)c->view.width * c->view.height * (uint64_t)c->K;
    slots = slots > (uint64_t)W ? slots : (uint64_t)W;
    int i = W > 16;
    oit_status s = reserve(c, BUF_SLOTS, slots * 16, err);
    if (s == OIT_OK)
        s = tiled_programs(c, i, err);
    if (s != OIT_OK)
        return s;
    bind_buffers(c);
    uint64_t tile_pixels = c->cap[BUF_SLOTS] / 16 / (uint64_t)W;
    int rw = r[2] - r[0];
    int tw = (uint64_t)rw < tile_pixels ? rw : (int)tile_pixels;
    uint64_t rows = tile_pixels / (uint64_t)tw;
    int th = rows < (uint64_t)(r[3] - r[1]) ? (int)rows : r[3] - r[1];
    for (int y = r[1]; y < r[3]; y += th)
        for (int x = r[0]; x < r[2]; x += tw) {
            int t[4] = {x, y, x + tw < r[2] ? x + tw : r[2], y + th < r[3] ? y + th : r[3]};
            tile_pass(c, meshes, n, W, i, t);
        }
    return oit_gl_check("capture: tiled batch", err);
}

oit_status oit_capture_batch_layers(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                    const int rect[4], int layers, oit_error *err)
{
    if ((layers <= c->K && !c->tiled) || uses_counted(c) || c->backend == OIT_CAPTURE_COMPUTE)
        return oit_capture_batch(c, meshes, n, rect, err);
    if (layers > OIT_CAPTURE_MAX_LAYERS)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: a batch of %d layers, more than "
                             "%d", layers, OIT_CAPTURE_MAX_LAYERS);
    int r[4] = {0}, empty = 1;
    oit_status s = batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    return tiled_batch(c, meshes, n, r, layers > c->K ? layers : c->K, err);
}

/* Totals (and with write_out the final colours, into out_buf from its
 * start) of the pixels [first, first + count). */
static void end_pass(oit_capture *c, uint64_t first, uint64_t count, int write_out)
{
    GLuint p = c->prog[PROG_END];
    glUseProgram(p);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_first"), (GLuint)first);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_count"), (GLuint)count);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_out"), write_out);
    oit_gl_dispatch_x(p, glGetUniformLocation(p, "u_group0"), oit_gl_groups(count, 64),
                      c->max_groups);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Resolves the carried state against the background into out, in bands of
 * GL rows as many as out_buf holds, then reads the totals. */
static oit_status read_output(oit_capture *c, oit_image *out, GLuint totals[4], oit_error *err)
{
    int w = c->view.width, h = c->view.height;
    oit_status s = oit_image_alloc(out, w, h, err);
    if (s != OIT_OK)
        return s;
    size_t row = (size_t)w * 16;
    int firstk = c->backend == OIT_CAPTURE_FIRSTK && !c->firstk_off;
    if (uses_counted(c)) {
        /* The whole frame in one band where the budget allows: each band is
         * a pass and a read-back of its own. */
        uint64_t frame = (uint64_t)row * h, want = frame;
        if (c->slot_budget && want > c->slot_budget)
            want = c->slot_budget > row ? c->slot_budget : row;
        want = within_binding(c, want, row);
        s = firstk ? oit_gl_buffer_reserve(&c->firstk.store, &c->firstk.store_cap, want,
                                           "first-k capture fragments", err)
                   : oit_gl_buffer_reserve(&c->counted.frags, &c->counted.frags_cap, want,
                                           "counted capture fragments", err);
        note_peak(c);
        c->out_buf = firstk ? c->firstk.store : c->counted.frags;
        if (s != OIT_OK) {
            oit_image_free(out);
            return s;
        }
    }
    /* Untiled, the frame's K slots a pixel would fit: one band, one pass. */
    if (c->backend == OIT_CAPTURE_ARRAY && !c->tiled) {
        s = reserve(c, BUF_SLOTS, within_binding(c, (uint64_t)row * h, row), err);
        if (s != OIT_OK) {
            oit_image_free(out);
            return s;
        }
    }
    /* a grown buffer may pass what one binding spans */
    uint64_t held = within_binding(c, out_cap(c), row);
    bind_within(c, OIT_BIND_OUT, c->out_buf, held);
    int band = (int)(held / row < (uint64_t)h ? held / row : (uint64_t)h);
    for (int y0 = 0; y0 < h; y0 += band) {
        int y1 = y0 + band < h ? y0 + band : h;
        oit_gpu_timer_mark(c->timer, OIT_GPU_RESOLVE);
        end_pass(c, (uint64_t)y0 * w, (uint64_t)(y1 - y0) * w, 1);
        oit_gpu_timer_mark(c->timer, OIT_GPU_READBACK);
        /* GL rows are bottom first: each row goes to its flipped place. */
        for (int y = y0; y < y1; y++)
            glGetNamedBufferSubData(c->out_buf, (GLintptr)((size_t)(y - y0) * row),
                                    (GLsizeiptr)row, out->rgba + (size_t)(h - 1 - y) * w * 4);
    }
    glGetNamedBufferSubData(c->buf[BUF_TOTALS], 0, 16, totals);
    s = oit_gl_check("capture: readback", err);
    if (s != OIT_OK)
        oit_image_free(out);
    return s;
}

static oit_status finish_frame(oit_capture *c, oit_error *err)
{
    if (!c->in_frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: end without begin");
    c->in_frame = 0;
    bind_buffers(c);
    note_peak(c); /* the multi-draw buffers grow within batches */
    return OIT_OK;
}

static void fill_stats(const oit_capture *c, const GLuint totals[4], oit_frame_stats *stats)
{
    if (!stats)
        return;
    memset(stats, 0, sizeof *stats);
    stats->ms = oit_time_ms() - c->t0;
    stats->overflow_pixels = totals[0];
    stats->fragments = (uint64_t)totals[2] << 32 | totals[1];
    stats->max_layers = totals[3];
    stats->gpu_bytes_peak = c->bytes_peak;
    stats->batches = c->batches + (uses_counted(c) ? c->counted.splits : 0);
    stats->second_pass_pixels = c->firstk.second_pixels;
    stats->second_pass_packs = c->firstk.second_packs;
    /* first-K switched off captures as the counted backend does */
    stats->capture = oit_capture_kind_name(c->backend == OIT_CAPTURE_FIRSTK && c->firstk_off
                                               ? OIT_CAPTURE_COUNTED
                                               : c->backend);
    stats->capture_k = (uint32_t)c->K;
    /* how its K-slot fills were made (the counted capture has none) */
    int none = c->backend == OIT_CAPTURE_COUNTED || c->backend == OIT_CAPTURE_COMPUTE ||
               (c->backend == OIT_CAPTURE_FIRSTK && c->firstk_off);
    stats->capture_slots = none ? NULL : c->routed ? "stencil" : "array";
    stats->capture_slots_k = !none && c->routed ? (uint32_t)c->stencil.K : 0;
}

oit_status oit_capture_end(oit_capture *c, oit_image *out, oit_frame_stats *stats,
                           oit_error *err)
{
    oit_status s = finish_frame(c, err);
    if (s != OIT_OK)
        return s;
    GLuint totals[4];
    s = read_output(c, out, totals, err);
    glFinish();
    if (s == OIT_OK)
        fill_stats(c, totals, stats);
    return s;
}

oit_status oit_capture_end_gpu(oit_capture *c, unsigned *state, oit_frame_stats *stats,
                               oit_error *err)
{
    oit_status s = finish_frame(c, err);
    if (s != OIT_OK)
        return s;
    oit_gpu_timer_mark(c->timer, OIT_GPU_RESOLVE);
    end_pass(c, 0, (uint64_t)c->view.width * c->view.height, 0);
    oit_gpu_timer_mark(c->timer, OIT_GPU_READBACK);
    GLuint totals[4];
    glGetNamedBufferSubData(c->buf[BUF_TOTALS], 0, 16, totals);
    s = oit_gl_check("capture: end on the GPU", err);
    if (s != OIT_OK)
        return s;
    *state = c->buf[BUF_STATE];
    fill_stats(c, totals, stats);
    return OIT_OK;
}
