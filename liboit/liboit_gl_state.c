/* The caller's GL state (liboit_internal.h): saved and restored around a
 * draw, the blend of the capture's state into its framebuffer, and its
 * depth texture checked and bound. */
#include "liboit/liboit_internal.h"

static const GLenum kToggles[7] = {GL_BLEND,           GL_DEPTH_TEST,   GL_STENCIL_TEST,
                                   GL_CULL_FACE,       GL_SCISSOR_TEST, GL_MULTISAMPLE,
                                   GL_FRAMEBUFFER_SRGB};

void oit_lib_gl_save(gl_saved *g)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &g->draw_fb);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &g->read_fb);
    glGetIntegerv(GL_VIEWPORT, g->viewport);
    glGetIntegerv(GL_CURRENT_PROGRAM, &g->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &g->vao);
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &g->indirect);
    glGetIntegerv(GL_BLEND_SRC_RGB, &g->src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &g->dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &g->src_a);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &g->dst_a);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &g->eq_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &g->eq_a);
    glGetBooleanv(GL_COLOR_WRITEMASK, g->colour_mask);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &g->depth_mask);
    for (int i = 0; i < 7; i++)
        g->enabled[i] = glIsEnabled(kToggles[i]);
}

void oit_lib_gl_restore(const gl_saved *g)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)g->draw_fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)g->read_fb);
    glViewport(g->viewport[0], g->viewport[1], g->viewport[2], g->viewport[3]);
    /* A program the caller deleted while it was current lived only as long
     * as it stayed current (GL 4.5, 7.3): once liboit's own replaced it,
     * it is gone, and binding its name again would fail; the caller then
     * gets none, as after any glUseProgram of another. */
    glUseProgram(glIsProgram((GLuint)g->program) ? (GLuint)g->program : 0);
    glBindVertexArray((GLuint)g->vao);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, (GLuint)g->indirect);
    glBlendFuncSeparate((GLenum)g->src_rgb, (GLenum)g->dst_rgb, (GLenum)g->src_a, (GLenum)g->dst_a);
    glBlendEquationSeparate((GLenum)g->eq_rgb, (GLenum)g->eq_a);
    glColorMask(g->colour_mask[0], g->colour_mask[1], g->colour_mask[2], g->colour_mask[3]);
    glDepthMask(g->depth_mask);
    for (int i = 0; i < 7; i++)
        (g->enabled[i] ? glEnable : glDisable)(kToggles[i]);
}

/* dst = C + T * dst through dual-source blending, one fragment per pixel,
 * over the target's rect at (x, y) of v's size, the state's pixels. */
/* The blend program, built at the first draw over a framebuffer (a run
 * that only reads images back never needs it). */
oit_status oit_lib_blend_ready(oit_renderer *r, oit_error *err)
{
    if (r->blend_prog)
        return OIT_OK;
    return oit_blend_into_build(r->programs, &r->blend_prog, err);
}

void oit_lib_blend_over(const oit_renderer *r, const oit_frame *f, const oit_view *v, int x, int y,
                        GLuint state)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->framebuffer);
    glViewport(x, y, v->width, v->height);
    for (int i = 1; i < 5; i++)
        glDisable(kToggles[i]);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_SRC1_COLOR);
    /* Linear light: C and T are linear, so the blend must read and write
     * linear values; GL decodes and encodes an sRGB target's values only
     * with GL_FRAMEBUFFER_SRGB (liboit.h, Result). */
    if (v->shading.colour_space == OIT_COLOUR_LINEAR)
        glEnable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(r->blend_prog);
    glProgramUniform2i(r->blend_prog, OIT_LOC_SIZE, v->width, v->height);
    glProgramUniform2i(r->blend_prog, OIT_LOC_ORIGIN, x, y);
    /* The state buffer's layout follows the shading (frag_glsl.h). */
    glProgramUniform1i(r->blend_prog, glGetUniformLocation(r->blend_prog, "u_mode"),
                       v->shading.mode == OIT_SHADING_TRANSLUCENT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, state);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindVertexArray(r->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* oit_frame.depth_texture: a single-sample 2D depth texture covering the
 * viewport, texel (x, y) the target's pixel (x, y). */
oit_status oit_lib_check_depth_texture(const oit_frame *f, oit_error *err)
{
    GLuint tex = f->depth_texture;
    if (!glIsTexture(tex))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_frame.depth_texture = %u is not a "
                             "texture",
                             tex);
    GLint target = 0, bits = 0, w = 0, h = 0, mode = GL_DEPTH_COMPONENT;
    glGetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_frame.depth_texture = %u: target "
                             "0x%x is not GL_TEXTURE_2D",
                             tex, (unsigned)target);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_DEPTH_SIZE, &bits);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureParameteriv(tex, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    if (bits <= 0 || mode != GL_DEPTH_COMPONENT)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_frame.depth_texture = %u: level 0 "
                             "holds no depth%s",
                             tex, bits > 0 ? " (GL_DEPTH_STENCIL_TEXTURE_MODE reads stencil)" : "");
    if (f->viewport_x < 0 || f->viewport_y < 0 || w < f->viewport_x + f->viewport_width ||
        h < f->viewport_y + f->viewport_height)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_frame.depth_texture = %u: %dx%d does "
                             "not cover the viewport %d,%d %dx%d (it is of the target's size)",
                             tex, w, h, f->viewport_x, f->viewport_y, f->viewport_width,
                             f->viewport_height);
    return oit_gl_check("oit_frame.depth_texture", err);
}

/* The texture unit and sampler binding oit_renderer_draw takes for the
 * depth texture, given back after the capture. liboit.h tells callers the
 * unit by number. */
_Static_assert(OIT_TEX_OPAQUE_DEPTH == 7, "liboit.h documents texture unit 7");

void oit_lib_depth_unit_bind(const oit_renderer *r, GLuint tex, depth_unit *u)
{
    glGetIntegerv(GL_ACTIVE_TEXTURE, &u->active);
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_DEPTH);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &u->tex);
    glGetIntegerv(GL_SAMPLER_BINDING, &u->sampler);
    glBindTexture(GL_TEXTURE_2D, tex);
    glBindSampler(OIT_TEX_OPAQUE_DEPTH, r->depth_sampler);
    glActiveTexture((GLenum)u->active);
}

/* Texture unit 6 (OIT_TEX_OPAQUE_KEYS), which the opaque pre-pass binds
 * (view/render/capture/opaque_keys.h): liboit.h promises it back. */
_Static_assert(OIT_TEX_OPAQUE_KEYS == 6, "liboit.h documents texture unit 6");
GLint oit_lib_keys_unit_save(void)
{
    GLint active = 0, tex = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_KEYS);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex);
    glActiveTexture((GLenum)active);
    return tex;
}

void oit_lib_depth_unit_restore(const depth_unit *u)
{
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_DEPTH);
    glBindTexture(GL_TEXTURE_2D, (GLuint)u->tex);
    glBindSampler(OIT_TEX_OPAQUE_DEPTH, (GLuint)u->sampler);
    glActiveTexture((GLenum)u->active);
}
