/* Unsorted blending (unsorted.h): premultiplied "over", dst = src + (1 - a)
 * dst, into an RGBA32F target cleared to the background. */
#include "render/baselines/unsorted.h"
#include "render/baselines/methods.h"

#include "render/baselines/baseline_common.h"
#include "render/image.h"
#include "render/shade.h"

#include <stdlib.h>

struct oit_unsorted {
    GLuint prog, fbo, tex, query;
    int w, h;
    uint64_t bytes_peak;
};

static const char blend_fs[] =
    "layout(location = 0) out vec4 o_colour;\n"
    "void main() { o_colour = oit_premultiplied(oit_fragment()); }\n";

static void oit_unsorted_destroy(oit_unsorted *self);

static oit_status oit_unsorted_create(oit_unsorted **out, oit_error *err)
{
    *out = NULL;
    oit_unsorted *u = calloc(1, sizeof *u);
    if (!u)
        return oit_error_set(err, OIT_ERR_NOMEM, "unsorted: out of memory");
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *fs[] = {oit_glsl_version, oit_glsl_fragment_gen, oit_glsl_premultiplied,
                        blend_fs, NULL};
    oit_status s = oit_gl_program_graphics("unsorted blend pass", vs, fs, &u->prog, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &u->fbo);
        glCreateQueries(GL_SAMPLES_PASSED, 1, &u->query);
        s = oit_gl_check("unsorted: framebuffer and query", err);
    }
    if (s != OIT_OK) {
        oit_unsorted_destroy(u);
        return s;
    }
    *out = u;
    return OIT_OK;
}

static void oit_unsorted_destroy(oit_unsorted *u)
{
    if (!u)
        return;
    glDeleteProgram(u->prog);
    glDeleteFramebuffers(1, &u->fbo);
    glDeleteTextures(1, &u->tex);
    glDeleteQueries(1, &u->query);
    free(u);
}

static oit_status resize(oit_unsorted *u, int w, int h, oit_error *err)
{
    if (u->tex && u->w == w && u->h == h)
        return OIT_OK;
    glDeleteTextures(1, &u->tex);
    glCreateTextures(GL_TEXTURE_2D, 1, &u->tex);
    glTextureStorage2D(u->tex, 1, GL_RGBA32F, w, h);
    glNamedFramebufferTexture(u->fbo, GL_COLOR_ATTACHMENT0, u->tex, 0);
    u->w = w;
    u->h = h;
    uint64_t bytes = (uint64_t)w * h * 16;
    if (bytes > u->bytes_peak)
        u->bytes_peak = bytes;
    return oit_gl_check("unsorted: RGBA32F target", err);
}

static void draw(oit_unsorted *u, const oit_gpu_mesh *const *meshes, int n,
                 const oit_view *v)
{
    float bg[4] = {0, 0, 0, 0};
    for (int c = 0; c < 3; c++)
        bg[c] = v->shading.background[c] > 0.0f ? v->shading.background[c] : 0.0f;
    /* Linear light (shade.h, "Colour space"): the float target blends in
     * linear light over the decoded background; the readback is encoded. */
    for (int c = 0; c < 3 && v->shading.colour_space == OIT_COLOUR_LINEAR; c++)
        bg[c] = (float)oit_srgb_decode(bg[c]);
    oit_glsl_raster_begin(u->fbo, v->width, v->height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(u->fbo, GL_COLOR, 0, bg);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    oit_baseline_draw(u->prog, GL_SAMPLES_PASSED, u->query, meshes, n);
    glDisable(GL_BLEND);
}

static oit_status oit_unsorted_render(oit_unsorted *u, const oit_gpu_mesh *const *meshes, int n,
                                      const oit_view *view, oit_image *out,
                                      oit_frame_stats *stats, oit_error *err)
{
    oit_view v;
    double t0;
    oit_status s = oit_baseline_begin("unsorted", view, n, &v, &t0, err);
    if (s != OIT_OK)
        return s;
    s = resize(u, v.width, v.height, err);
    if (s != OIT_OK)
        return s;
    oit_glsl_set_view(u->prog, &v);
    draw(u, meshes, n, &v);
    s = oit_gl_check("unsorted: blend pass", err);
    if (s == OIT_OK)
        s = oit_baseline_read_texture("unsorted", u->tex, v.width, v.height, out, err);
    if (s == OIT_OK && v.shading.colour_space == OIT_COLOUR_LINEAR)
        for (size_t i = 0; i < (size_t)v.width * v.height * 4; i++)
            if (i % 4 != 3)
                out->rgba[i] = (float)oit_srgb_encode(out->rgba[i]);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(u->query, GL_QUERY_RESULT, &samples);
    if (s != OIT_OK || !stats)
        return s;
    oit_baseline_stats(stats, t0, samples, 0, u->bytes_peak, 1);
    return OIT_OK;
}

OIT_BASELINE_METHOD(unsorted, oit_unsorted, 0, OIT_NO_THRESHOLD);
