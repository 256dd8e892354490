/* Weighted blended OIT (wboit.h). Accumulation uses blend state per draw
 * buffer: (ONE, ONE) on accum, (ZERO, ONE_MINUS_SRC_COLOR) on reveal. */
#include "render/baselines/wboit.h"
#include "render/baselines/methods.h"

#include "render/baselines/baseline_common.h"
#include "render/image/image.h"

#include <stdlib.h>

enum { TEX_ACCUM, TEX_REVEAL, TEX_OUT, TEX_N };
enum { PROG_ACCUM, PROG_RESOLVE, PROG_N };

struct oit_wboit {
    oit_blend_passes p;
};

static const char accum_fs[] =
    "layout(location = 0) out vec4 o_accum;\n"
    "layout(location = 1) out float o_reveal;\n"
    "float oit_weight(float t, float a) {\n"
    "    return a * clamp(10.0 / (1e-5 + pow(t / 5.0, 2.0) + pow(t / 200.0, 6.0)), 1e-2, 3e3);\n"
    "}\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    uvec4 f = oit_fragment();\n"
    "    vec4 c = oit_premultiplied(f);\n"
    "    o_accum = c * oit_weight(uintBitsToFloat(f.x), c.a);\n"
    "    o_reveal = c.a;\n"
    "}\n";

static const char resolve_cs[] =
    OIT_GLSL_TO_TEXTURE_HEAD
    "layout(binding = OIT_TEX_ACCUM) uniform sampler2D u_accum;\n"
    "layout(binding = OIT_TEX_REVEAL) uniform sampler2D u_reveal;\n"
    OIT_GLSL_TO_TEXTURE_MAIN
    "    vec4 acc = texelFetch(u_accum, px, 0);\n"
    "    float r = texelFetch(u_reveal, px, 0).r;\n"
    "    vec3 c = acc.rgb / max(acc.a, 1e-5);\n"
    "    imageStore(u_out, px, vec4(oit_output(c * (1.0 - r) + oit_background() * r), 1.0));\n"
    "}\n";

static const oit_glsl_program programs[PROG_N] = {
    [PROG_ACCUM] = {"WBOIT accumulation pass", .fs = {oit_glsl_premultiplied, accum_fs}},
    [PROG_RESOLVE] = {"WBOIT resolve", .cs = {resolve_cs}},
};

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
