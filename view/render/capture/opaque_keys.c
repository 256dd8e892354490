/* The opaque pre-pass (opaque_keys.h). */
#include "view/render/capture/opaque_keys.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

struct oit_opaque_keys {
    GLuint prog, fbo, tex;
    int w, h;  /* the texture's size */
    int on;    /* this frame has opaque triangles */
    int width, height; /* the frame's */
};
_Static_assert(offsetof(struct oit_opaque_keys, prog) == 0,
               "oit_glsl_module_create builds the first member");

extern const char oit_opaque_keys_fs[]; /* glsl/opaque_keys.glsl */
static const oit_glsl_program program = {"opaque keys", .fs = {oit_opaque_keys_fs}};

void oit_opaque_keys_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &program);
}

oit_status oit_opaque_keys_create(oit_opaque_keys **out, oit_error *err)
{
    oit_status st;
    oit_opaque_keys *k = oit_glsl_module_create(sizeof *k, &program, "opaque keys", &st, err);
    if (k)
        glCreateFramebuffers(1, &k->fbo);
    *out = k;
    return st;
}

void oit_opaque_keys_destroy(oit_opaque_keys *k)
{
    if (!k)
        return;
    glDeleteProgram(k->prog);
    glDeleteFramebuffers(1, &k->fbo);
    glDeleteTextures(1, &k->tex);
    free(k);
}

/* A texture of at least the frame's size; kept across frames. */
static oit_status ensure_texture(oit_opaque_keys *k, int w, int h, oit_error *err)
{
    if (k->tex && k->w >= w && k->h >= h)
        return OIT_OK;
    glDeleteTextures(1, &k->tex);
    k->w = w > k->w ? w : k->w;
    k->h = h > k->h ? h : k->h;
    glCreateTextures(GL_TEXTURE_2D, 1, &k->tex);
    glTextureStorage2D(k->tex, 1, GL_R32F, k->w, k->h);
    glNamedFramebufferTexture(k->fbo, GL_COLOR_ATTACHMENT0, k->tex, 0);
    glNamedFramebufferDrawBuffer(k->fbo, GL_COLOR_ATTACHMENT0);
    GLenum status = glCheckNamedFramebufferStatus(k->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return oit_error_set(err, OIT_ERR_GL, "opaque keys: an r32f framebuffer of %dx%d is "
                             "incomplete (0x%x)", k->w, k->h, status);
    return oit_gl_check("opaque keys: texture", err);
}

oit_status oit_opaque_keys_begin(oit_opaque_keys *k, const oit_view *v, const oit_opaque_depth *o,
                                 int *on, oit_error *err)
{
    k->on = *on = oit_shading_opaque(&v->shading);
    if (!k->on)
        return OIT_OK;
    oit_status st = ensure_texture(k, v->width, v->height, err);
    if (st != OIT_OK) {
        k->on = *on = 0;
        return st;
    }
    k->width = v->width;
    k->height = v->height;
    const float inf = INFINITY;
    glClearTexImage(k->tex, 0, GL_RED, GL_FLOAT, &inf);
    oit_glsl_set_view(k->prog, v);
    oit_glsl_set_opaque(k->prog, o); /* the caller's projection, when given */
    glBindTextureUnit(OIT_TEX_OPAQUE_KEYS, k->tex);
    return oit_gl_check("opaque keys: begin", err);
}

void oit_opaque_keys_draw(oit_opaque_keys *k, struct oit_gpu_draws *draws,
                          const oit_gpu_mesh *const *meshes, int n, const int r[4])
{
    if (!k->on || n <= 0)
        return;
    /* Not a feedback loop: the captures sample the texture, this pass
     * alone renders to it, and GL orders a draw's framebuffer writes
     * before later draws' texture fetches. */
    glBindTextureUnit(OIT_TEX_OPAQUE_KEYS, 0);
    oit_glsl_raster_begin(k->fbo, k->width, k->height);
    glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
    glUseProgram(k->prog);
    if (draws)
        oit_gpu_mesh_draw_many(draws, meshes, n);
    else
        for (int i = 0; i < n; i++)
            oit_gpu_mesh_draw(meshes[i], k->prog);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glBindTextureUnit(OIT_TEX_OPAQUE_KEYS, k->tex);
}

uint64_t oit_opaque_keys_gpu_bytes(const oit_opaque_keys *k)
{
    return k && k->tex ? (uint64_t)k->w * (uint64_t)k->h * 4u : 0;
}
