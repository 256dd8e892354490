/* Stencil-routed K-sample target (capture_stencil.h). The routing draw runs
 * with multisampling off, as in the paper: each fragment then covers every
 * sample, and only the per-sample stencil test decides where it lands. */
#include "render/capture_stencil.h"

#include "render/capture_glsl.h"
#include "render/frag_glsl.h"

#include <string.h>

oit_status oit_stencil_check_limits(int K, oit_error *err)
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

oit_status oit_stencil_target_init(oit_stencil_target *t, int K, oit_error *err)
{
    memset(t, 0, sizeof *t);
    t->samples = K;
    const char *vs[] = {oit_glsl_version, oit_capture_fullscreen_vs, NULL};
    const char *fs[] = {oit_glsl_version, "void main() {}\n", NULL};
    oit_status s = oit_gl_program_graphics("stencil routing set-up", vs, fs, &t->init_prog, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &t->fbo);
        glCreateVertexArrays(1, &t->vao);
    }
    return s;
}

void oit_stencil_target_release(oit_stencil_target *t)
{
    glDeleteProgram(t->init_prog);
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
    glCreateRenderbuffers(1, &t->depth_stencil);
    glNamedRenderbufferStorageMultisample(t->depth_stencil, t->samples, GL_DEPTH24_STENCIL8, w, h);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->colour, 0);
    glNamedFramebufferRenderbuffer(t->fbo, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                   t->depth_stencil);
    GLenum status = glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER);
    t->width = w;
    t->height = h;
    oit_status s = oit_gl_check("stencil capture: multisample target", err);
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

void oit_stencil_target_route(oit_stencil_target *t, const int rect[4])
{
    bind(t, rect, GL_FALSE);
    glStencilMask(0xff);
    glStencilOp(GL_REPLACE, GL_REPLACE, GL_REPLACE);
    /* One full-screen draw per sample, masked to that sample. */
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_SAMPLE_MASK);
    glUseProgram(t->init_prog);
    glBindVertexArray(t->vao);
    for (int i = 0; i < t->samples; i++) {
        glSampleMaski(0, 1u << i);
        glStencilFunc(GL_ALWAYS, i + 1, 0xff);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glSampleMaski(0, ~0u);
    glDisable(GL_SAMPLE_MASK);
}

void oit_stencil_target_begin_draw(oit_stencil_target *t, const int rect[4])
{
    bind(t, rect, GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_MULTISAMPLE);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_DECR, GL_DECR, GL_DECR);
}

void oit_stencil_target_end_draw(void)
{
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

uint64_t oit_stencil_target_bytes(const oit_stencil_target *t)
{
    return (uint64_t)t->width * t->height * t->samples * (16 + 4);
}
