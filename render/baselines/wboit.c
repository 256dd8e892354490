/* Weighted blended OIT (wboit.h). Accumulation uses blend state per draw
 * buffer: (ONE, ONE) on accum, (ZERO, ONE_MINUS_SRC_COLOR) on reveal. */
#include "render/baselines/wboit.h"
#include "render/baselines/methods.h"

#include "render/baselines/baseline_common.h"
#include "render/image.h"

#include <stdlib.h>

enum { TEX_ACCUM, TEX_REVEAL, TEX_OUT, TEX_N };

struct oit_wboit {
    GLuint accum_prog, resolve_prog, fbo, query;
    GLuint tex[TEX_N];
    int w, h;
    uint64_t bytes_peak;
};

static const char accum_fs[] =
    "layout(location = 0) out vec4 o_accum;\n"
    "layout(location = 1) out float o_reveal;\n"
    "float oit_weight(float t, float a) {\n"
    "    return a * clamp(10.0 / (1e-5 + pow(t / 5.0, 2.0) + pow(t / 200.0, 6.0)), 1e-2, 3e3);\n"
    "}\n"
    "void main() {\n"
    "    uvec4 f = oit_fragment();\n"
    "    vec4 c = oit_premultiplied(f);\n"
    "    o_accum = c * oit_weight(uintBitsToFloat(f.x), c.a);\n"
    "    o_reveal = c.a;\n"
    "}\n";

static const char resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(location = 9) uniform vec3 u_background;\n"
    "uniform int u_colour_space;\n"
    OIT_GLSL_SRGB_FUNCS
    OIT_GLSL_OUTPUT
    "layout(binding = OIT_TEX_ACCUM) uniform sampler2D u_accum;\n"
    "layout(binding = OIT_TEX_REVEAL) uniform sampler2D u_reveal;\n"
    "layout(rgba32f, binding = OIT_IMG_OUT) writeonly uniform image2D u_out;\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_size.x || px.y >= u_size.y) return;\n"
    "    vec4 acc = texelFetch(u_accum, px, 0);\n"
    "    float r = texelFetch(u_reveal, px, 0).r;\n"
    "    vec3 c = acc.rgb / max(acc.a, 1e-5);\n"
    "    imageStore(u_out, px, vec4(oit_output(c * (1.0 - r) + oit_background() * r), 1.0));\n"
    "}\n";

static oit_status build_programs(oit_wboit *w, oit_error *err)
{
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *fs[] = {oit_glsl_version, oit_glsl_fragment_gen, oit_glsl_premultiplied,
                        accum_fs, NULL};
    const char *cs[] = {oit_glsl_version, resolve_cs, NULL};
    oit_status s = oit_gl_program_graphics("WBOIT accumulation pass", vs, fs, &w->accum_prog,
                                           err);
    if (s == OIT_OK)
        s = oit_gl_program_compute("WBOIT resolve", cs, &w->resolve_prog, err);
    return s;
}

static void oit_wboit_destroy(oit_wboit *self);

static oit_status oit_wboit_create(oit_wboit **out, oit_error *err)
{
    *out = NULL;
    oit_wboit *w = calloc(1, sizeof *w);
    if (!w)
        return oit_error_set(err, OIT_ERR_NOMEM, "WBOIT: out of memory");
    oit_status s = build_programs(w, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &w->fbo);
        glCreateQueries(GL_SAMPLES_PASSED, 1, &w->query);
        s = oit_gl_check("WBOIT: framebuffer and query", err);
    }
    if (s != OIT_OK) {
        oit_wboit_destroy(w);
        return s;
    }
    *out = w;
    return OIT_OK;
}

static void oit_wboit_destroy(oit_wboit *w)
{
    if (!w)
        return;
    glDeleteProgram(w->accum_prog);
    glDeleteProgram(w->resolve_prog);
    glDeleteFramebuffers(1, &w->fbo);
    glDeleteQueries(1, &w->query);
    glDeleteTextures(TEX_N, w->tex);
    free(w);
}

static oit_status resize(oit_wboit *w, int width, int height, oit_error *err)
{
    if (w->tex[0] && w->w == width && w->h == height)
        return OIT_OK;
    static const GLenum formats[TEX_N] = {GL_RGBA32F, GL_R32F, GL_RGBA32F};
    glDeleteTextures(TEX_N, w->tex);
    glCreateTextures(GL_TEXTURE_2D, TEX_N, w->tex);
    for (int i = 0; i < TEX_N; i++)
        glTextureStorage2D(w->tex[i], 1, formats[i], width, height);
    glNamedFramebufferTexture(w->fbo, GL_COLOR_ATTACHMENT0, w->tex[TEX_ACCUM], 0);
    glNamedFramebufferTexture(w->fbo, GL_COLOR_ATTACHMENT1, w->tex[TEX_REVEAL], 0);
    static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(w->fbo, 2, bufs);
    w->w = width;
    w->h = height;
    uint64_t bytes = (uint64_t)width * height * (16 + 4 + 16);
    if (bytes > w->bytes_peak)
        w->bytes_peak = bytes;
    return oit_gl_check("WBOIT: float targets", err);
}

static void accumulate(oit_wboit *w, const oit_gpu_mesh *const *meshes, int n)
{
    static const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
    oit_glsl_raster_begin(w->fbo, w->w, w->h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(w->fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(w->fbo, GL_COLOR, 1, one);
    glEnable(GL_BLEND);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
    oit_baseline_draw(w->accum_prog, GL_SAMPLES_PASSED, w->query, meshes, n);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
}

static void resolve(oit_wboit *w)
{
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(OIT_TEX_ACCUM, w->tex[TEX_ACCUM]);
    glBindTextureUnit(OIT_TEX_REVEAL, w->tex[TEX_REVEAL]);
    glBindImageTexture(OIT_IMG_OUT, w->tex[TEX_OUT], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    oit_baseline_dispatch_frame(w->resolve_prog, w->w, w->h);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
}

static oit_status oit_wboit_render(oit_wboit *w, const oit_gpu_mesh *const *meshes, int n,
                                   const oit_view *view, oit_image *out,
                                   oit_frame_stats *stats, oit_error *err)
{
    oit_view v;
    double t0;
    oit_status s = oit_baseline_begin("WBOIT", view, n, &v, &t0, err);
    if (s != OIT_OK)
        return s;
    s = resize(w, v.width, v.height, err);
    if (s != OIT_OK)
        return s;
    oit_glsl_set_view(w->accum_prog, &v);
    oit_glsl_set_view(w->resolve_prog, &v);
    accumulate(w, meshes, n);
    resolve(w);
    s = oit_gl_check("WBOIT: passes", err);
    if (s == OIT_OK)
        s = oit_baseline_read_texture("WBOIT", w->tex[TEX_OUT], v.width, v.height, out, err);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(w->query, GL_QUERY_RESULT, &samples);
    if (s != OIT_OK || !stats)
        return s;
    oit_baseline_stats(stats, t0, samples, 0, w->bytes_peak, 1);
    return OIT_OK;
}

OIT_BASELINE_METHOD(wboit, oit_wboit, 0, OIT_NO_THRESHOLD);
