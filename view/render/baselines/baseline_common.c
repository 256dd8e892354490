/* Shared pieces of the baseline methods (baseline_common.h). */
#include "view/render/baselines/baseline_common.h"

#include "base/clock.h"
#include "view/render/image/image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The GLSL of oit_glsl_premultiplied, oit_glsl_sorted_resolve and
 * oit_glsl_to_texture is embedded from glsl/ (render/CMakeLists.txt). */

oit_status oit_gpu_buffers_reserve(oit_gpu_buffers *b, int which, uint64_t bytes,
                                   oit_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "%s %s", b->method, b->names[which]);
    oit_status s = oit_gl_buffer_reserve(&b->buf[which], &b->cap[which], bytes, what, err);
    oit_gpu_buffers_note(b);
    return s;
}

oit_status oit_gpu_buffers_reserve_all(oit_gpu_buffers *b, int n, const uint64_t *bytes,
                                       oit_error *err)
{
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++)
        if (bytes[i])
            s = oit_gpu_buffers_reserve(b, i, bytes[i], err);
    return s;
}

void oit_gpu_buffers_note(oit_gpu_buffers *b)
{
    uint64_t held = b->texture_bytes;
    for (int i = 0; i < OIT_GPU_BUFFERS_MAX; i++)
        held += b->cap[i];
    if (held > b->peak)
        b->peak = held;
}

void oit_gpu_buffers_release(oit_gpu_buffers *b)
{
    glDeleteBuffers(OIT_GPU_BUFFERS_MAX, b->buf);
    memset(b->buf, 0, sizeof b->buf);
    memset(b->cap, 0, sizeof b->cap);
}

oit_status oit_peel_passes_create(oit_peel_passes *p, const char *method,
                                  const oit_glsl_program programs[OIT_PEEL_PROG_N], oit_error *err)
{
    GLuint progs[OIT_PEEL_PROG_N] = {0, 0, 0};
    oit_status s = oit_glsl_programs_build(NULL, programs, OIT_PEEL_PROG_N, progs, err);
    p->peel = progs[OIT_PEEL_PROG_PASS];
    p->merge = progs[OIT_PEEL_PROG_MERGE];
    p->final = progs[OIT_PEEL_PROG_FINAL];
    if (s != OIT_OK)
        return s;
    glCreateFramebuffers(2, p->fbo);
    glCreateQueries(GL_ANY_SAMPLES_PASSED, 1, &p->query);
    char what[96];
    snprintf(what, sizeof what, "%s: framebuffers and query", method);
    return oit_gl_check(what, err);
}

void oit_peel_passes_release(oit_peel_passes *p)
{
    glDeleteProgram(p->peel);
    glDeleteProgram(p->merge);
    glDeleteProgram(p->final);
    glDeleteFramebuffers(2, p->fbo);
    glDeleteQueries(1, &p->query);
    memset(p, 0, sizeof *p);
}

void oit_peel_passes_set_view(const oit_peel_passes *p, const oit_view *v)
{
    oit_glsl_set_view(p->peel, v);
    oit_glsl_set_view(p->merge, v);
    oit_glsl_set_view(p->final, v);
}

int oit_peel_passes_draw(const oit_peel_passes *p, const oit_gpu_mesh *const *meshes, int n)
{
    oit_baseline_draw(p->peel, GL_ANY_SAMPLES_PASSED, p->query, meshes, n);
    GLuint any = 0;
    glGetQueryObjectuiv(p->query, GL_QUERY_RESULT, &any);
    return any != 0;
}

void oit_peel_passes_merge(const oit_peel_passes *p, int first, int w, int h)
{
    glProgramUniform1i(p->merge, glGetUniformLocation(p->merge, "u_first"), first);
    oit_baseline_dispatch_frame(p->merge, w, h);
}

void oit_baseline_draw(GLuint prog, GLenum query_target, GLuint query,
                       const oit_gpu_mesh *const *meshes, int n)
{
    glUseProgram(prog);
    if (query)
        glBeginQuery(query_target, query);
    for (int i = 0; i < n; i++)
        oit_gpu_mesh_draw(meshes[i], prog);
    if (query)
        glEndQuery(query_target);
}

void oit_baseline_dispatch_frame(GLuint prog, int w, int h)
{
    glUseProgram(prog);
    glDispatchCompute(oit_gl_groups((uint64_t)w, 8), oit_gl_groups((uint64_t)h, 8), 1);
}

void oit_baseline_dispatch_to_texture(GLuint prog, GLuint out, int w, int h)
{
    glBindImageTexture(OIT_IMG_OUT, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    oit_baseline_dispatch_frame(prog, w, h);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
}

uint64_t oit_baseline_pixel_bytes(const void *impl, const oit_view *view)
{
    (void)impl;
    (void)view;
    return OIT_BASELINE_PIXEL_BYTES;
}

oit_status oit_baseline_begin(const char *method, const oit_view *view, int n,
                              oit_baseline_frame *fr, oit_error *err)
{
    memset(fr, 0, sizeof *fr);
    fr->t0 = oit_time_ms();
    fr->view = *view;
    oit_view *v = &fr->view;
    oit_shading_resolve_defaults(&v->shading);
    GLint max_w = 0, max_h = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
    if (v->width <= 0 || v->height <= 0 || v->width > max_w || v->height > max_h || n < 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: frame %dx%d (with %d meshes) is "
                             "not renderable (at most %dx%d pixels)", method, v->width,
                             v->height, n, max_w, max_h);
    return OIT_OK;
}

oit_status oit_baseline_end(oit_baseline_frame *fr, oit_frame_stats *stats, oit_status s)
{
    if (s == OIT_OK && stats) {
        *stats = fr->stats;
        stats->ms = oit_time_ms() - fr->t0;
    }
    return s;
}

GLuint oit_baseline_texture(GLenum format, int w, int h)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    oit_gl_poison_texture(t, format);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

static oit_status read_any(const char *method, GLuint obj, int is_texture, int w, int h,
                           oit_image *out, oit_error *err)
{
    oit_status s = oit_image_alloc(out, w, h, err);
    if (s == OIT_OK)
        s = oit_gl_read_rows(obj, is_texture, w, h, 16, out->rgba, method, err);
    if (s != OIT_OK) {
        oit_image_free(out);
        return s;
    }
    for (size_t i = 3; i < (size_t)w * h * 4; i += 4)
        out->rgba[i] = 1.0f;
    return OIT_OK;
}

oit_status oit_baseline_read_texture(const char *method, GLuint tex, int w, int h,
                                     oit_image *out, oit_error *err)
{
    return read_any(method, tex, 1, w, h, out, err);
}

oit_status oit_baseline_read_buffer(const char *method, GLuint buf, int w, int h,
                                    oit_image *out, oit_error *err)
{
    return read_any(method, buf, 0, w, h, out, err);
}

oit_status oit_blend_passes_init(oit_blend_passes *p, const char *method,
                                 const oit_glsl_program *programs, int n_prog,
                                 const GLenum *formats, int n_tex, int attached, oit_error *err)
{
    p->method = method;
    p->n_prog = n_prog;
    p->n_tex = n_tex;
    p->attached = attached;
    memcpy(p->format, formats, sizeof *formats * (size_t)n_tex);
    char what[96];
    snprintf(what, sizeof what, "%s: framebuffer and query", method);
    oit_status s = oit_glsl_programs_build(NULL, programs, n_prog, p->prog, err);
    if (s == OIT_OK)
        s = oit_gl_framebuffer_create(&p->fbo, &p->query, what, err);
    return s;
}

void oit_blend_passes_release(oit_blend_passes *p)
{
    oit_glsl_programs_delete(p->prog, p->n_prog);
    glDeleteFramebuffers(1, &p->fbo);
    glDeleteQueries(1, &p->query);
    glDeleteTextures(p->n_tex, p->tex);
}

static oit_status blend_targets(oit_blend_passes *p, int w, int h, oit_error *err)
{
    if (p->tex[0] && p->w == w && p->h == h)
        return OIT_OK;
    static const GLenum colour[OIT_BLEND_TARGETS_MAX] = {
        GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDeleteTextures(p->n_tex, p->tex);
    p->bytes = 0;
    for (int i = 0; i < p->n_tex; i++) {
        p->tex[i] = oit_baseline_texture(p->format[i], w, h);
        p->bytes += (uint64_t)w * h * (p->format[i] == GL_R32F ? 4 : 16);
    }
    for (int i = 0; i < p->attached; i++)
        glNamedFramebufferTexture(p->fbo, colour[i], p->tex[i], 0);
    glNamedFramebufferDrawBuffers(p->fbo, p->attached, colour);
    p->w = w;
    p->h = h;
    if (p->bytes > p->peak)
        p->peak = p->bytes;
    char what[96];
    snprintf(what, sizeof what, "%s: float targets", p->method);
    return oit_gl_check(what, err);
}

oit_status oit_blend_passes_begin(oit_blend_passes *p, const oit_view *v, oit_error *err)
{
    oit_status s = blend_targets(p, v->width, v->height, err);
    if (s == OIT_OK)
        oit_glsl_set_view_all(p->prog, p->n_prog, v);
    return s;
}

oit_status oit_blend_passes_end(oit_blend_passes *p, int result, uint64_t bytes_peak,
                                oit_image *out, oit_frame_stats *stats, oit_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "%s: passes", p->method);
    oit_status s = oit_gl_check(what, err);
    if (s == OIT_OK)
        s = oit_baseline_read_texture(p->method, p->tex[result], p->w, p->h, out, err);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(p->query, GL_QUERY_RESULT, &samples);
    *stats = (oit_frame_stats){.fragments = samples, .gpu_bytes_peak = bytes_peak, .batches = 1};
    return s;
}
