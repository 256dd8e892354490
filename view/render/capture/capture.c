/* Batch capture (capture.h): what every backend shares. A frame carries the
 * per-pixel state of shade.h across batches; each batch is captured by the
 * backend (capture_backend.h: its fill, sort and composite over the batch's
 * rect), and the frame's end resolves the state against the background.
 * Buffers are in GL row order (bottom first); the rect and the output image
 * are flipped at the interface. */
#include "view/render/capture/capture.h"

#include "base/clock.h"
#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/render/image/rect.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- buffers ----------------------------------------------------------------- */

static uint64_t held_bytes(const oit_capture *c)
{
    uint64_t b = c->ops->bytes(c->be) + oit_gpu_draws_bytes(c->draws);
    for (int i = 0; i < OIT_CAPTURE_BUFS; i++)
        b += c->cap[i];
    return b + oit_opaque_keys_gpu_bytes(c->keys);
}

void oit_capture_note_peak(oit_capture *c)
{
    uint64_t held = held_bytes(c);
    c->frame.bytes_peak = held > c->frame.bytes_peak ? held : c->frame.bytes_peak;
}

oit_status oit_capture_reserve(oit_capture *c, GLuint *buf, uint64_t *cap, uint64_t bytes,
                               const char *name, oit_error *err)
{
    oit_status s = oit_gl_buffer_reserve(buf, cap, bytes, name, err);
    oit_capture_note_peak(c);
    return s;
}

static oit_status reserve(oit_capture *c, int which, uint64_t bytes, oit_error *err)
{
    static const char *names[OIT_CAPTURE_BUFS] = {"capture counts", "capture state",
                                                  "capture totals"};
    return oit_capture_reserve(c, &c->buf[which], &c->cap[which], bytes, names[which], err);
}

uint64_t oit_capture_pixel_bytes(const oit_view *v)
{
    return oit_state_bytes(v->shading.mode == OIT_SHADING_TRANSLUCENT);
}

/* The state buffer's bytes for the frame v: its layout follows the shading. */
static uint64_t state_bytes(const oit_view *v)
{
    return (uint64_t)v->width * v->height * oit_capture_pixel_bytes(v);
}

uint64_t oit_capture_within_binding(const oit_capture *c, uint64_t bytes, uint64_t row)
{
    uint64_t most = c->frame.bind > row ? c->frame.bind : row;
    return bytes < most ? bytes : most;
}

/* A driver need address no more than one binding spans, so an index past
 * it reads 0 and writes nothing here too, where it would go unnoticed
 * elsewhere. */
void oit_capture_bind_within(const oit_capture *c, GLuint binding, GLuint buf, uint64_t cap)
{
    uint64_t size = cap < c->frame.bind ? cap : c->frame.bind;
    if (buf && size)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buf, 0, (GLsizeiptr)size);
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buf);
}

void oit_capture_bind_buffers(const oit_capture *c)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, c->buf[OIT_CAPTURE_COUNTS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, c->buf[OIT_CAPTURE_TOTALS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, c->buf[OIT_CAPTURE_STATE]);
    c->ops->bind(c);
}

/* The frame's shared buffers, then the backend's. */
static oit_status allocate(oit_capture *c, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height, state = state_bytes(v);
    oit_status s = oit_gl_check_ssbo_size(state, "capture: the frame's largest buffer", err);
    if (s == OIT_OK)
        s = reserve(c, OIT_CAPTURE_COUNTS, pixels * 4, err);
    if (s == OIT_OK)
        s = reserve(c, OIT_CAPTURE_STATE, state, err);
    if (s == OIT_OK)
        s = reserve(c, OIT_CAPTURE_TOTALS, 16, err);
    if (s == OIT_OK)
        s = c->ops->begin(c, err);
    oit_capture_note_peak(c);
    return s;
}

/* ---- settings and uniforms ----------------------------------------------------- */

/* The threshold in every program that tests it, effective from the next
 * batch on. */
static void apply_epsilon(oit_capture *c, float e)
{
    c->frame.applied = e;
    c->ops->epsilon(c, e);
}

void oit_capture_apply_epsilon(oit_capture *c)
{
    apply_epsilon(c, c->set.epsilon);
}

/* Pixels no earlier batch of the frame composited carry T = 1, where the
 * per-fragment saturation test can drop nothing: a batch wholly outside
 * the box of the earlier ones runs without it. Reading the state at every
 * fragment costs (15% of a frame of the 2CylinderEngine in one pack on
 * llvmpipe), and a frame's first pack is often its only one. */
static void gate_epsilon(oit_capture *c, const int r[4])
{
    int *b = c->frame.touched;
    int first = b[0] >= b[2];
    float want = first || !oit_rect_overlaps(b, r) ? 0.0f : c->set.epsilon;
    if (want != c->frame.applied)
        apply_epsilon(c, want);
    if (first)
        memcpy(b, r, sizeof c->frame.touched);
    else
        oit_rect_grow(b, r);
}

void oit_capture_set_frame_uniforms(const oit_capture *c, GLuint *progs, int n)
{
    for (int i = 0; i < n; i++) {
        oit_glsl_set_view(progs[i], &c->view);
        glProgramUniform1i(progs[i], glGetUniformLocation(progs[i], "u_K"), c->K);
        glProgramUniform1ui(progs[i], glGetUniformLocation(progs[i], "u_count"),
                            (GLuint)((uint64_t)c->view.width * c->view.height));
    }
    /* the opaque depth's projection replaces the view's */
    oit_glsl_set_opaque_all(progs, n, &c->opaque);
}

static void set_uniforms(oit_capture *c)
{
    oit_capture_set_frame_uniforms(c, &c->end_prog, 1);
    c->ops->uniforms(c);
    apply_epsilon(c, c->set.epsilon);
}

void oit_capture_set_opaque(oit_capture *c, const oit_opaque_depth *o)
{
    memset(&c->opaque, 0, sizeof c->opaque);
    if (o && o->enabled)
        c->opaque = *o;
    c->opaque.keyed = 0; /* each frame's own (opaque_begin) */
}

/* The frame's opaque pre-pass (opaque_keys.h), when its shading has opaque
 * triangles; before set_uniforms, which passes keyed to the programs. */
static oit_status opaque_begin(oit_capture *c, oit_error *err)
{
    c->opaque.keyed = 0;
    if (!oit_shading_opaque(&c->view.shading))
        return OIT_OK;
    oit_status s = c->keys ? OIT_OK : oit_opaque_keys_create(&c->keys, err);
    int on = 0;
    if (s == OIT_OK)
        s = oit_opaque_keys_begin(c->keys, &c->view, c->opaque.enabled ? &c->opaque : NULL, &on,
                                  err);
    c->opaque.keyed = on;
    oit_capture_note_peak(c);
    return s;
}

unsigned oit_capture_state_buffer(const oit_capture *c)
{
    return c->buf[OIT_CAPTURE_STATE];
}

uint64_t oit_capture_draw_calls(const oit_capture *c)
{
    return oit_gpu_draws_calls(c->draws) - c->frame.calls0;
}

/* ---- the frame ------------------------------------------------------------------ */

oit_status oit_capture_begin(oit_capture *c, const oit_view *view, oit_error *err)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_size);
    if (view->width <= 0 || view->height <= 0 || view->width > max_size ||
        view->height > max_size)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: frame %dx%d is not renderable "
                             "(at most %d pixels a side)", view->width, view->height, max_size);
    c->view = *view;
    oit_shading_resolve_defaults(&c->view.shading);
    uint64_t driver = oit_gl_ssbo_max_bytes(), limit = c->set.store_limit;
    c->frame = (oit_capture_frame){
        .t0 = oit_time_ms(), .applied = c->frame.applied,
        .bind = limit && limit < driver ? limit : driver,
        .calls0 = oit_gpu_draws_calls(c->draws),
        .view_key = oit_view_key(&c->view),
    };
    c->frame.bytes_peak = held_bytes(c); /* this frame's peak: buffers may have been released */
    oit_status s = allocate(c, &c->view, err);
    if (s != OIT_OK)
        return s;
    static const GLuint zero = 0;
    glClearNamedBufferData(c->buf[OIT_CAPTURE_COUNTS], GL_R32UI, GL_RED_INTEGER,
                           GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(c->buf[OIT_CAPTURE_TOTALS], GL_R32UI, GL_RED_INTEGER,
                           GL_UNSIGNED_INT, &zero);
    glNamedFramebufferParameteri(c->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, view->width);
    glNamedFramebufferParameteri(c->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, view->height);
    if ((s = opaque_begin(c, err)) != OIT_OK)
        return s;
    set_uniforms(c);
    oit_capture_bind_buffers(c);
    /* The state buffer of the frame before may still be read by a pass the
     * caller issued after oit_capture_end_gpu (liboit's blend): order those
     * reads before this frame's first shader write to it. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    /* All zero is the state of a pixel nothing has reached (frag_glsl.h). */
    glClearNamedBufferSubData(c->buf[OIT_CAPTURE_STATE], GL_R32UI, 0,
                              (GLsizeiptr)state_bytes(&c->view), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    s = oit_gl_check("capture: begin", err);
    c->frame.in_frame = s == OIT_OK;
    return s;
}

/* The caller's rect (top rows first, exclusive ends) clamped to the frame
 * and turned into GL rows; returns 0 when it is empty. */
static int gl_rect(const oit_capture *c, const int rect[4], int out[4])
{
    int w = c->view.width, h = c->view.height;
    int r[4] = {0, 0, w, h};
    if (rect)
        memcpy(r, rect, sizeof r);
    r[0] = r[0] < 0 ? 0 : r[0];
    r[1] = r[1] < 0 ? 0 : r[1];
    r[2] = r[2] > w ? w : r[2];
    r[3] = r[3] > h ? h : r[3];
    out[0] = r[0];
    out[1] = h - r[3];
    out[2] = r[2];
    out[3] = h - r[1];
    return r[2] > r[0] && r[3] > r[1];
}

void oit_capture_draw_scissored(oit_capture *c, GLuint prog, const oit_gpu_mesh *const *meshes,
                                int n, const int r[4])
{
    oit_glsl_draw_scissored(c->fbo, c->view.width, c->view.height, prog, c->draws, meshes, n, r);
}

void oit_capture_resolve(GLuint prog, const int r[4])
{
    glUseProgram(prog);
    glProgramUniform4i(prog, glGetUniformLocation(prog, "u_rect"), r[0], r[1], r[2], r[3]);
    glDispatchCompute(oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                      oit_gl_groups((uint64_t)(r[3] - r[1]), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

oit_status oit_capture_batch_start(oit_capture *c, const oit_gpu_mesh *const *meshes,
                                   const int rect[4], int n, int r[4], int *empty,
                                   oit_error *err)
{
    if (!c->frame.in_frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: batch outside "
                             "oit_capture_begin/oit_capture_end");
    c->frame.batches++;
    *empty = !gl_rect(c, rect, r) || n <= 0;
    if (!*empty)
        gate_epsilon(c, r);
    if (!*empty && c->opaque.keyed)
        oit_opaque_keys_draw(c->keys, c->draws, meshes, n, r);
    return OIT_OK;
}

oit_counted_frame oit_capture_counted_frame(oit_capture *c)
{
    return (oit_counted_frame){.fbo = c->fbo,
                               .counts = c->buf[OIT_CAPTURE_COUNTS],
                               .state = c->buf[OIT_CAPTURE_STATE],
                               .width = c->view.width,
                               .height = c->view.height,
                               .draws = c->draws,
                               .bind = c->frame.bind,
                               .view_key = c->frame.view_key,
                               .timer = c->set.timer,
                               .waits = &c->frame.waits};
}

oit_status oit_capture_batch(oit_capture *c, const oit_gpu_mesh *const *meshes,
                             int n, const int rect[4], oit_error *err)
{
    return c->ops->batch(c, meshes, n, rect, c->K, err);
}

oit_status oit_capture_batch_layers(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                    const int rect[4], int layers, oit_error *err)
{
    return c->ops->batch(c, meshes, n, rect, layers, err);
}

/* ---- the frame's end ------------------------------------------------------------ */

/* Totals (and with write_out 1 the final colours, into the output buffer
 * from its start) of the pixels [first, first + count); write_out 2: their
 * fragment counts instead (a float in the first word of each 16 bytes), no
 * totals. */
static void end_pass(oit_capture *c, uint64_t first, uint64_t count, int write_out)
{
    GLuint p = c->end_prog;
    glUseProgram(p);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_first"), (GLuint)first);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_count"), (GLuint)count);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_out"), write_out);
    oit_gl_dispatch_x(p, glGetUniformLocation(p, "u_group0"), oit_gl_groups(count, 64),
                      c->max_groups);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The fragment counts of GL rows [y0, y1) into counts (row 0 at the top),
 * through the output buffer buf (16 bytes a pixel, the count a float in
 * the first word), after the band's colours were read. */
static oit_status read_counts(oit_capture *c, GLuint buf, int y0, int y1, uint32_t *counts,
                              oit_error *err)
{
    int w = c->view.width, h = c->view.height;
    size_t row = (size_t)w * 16, words = (size_t)w * 4 * (size_t)(y1 - y0);
    end_pass(c, (uint64_t)y0 * w, (uint64_t)(y1 - y0) * w, 2);
    float *f = malloc(words * sizeof *f);
    if (!f)
        return oit_error_set(err, OIT_ERR_NOMEM, "capture: no memory to read %dx%d fragment "
                             "counts", w, y1 - y0);
    glGetNamedBufferSubData(buf, 0, (GLsizeiptr)(row * (size_t)(y1 - y0)), f);
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < w; x++)
            counts[(size_t)(h - 1 - y) * w + x] = (uint32_t)f[((size_t)(y - y0) * w + x) * 4];
    free(f);
    return OIT_OK;
}

/* Resolves the carried state against the background into out (oit_image_reserve: written in
 * place where it holds an image of the frame's size, else allocated), in bands of GL rows, as
 * many as the backend's output buffer holds, then reads the totals. */
static oit_status read_output(oit_capture *c, oit_image *out, uint32_t *counts,
                              GLuint totals[4], oit_error *err)
{
    int w = c->view.width, h = c->view.height, made = 0;
    oit_status s = oit_image_reserve(out, w, h, &made, err);
    if (s != OIT_OK)
        return s;
    size_t row = (size_t)w * 16;
    oit_capture_out o = {0, 0};
    s = c->ops->end(c, (uint64_t)row * h, row, &o, err);
    if (s != OIT_OK) {
        if (made)
            oit_image_free(out);
        return s;
    }
    /* a grown buffer may pass what one binding spans */
    uint64_t held = oit_capture_within_binding(c, o.cap, row);
    oit_capture_bind_within(c, OIT_BIND_OUT, o.buf, held);
    int band = (int)(held / row < (uint64_t)h ? held / row : (uint64_t)h);
    for (int y0 = 0; s == OIT_OK && y0 < h; y0 += band) {
        int y1 = y0 + band < h ? y0 + band : h;
        oit_gpu_timer_mark(c->set.timer, OIT_GPU_RESOLVE);
        end_pass(c, (uint64_t)y0 * w, (uint64_t)(y1 - y0) * w, 1);
        oit_gpu_timer_mark(c->set.timer, OIT_GPU_READBACK);
        /* GL rows are bottom first: each row goes to its flipped place. */
        for (int y = y0; y < y1; y++)
            glGetNamedBufferSubData(o.buf, (GLintptr)((size_t)(y - y0) * row),
                                    (GLsizeiptr)row, out->rgba + (size_t)(h - 1 - y) * w * 4);
        if (counts)
            s = read_counts(c, o.buf, y0, y1, counts, err);
    }
    glGetNamedBufferSubData(c->buf[OIT_CAPTURE_TOTALS], 0, 16, totals);
    if (s == OIT_OK)
        s = oit_gl_check("capture: readback", err);
    if (s != OIT_OK && made)
        oit_image_free(out);
    return s;
}

static oit_status finish_frame(oit_capture *c, oit_error *err)
{
    if (!c->frame.in_frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: end without begin");
    c->frame.in_frame = 0;
    oit_capture_bind_buffers(c);
    oit_capture_note_peak(c); /* the multi-draw buffers grow within batches */
    return OIT_OK;
}

/* After the frame's final read-back: the backend's figures measured on the
 * GPU, and whether the frame ended short. */
static void ended(oit_capture *c, oit_status s)
{
    c->ended_short = s == OIT_OK && c->ops->ended && c->ops->ended(c);
}

static void fill_stats(const oit_capture *c, const GLuint totals[4], oit_frame_stats *stats)
{
    if (!stats)
        return;
    memset(stats, 0, sizeof *stats);
    stats->ms = oit_time_ms() - c->frame.t0;
    stats->overflow_pixels = totals[0];
    stats->fragments = (uint64_t)totals[2] << 32 | totals[1];
    stats->max_layers = totals[3];
    stats->gpu_bytes_peak = c->frame.bytes_peak;
    stats->batches = c->frame.batches;
    stats->capture_k = (uint32_t)c->K;
    stats->host_waits = c->frame.waits.count;
    c->ops->stats(c, stats);
}

oit_status oit_capture_end(oit_capture *c, oit_image *out, oit_frame_stats *stats,
                           oit_error *err)
{
    return oit_capture_end_counts(c, out, NULL, stats, err);
}

oit_status oit_capture_end_counts(oit_capture *c, oit_image *out, uint32_t *counts,
                                  oit_frame_stats *stats, oit_error *err)
{
    oit_status s = finish_frame(c, err);
    if (s != OIT_OK)
        return s;
    GLuint totals[4];
    s = read_output(c, out, counts, totals, err);
    glFinish();
    if (s == OIT_OK)
        c->frame.fragments = (uint64_t)totals[2] << 32 | totals[1];
    ended(c, s);
    if (s == OIT_OK)
        fill_stats(c, totals, stats);
    return s;
}

oit_status oit_capture_end_gpu(oit_capture *c, unsigned *state, oit_frame_stats *stats,
                               oit_error *err)
{
    oit_status s = finish_frame(c, err);
    if (s != OIT_OK)
        return s;
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_RESOLVE);
    end_pass(c, 0, (uint64_t)c->view.width * c->view.height, 0);
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_READBACK);
    GLuint totals[4];
    glGetNamedBufferSubData(c->buf[OIT_CAPTURE_TOTALS], 0, 16, totals);
    s = oit_gl_check("capture: end on the GPU", err);
    if (s == OIT_OK)
        c->frame.fragments = (uint64_t)totals[2] << 32 | totals[1];
    ended(c, s);
    if (s != OIT_OK)
        return s;
    *state = c->buf[OIT_CAPTURE_STATE];
    fill_stats(c, totals, stats);
    return OIT_OK;
}
