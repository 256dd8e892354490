/* Dual depth peeling (dual_peel.h). Two RG32F (-nearest, farthest) targets
 * ping-pong: a pass reads one and writes the next pairs into the other,
 * cleared to -inf (no fragment: the MAX identity). A pixel whose pair reads
 * (-inf, -inf) has nothing left: every fragment is outside the interval. */
#include "view/render/baselines/dual_peel.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { BUF_FRONT, BUF_BACK, BUF_COUNT, BUF_OUT, BUF_N };
enum { IMG_FRONT, IMG_BACK, IMG_N };
enum { STATE_BYTES = 48, BACK_BYTES = 32 }; /* std430 sizes of oit_state, back_acc */
_Static_assert(STATE_BYTES <= OIT_BASELINE_PIXEL_BYTES, "frames are banded for the state");
#define MAX_PASSES 1000000u

struct oit_dual_peel {
    oit_peel_passes pp;
    GLuint minmax[2], layer[IMG_N];
    int w, h;
    oit_gpu_buffers b;
};

static const char *const buffer_names[BUF_N] = {"front state", "back state", "counters",
                                                "output"};

/* glsl/dual_peel*.glsl: the peel pass's fragment stage, the merge of the
 * front and back layers, and the final pass (glsl/dual_back_acc.glsl, the
 * back accumulation's layout, leads the last two). */
extern const char oit_dual_peel_fs[], oit_dual_peel_merge_cs[], oit_dual_peel_final_cs[];

static const oit_glsl_program programs[OIT_PEEL_PROG_N] = {
    [OIT_PEEL_PROG_PASS] = {"dual peeling pass", .fs = {oit_dual_peel_fs}},
    [OIT_PEEL_PROG_MERGE] = {"dual peeling merge",
                             .cs = {oit_glsl_composite, oit_glsl_premultiplied,
                                    oit_dual_peel_merge_cs}},
    [OIT_PEEL_PROG_FINAL] = {"dual peeling final",
                             .cs = {oit_glsl_composite, oit_dual_peel_final_cs}},
};

void oit_dual_peel_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(programs, OIT_PEEL_PROG_N, visit, user);
}

static oit_status oit_dual_peel_init(oit_dual_peel *d, oit_error *err)
{
    d->b.method = "dual peeling";
    d->b.names = buffer_names;
    return oit_peel_passes_create(&d->pp, "dual peeling", programs, err);
}

static void release_targets(oit_dual_peel *d)
{
    glDeleteTextures(2, d->minmax);
    glDeleteTextures(IMG_N, d->layer);
    memset(d->minmax, 0, sizeof d->minmax);
    memset(d->layer, 0, sizeof d->layer);
}

static void oit_dual_peel_release(oit_dual_peel *d)
{
    oit_peel_passes_release(&d->pp);
    release_targets(d);
    oit_gpu_buffers_release(&d->b);
}

static oit_status resize_targets(oit_dual_peel *d, int w, int h, oit_error *err)
{
    if (d->minmax[0] && d->w == w && d->h == h)
        return OIT_OK;
    release_targets(d);
    for (int i = 0; i < 2; i++) {
        d->minmax[i] = oit_baseline_texture(GL_RG32F, w, h);
        glNamedFramebufferTexture(d->pp.fbo[i], GL_COLOR_ATTACHMENT0, d->minmax[i], 0);
    }
    for (int i = 0; i < IMG_N; i++)
        d->layer[i] = oit_baseline_texture(GL_RGBA32UI, w, h);
    d->w = w;
    d->h = h;
    d->b.texture_bytes = (uint64_t)w * h * (2 * 8 + IMG_N * 16);
    oit_gpu_buffers_note(&d->b);
    if (glCheckNamedFramebufferStatus(d->pp.fbo[0], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return oit_error_set(err, OIT_ERR_GL, "dual peeling: the RG32F target of %dx%d is "
                             "not renderable here", w, h);
    return oit_gl_check("dual peeling: targets", err);
}

static oit_status prepare(oit_dual_peel *d, const oit_view *v, oit_error *err)
{
    if (v->shading.mode != OIT_SHADING_TRANSPARENT)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "dual peeling: translucent shading is "
                             "not supported (absorption needs all layers in front-to-back "
                             "order; the back half is composited back to front)");
    uint64_t pixels = (uint64_t)v->width * v->height;
    oit_status s = oit_gl_check_ssbo_size(pixels * STATE_BYTES, "dual peeling: the "
                                          "frame's front state", err);
    if (s == OIT_OK)
        s = resize_targets(d, v->width, v->height, err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(&d->b, BUF_N, (const uint64_t[BUF_N]){
            pixels * STATE_BYTES, pixels * BACK_BYTES, 16, pixels * 16}, err);
    if (s != OIT_OK)
        return s;
    oit_peel_passes_set_view(&d->pp, v);
    static const GLuint zero = 0;
    glClearNamedBufferData(d->b.buf[BUF_COUNT], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, d->b.buf[BUF_FRONT]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, d->b.buf[BUF_BACK]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, d->b.buf[BUF_COUNT]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, d->b.buf[BUF_OUT]);
    glBindImageTexture(OIT_IMG_FRONT, d->layer[IMG_FRONT], 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_RGBA32UI);
    glBindImageTexture(OIT_IMG_BACK, d->layer[IMG_BACK], 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_RGBA32UI);
    return oit_gl_check("dual peeling: frame set-up", err);
}

/* Draws into minmax[cur], peeling against minmax[1 - cur] unless init;
 * returns whether any fragment was left inside. */
static int peel(oit_dual_peel *d, int cur, int init, const oit_gpu_mesh *const *meshes, int n)
{
    const float none[4] = {-INFINITY, -INFINITY, 0.0f, 0.0f};
    oit_glsl_raster_begin(d->pp.fbo[cur], d->w, d->h);
    glColorMask(GL_TRUE, GL_TRUE, GL_FALSE, GL_FALSE);
    glClearNamedFramebufferfv(d->pp.fbo[cur], GL_COLOR, 0, none);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MAX);
    glBindTextureUnit(OIT_TEX_LAYER, d->minmax[1 - cur]);
    glProgramUniform1i(d->pp.peel, glGetUniformLocation(d->pp.peel, "u_init"), init);
    int any = oit_peel_passes_draw(&d->pp, meshes, n);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    return any;
}

/* Composites the layers peeled against minmax[prev]. */
static void merge(oit_dual_peel *d, int prev, int first)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(OIT_TEX_LAYER, d->minmax[prev]);
    oit_peel_passes_merge(&d->pp, first, d->w, d->h);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

/* The first pass gathers the pairs; each later one peels two layers and
 * leaves every unfinished pixel a strictly narrower interval, so the loop
 * ends; the cap only turns a driver that broke that into an error. A frame
 * without fragments still merges once, to start every pixel's state. */
static oit_status peel_all(oit_dual_peel *d, const oit_gpu_mesh *const *meshes, int n,
                           uint32_t *passes, oit_error *err)
{
    int prev = 0, first = 1;
    int more = peel(d, 0, 1, meshes, n);
    for (*passes = 1; more; ++*passes) {
        if (*passes == MAX_PASSES)
            return oit_error_set(err, OIT_ERR_GL, "dual peeling: fragments still left "
                                 "after %u passes; the driver does not keep t's order",
                                 (unsigned)MAX_PASSES);
        more = peel(d, 1 - prev, 0, meshes, n);
        merge(d, prev, first);
        first = 0;
        prev = 1 - prev;
    }
    if (first)
        merge(d, prev, 1);
    oit_baseline_dispatch_frame(d->pp.final, d->w, d->h);
    return oit_gl_check("dual peeling: passes", err);
}

static oit_status oit_dual_peel_render(oit_dual_peel *d, const oit_gpu_mesh *const *meshes, int n,
                                       const oit_view *v, oit_image *out,
                                       oit_frame_stats *stats, oit_error *err)
{
    uint32_t passes = 0;
    GLuint figures[2] = {0, 0}; /* fragments, max_len */
    oit_status s = prepare(d, v, err);
    if (s == OIT_OK)
        s = peel_all(d, meshes, n, &passes, err);
    if (s == OIT_OK) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(d->b.buf[BUF_COUNT], 0, 8, figures);
        s = oit_baseline_read_buffer("dual peeling", d->b.buf[BUF_OUT], v->width, v->height,
                                     out, err);
    }
    *stats = (oit_frame_stats){.fragments = figures[0], .max_layers = figures[1],
                               .gpu_bytes_peak = d->b.peak, .batches = passes};
    return s;
}

OIT_BASELINE_METHOD(ddp, oit_dual_peel, "dual peeling", 0, OIT_NO_THRESHOLD);
