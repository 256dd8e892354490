/* Weighted blended OIT (wboit.h). Accumulation uses blend state per draw
 * buffer: (ONE, ONE) on accum, (ZERO, ONE_MINUS_SRC_COLOR) on reveal. */
#include "view/render/baselines/wboit.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"

#include <stdlib.h>

enum { TEX_ACCUM, TEX_REVEAL, TEX_OUT, TEX_N };
enum { PROG_ACCUM, PROG_RESOLVE, PROG_N };

struct oit_wboit {
    oit_blend_passes p;
};

/* glsl/wboit_*.glsl: the accumulation's fragment stage and the resolve
 * (after oit_glsl_to_texture). */
extern const char oit_wboit_accum_fs[], oit_wboit_resolve_cs[];

static const oit_glsl_program programs[PROG_N] = {
    [PROG_ACCUM] = {"WBOIT accumulation pass", .fs = {oit_glsl_premultiplied, oit_wboit_accum_fs}},
    [PROG_RESOLVE] = {"WBOIT resolve", .cs = {oit_glsl_to_texture, oit_wboit_resolve_cs}},
};

void oit_wboit_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(programs, PROG_N, visit, user);
}

static oit_status oit_wboit_init(oit_wboit *w, oit_error *err)
{
    static const GLenum formats[TEX_N] = {GL_RGBA32F, GL_R32F, GL_RGBA32F};
    return oit_blend_passes_init(&w->p, "WBOIT", programs, PROG_N, formats, TEX_N, 2, err);
}

static void oit_wboit_release(oit_wboit *w)
{
    oit_blend_passes_release(&w->p);
}

static void accumulate(oit_blend_passes *p, const oit_gpu_mesh *const *meshes, int n)
{
    static const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
    oit_glsl_raster_begin(p->fbo, p->w, p->h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(p->fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(p->fbo, GL_COLOR, 1, one);
    glEnable(GL_BLEND);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
    oit_baseline_draw(p->prog[PROG_ACCUM], GL_SAMPLES_PASSED, p->query, meshes, n);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
}

static void resolve(oit_blend_passes *p)
{
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(OIT_TEX_ACCUM, p->tex[TEX_ACCUM]);
    glBindTextureUnit(OIT_TEX_REVEAL, p->tex[TEX_REVEAL]);
    oit_baseline_dispatch_to_texture(p->prog[PROG_RESOLVE], p->tex[TEX_OUT], p->w, p->h);
}

static oit_status oit_wboit_render(oit_wboit *w, const oit_gpu_mesh *const *meshes, int n,
                                   const oit_view *v, oit_image *out, oit_frame_stats *stats,
                                   oit_error *err)
{
    oit_status s = oit_blend_passes_begin(&w->p, v, err);
    if (s != OIT_OK)
        return s;
    accumulate(&w->p, meshes, n);
    resolve(&w->p);
    return oit_blend_passes_end(&w->p, TEX_OUT, w->p.peak, out, stats, err);
}

OIT_BASELINE_METHOD(wboit, oit_wboit, "WBOIT", 0, OIT_NO_THRESHOLD);
