/* Unsorted blending (unsorted.h): premultiplied "over", dst = src + (1 - a)
 * dst, into an RGBA32F target cleared to the background. */
#include "view/render/baselines/unsorted.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"
#include "view/render/image/shade.h"

#include <stdlib.h>

struct oit_unsorted {
    oit_blend_passes p;
};

/* glsl/unsorted_blend.glsl */
extern const char oit_unsorted_blend_fs[];

static const oit_glsl_program program = {"unsorted blend pass",
                                         .fs = {oit_glsl_premultiplied, oit_unsorted_blend_fs}};

void oit_unsorted_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(&program, 1, visit, user);
}

static oit_status oit_unsorted_init(oit_unsorted *u, oit_error *err)
{
    static const GLenum target = GL_RGBA32F;
    return oit_blend_passes_init(&u->p, "unsorted", &program, 1, &target, 1, 1, err);
}

static void oit_unsorted_release(oit_unsorted *u)
{
    oit_blend_passes_release(&u->p);
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
    oit_glsl_raster_begin(u->p.fbo, v->width, v->height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(u->p.fbo, GL_COLOR, 0, bg);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    oit_baseline_draw(u->p.prog[0], GL_SAMPLES_PASSED, u->p.query, meshes, n);
    glDisable(GL_BLEND);
}

static oit_status oit_unsorted_render(oit_unsorted *u, const oit_gpu_mesh *const *meshes, int n,
                                      const oit_view *v, oit_image *out,
                                      oit_frame_stats *stats, oit_error *err)
{
    oit_status s = oit_blend_passes_begin(&u->p, v, err);
    if (s != OIT_OK)
        return s;
    draw(u, meshes, n, v);
    s = oit_blend_passes_end(&u->p, 0, u->p.peak, out, stats, err);
    if (s == OIT_OK && v->shading.colour_space == OIT_COLOUR_LINEAR)
        for (size_t i = 0; i < (size_t)v->width * v->height * 4; i++)
            if (i % 4 != 3)
                out->rgba[i] = (float)oit_srgb_encode(out->rgba[i]);
    return s;
}

OIT_BASELINE_METHOD(unsorted, oit_unsorted, "unsorted", 0, OIT_NO_THRESHOLD);
