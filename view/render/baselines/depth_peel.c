/* Depth peeling (depth_peel.h). Two layer targets (RGBA32UI, the packed
 * fragment) ping-pong: one is written, the other read as the layer before.
 * A pass clears its target to t = +inf (EXHAUSTED), so a pixel where it
 * keeps nothing discards everything from then on; before the first pass
 * the previous layer reads t bits 0, below every fragment's. The composite state
 * is the GLSL oit_state per pixel in a buffer, GL row order. */
#include "view/render/baselines/depth_peel.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"

#include <math.h>
#include <stdlib.h>

enum { BUF_STATE, BUF_COUNT, BUF_OUT, BUF_N };
enum { STATE_BYTES = 48 }; /* std430 size of oit_state */
_Static_assert(STATE_BYTES <= OIT_BASELINE_PIXEL_BYTES, "frames are banded for the state");
#define EXHAUSTED 0x7f800000u /* bits of +inf */
#define MAX_PASSES 1000000u

struct oit_depth_peel {
    oit_peel_passes pp;
    GLuint layer[2], depth;
    int w, h;
    oit_gpu_buffers b;
};

static const char *const buffer_names[BUF_N] = {"state", "counter", "output"};

/* glsl/depth_peel*.glsl: the peel pass's fragment stage, the merge of a
 * layer into the state, and the final pass. */
extern const char oit_depth_peel_fs[], oit_depth_peel_merge_cs[], oit_depth_peel_final_cs[];

static const oit_glsl_program programs[OIT_PEEL_PROG_N] = {
    [OIT_PEEL_PROG_PASS] = {"depth peeling pass", .fs = {oit_depth_peel_fs}},
    [OIT_PEEL_PROG_MERGE] = {"depth peeling merge",
                             .cs = {oit_glsl_composite, oit_depth_peel_merge_cs}},
    [OIT_PEEL_PROG_FINAL] = {"depth peeling final",
                             .cs = {oit_glsl_composite, oit_depth_peel_final_cs}},
};

void oit_depth_peel_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(programs, OIT_PEEL_PROG_N, visit, user);
}

static oit_status oit_depth_peel_init(oit_depth_peel *d, oit_error *err)
{
    d->b.method = "depth peeling";
    d->b.names = buffer_names;
    return oit_peel_passes_create(&d->pp, "depth peeling", programs, err);
}

static void release_targets(oit_depth_peel *d)
{
    glDeleteTextures(2, d->layer);
    glDeleteTextures(1, &d->depth);
    d->layer[0] = d->layer[1] = d->depth = 0;
}

static void oit_depth_peel_release(oit_depth_peel *d)
{
    oit_peel_passes_release(&d->pp);
    release_targets(d);
    oit_gpu_buffers_release(&d->b);
}

static oit_status resize_targets(oit_depth_peel *d, int w, int h, oit_error *err)
{
    if (d->depth && d->w == w && d->h == h)
        return OIT_OK;
    release_targets(d);
    d->depth = oit_baseline_texture(GL_DEPTH_COMPONENT32F, w, h);
    for (int i = 0; i < 2; i++) {
        d->layer[i] = oit_baseline_texture(GL_RGBA32UI, w, h);
        glNamedFramebufferTexture(d->pp.fbo[i], GL_COLOR_ATTACHMENT0, d->layer[i], 0);
        glNamedFramebufferTexture(d->pp.fbo[i], GL_DEPTH_ATTACHMENT, d->depth, 0);
    }
    d->w = w;
    d->h = h;
    d->b.texture_bytes = (uint64_t)w * h * (2 * 16 + 4);
    oit_gpu_buffers_note(&d->b);
    if (glCheckNamedFramebufferStatus(d->pp.fbo[0], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return oit_error_set(err, OIT_ERR_GL, "depth peeling: the RGBA32UI + DEPTH32F "
                             "target of %dx%d is not renderable here", w, h);
    return oit_gl_check("depth peeling: layer targets", err);
}

/* The inverse of a power of two above twice the largest t a kept fragment
 * can have (view depth <= zfar, along the steepest corner ray; twice for
 * rounding at the clip planes), so that t times it lies in [0, 1) and keeps
 * t's order exactly: a depth clamped to 1 would make ties. */
static float depth_scale(const oit_view *v)
{
    const oit_camera *c = &v->camera;
    double aspect = (double)v->width / v->height, t_max;
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC) {
        t_max = (double)c->zfar - c->znear; /* parallel rays from the near plane */
    } else {
        /* The steepest corner ray of the window (oit_camera_window). */
        double w[4];
        oit_camera_window(c, aspect, w);
        double sx = fmax(fabs(w[0]), fabs(w[1])), sy = fmax(fabs(w[2]), fabs(w[3]));
        t_max = c->zfar * sqrt(1.0 + sx * sx + sy * sy);
    }
    int e = 0;
    frexp(t_max, &e);
    return (float)ldexp(1.0, -(e + 1));
}

static oit_status prepare(oit_depth_peel *d, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    /* The depth buffer holds t scaled into [0, 1): it needs a bound on t. */
    if (isinf(v->camera.zfar))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "depth peeling: an infinite far plane "
                             "leaves no bound to scale depths by; give a finite zfar");
    oit_status s = oit_gl_check_ssbo_size(pixels * STATE_BYTES, "depth peeling: the "
                                          "frame's composite state", err);
    if (s == OIT_OK)
        s = resize_targets(d, v->width, v->height, err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(
            &d->b, BUF_N, (const uint64_t[BUF_N]){pixels * STATE_BYTES, 16, pixels * 16}, err);
    if (s != OIT_OK)
        return s;
    oit_peel_passes_set_view(&d->pp, v);
    glProgramUniform1f(d->pp.peel, glGetUniformLocation(d->pp.peel, "u_depth_scale"),
                       depth_scale(v));
    static const GLuint zero[4] = {0, 0, 0, 0};
    glClearTexImage(d->layer[1], 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero);
    glClearNamedBufferData(d->b.buf[BUF_COUNT], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, d->b.buf[BUF_STATE]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, d->b.buf[BUF_COUNT]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, d->b.buf[BUF_OUT]);
    return oit_gl_check("depth peeling: frame set-up", err);
}

/* Peels the layer behind layer[1 - cur] into layer[cur]; returns whether any
 * fragment was kept. */
static int peel(oit_depth_peel *d, int cur, const oit_gpu_mesh *const *meshes, int n)
{
    static const GLuint exhausted[4] = {EXHAUSTED, 0, 0, 0};
    static const float far_depth = 1.0f;
    oit_glsl_raster_begin(d->pp.fbo[cur], d->w, d->h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferuiv(d->pp.fbo[cur], GL_COLOR, 0, exhausted);
    glClearNamedFramebufferfv(d->pp.fbo[cur], GL_DEPTH, 0, &far_depth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindTextureUnit(OIT_TEX_LAYER, d->layer[1 - cur]);
    int any = oit_peel_passes_draw(&d->pp, meshes, n);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    return any;
}

static void merge(oit_depth_peel *d, int cur, int first)
{
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glBindTextureUnit(OIT_TEX_LAYER, d->layer[cur]);
    oit_peel_passes_merge(&d->pp, first, d->w, d->h);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Peels until a pass keeps nothing; the first merge always runs so that an
 * empty frame still starts every pixel's state. Each pass moves every
 * unfinished pixel strictly further back, so the loop ends after
 * max_layers + 1 passes; the cap only turns a driver that broke that into
 * an error instead of a hang. */
static oit_status peel_all(oit_depth_peel *d, const oit_gpu_mesh *const *meshes, int n,
                           uint32_t *layers, uint32_t *passes, oit_error *err)
{
    int cur = 0, more = 1;
    *layers = 0;
    *passes = 0;
    while (more) {
        if (*passes == MAX_PASSES)
            return oit_error_set(err, OIT_ERR_GL, "depth peeling: fragments still pass "
                                 "after %u layers; the driver does not keep t's order",
                                 (unsigned)MAX_PASSES);
        more = peel(d, cur, meshes, n);
        ++*passes;
        if (more || *passes == 1)
            merge(d, cur, *passes == 1);
        *layers += (uint32_t)more;
        cur = 1 - cur;
    }
    oit_baseline_dispatch_frame(d->pp.final, d->w, d->h);
    return oit_gl_check("depth peeling: passes", err);
}

static oit_status oit_depth_peel_render(oit_depth_peel *d, const oit_gpu_mesh *const *meshes,
                                        int n, const oit_view *v, oit_image *out,
                                        oit_frame_stats *stats, oit_error *err)
{
    oit_status s = prepare(d, v, err);
    if (s != OIT_OK)
        return s;
    uint32_t layers = 0, passes = 0;
    s = peel_all(d, meshes, n, &layers, &passes, err);
    GLuint fragments = 0;
    if (s == OIT_OK) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(d->b.buf[BUF_COUNT], 0, 4, &fragments);
        s = oit_baseline_read_buffer("depth peeling", d->b.buf[BUF_OUT], v->width, v->height,
                                     out, err);
    }
    *stats = (oit_frame_stats){.fragments = fragments, .max_layers = layers,
                               .gpu_bytes_peak = d->b.peak, .batches = passes};
    return s;
}

OIT_BASELINE_METHOD(dp, oit_depth_peel, "depth peeling", 0, OIT_NO_THRESHOLD);
