/* The generic half of every method (method.h): the GL context, the mesh on
 * the GPU, and the order in which they are released. */
#include "view/render/method.h"

#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "view/render/gl/band.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"

struct oit_method_state {
    const oit_method *method;
    const oit_mesh *mesh;
    oit_gl *gl;
    int gl_borrowed; /* gl is the caller's (oit_method_options.gl): not ours to destroy */
    oit_gpu_mesh *gpu;
    void *impl;
    uint64_t store_limit; /* oit_method_options.store_limit */
    oit_gpu_timer *timer; /* GL methods only */
    int timer_borrowed;   /* timer is oit_method_options.timer: not ours to destroy */
};

void oit_method_close(oit_method_state *st)
{
    if (!st)
        return;
    /* GL objects go before the context that owns them. */
    if (st->impl)
        st->method->destroy(st->impl);
    if (!st->timer_borrowed)
        oit_gpu_timer_destroy(st->timer);
    if (st->gpu)
        oit_gpu_mesh_destroy(st->gpu);
    if (st->gl && !st->gl_borrowed)
        oit_gl_destroy(st->gl);
    free(st);
}

/* The caller's context when it gives one (the viewer's window), else a
 * headless one of our own; an in-core method's mesh goes up once. */
static oit_status prepare_gl(oit_method_state *st, const oit_method_options *opt, oit_error *err)
{
    oit_status s = OIT_OK;
    if (opt && opt->gl) {
        st->gl = opt->gl;
        st->gl_borrowed = 1;
    } else {
        s = oit_gl_create(&(oit_gl_desc){0}, &st->gl, err);
    }
    st->timer_borrowed = opt && opt->timer;
    if (st->timer_borrowed)
        st->timer = opt->timer;
    else if (s == OIT_OK && !st->method->gpu_poll)
        s = oit_gpu_timer_create(&(oit_gpu_timer_desc){.no_queries = opt && opt->no_gpu_timer},
                                 &st->timer, err);
    if (s == OIT_OK && !(st->method->flags & OIT_RENDER_METHOD_PART_FILE))
        s = oit_gpu_mesh_create(st->mesh->tris, st->mesh->count, 0, &st->gpu, err);
    return s;
}

oit_status oit_method_open(const oit_method *m, const oit_mesh *mesh,
                           const oit_method_options *opt, oit_method_state **out,
                           oit_error *err)
{
    *out = NULL;
    oit_method_state *st = calloc(1, sizeof *st);
    if (!st)
        return oit_error_set(err, OIT_ERR_NOMEM, "method %s: cannot allocate its state", m->name);
    st->method = m;
    st->mesh = mesh;
    st->store_limit = opt ? opt->store_limit : 0;
    oit_status s = m->flags & OIT_RENDER_METHOD_GL ? prepare_gl(st, opt, err) : OIT_OK;
    if (s == OIT_OK)
        s = m->create(mesh, opt, &st->impl, err);
    if (s != OIT_OK) {
        oit_method_close(st);
        return s;
    }
    *out = st;
    return OIT_OK;
}

/* One frame (or band `band` of one) through the method. */
static oit_status render_once(oit_method_state *st, const oit_view *view, oit_image *out,
                              uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                              int band, int *split, oit_error *err)
{
    unsigned f = st->method->flags;
    uint64_t bind = f & OIT_RENDER_METHOD_GL ? oit_gl_ssbo_max_bytes() : UINT64_MAX;
    if (st->store_limit && st->store_limit < bind)
        bind = st->store_limit;
    *split = 0;
    oit_method_frame frame = {.mesh = st->mesh, .gpu = st->gpu, .view = view, .out = out,
                              .counts = f & OIT_RENDER_METHOD_COUNTS ? counts : NULL,
                              .ambiguous = f & OIT_RENDER_METHOD_AMBIGUITY ? ambiguous : NULL,
                              .stats = stats, .band = band, .store_limit = bind,
                              .split = split, .timer = st->timer};
    oit_status s = st->method->render(st->impl, &frame, err);
    /* A borrowed context is checked too: the viewer's window is ours. */
    if (s == OIT_OK)
        s = oit_gl_debug_check(st->gl, st->method->name, err);
    return s;
}

/* The frame as bands of at most `rows` rows, each copied into out (and its
 * counts into counts' rows); a band the method asks to split is taken
 * again in that many, and so are the bands after it. */
static oit_status render_bands(oit_method_state *st, const oit_view *view, int rows,
                               oit_image *out, uint32_t *counts, oit_frame_stats *stats,
                               oit_error *err)
{
    double t0 = oit_time_ms();
    int w = view->width, h = view->height, band = 0;
    oit_frame_stats sum = {0};
    oit_status s = oit_image_alloc(out, w, h, err);
    for (int y0 = 0; s == OIT_OK && y0 < h;) {
        int y1 = y0 + rows < h ? y0 + rows : h, split = 0;
        oit_view part_view;
        oit_view_band(view, y0, y1, &part_view);
        oit_image part = {0};
        oit_frame_stats part_stats = {0};
        s = render_once(st, &part_view, &part, counts ? counts + (size_t)y0 * w : NULL, NULL,
                        &part_stats, band, &split, err);
        if (s != OIT_OK && split > 1 && y1 - y0 > 1) {
            rows = (y1 - y0 + split - 1) / split;
            s = OIT_OK;
            continue;
        }
        if (s == OIT_OK) {
            memcpy(out->rgba + (size_t)y0 * w * 4, part.rgba,
                   (size_t)w * (size_t)(y1 - y0) * 4 * sizeof *part.rgba);
            oit_frame_stats_add(&sum, &part_stats);
            band++;
            y0 = y1;
        }
        oit_image_free(&part);
    }
    if (s != OIT_OK) {
        oit_image_free(out);
        return s;
    }
    sum.ms = oit_time_ms() - t0;
    if (stats)
        *stats = sum;
    return OIT_OK;
}

static oit_status render_frame(oit_method_state *st, const oit_view *view, oit_image *out,
                               uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                               oit_error *err);

/* The frame between the GPU timer's begin and end (gpu_timer.h). */
oit_status oit_method_render(oit_method_state *st, const oit_view *view, oit_image *out,
                             uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err)
{
    oit_gpu_timer_begin_frame(st->timer);
    oit_status s = render_frame(st, view, out, counts, ambiguous, stats, err);
    uint64_t frame = oit_gpu_timer_end_frame(st->timer);
    if (s == OIT_OK && stats && !st->method->gpu_poll)
        stats->gpu_frame = frame;
    /* The mesh went up once at open and stays for every frame: it is part
     * of each frame's peak, counted here for every in-core method alike. */
    if (s == OIT_OK && stats) {
        stats->gpu_mesh_bytes = oit_gpu_mesh_bytes(st->gpu);
        stats->gpu_bytes_peak += stats->gpu_mesh_bytes;
    }
    return s;
}

int oit_method_gpu_poll(oit_method_state *st, oit_gpu_times *out, int wait)
{
    if (st->method->gpu_poll)
        return st->method->gpu_poll(st->impl, out, wait);
    return oit_gpu_timer_poll(st->timer, out, wait);
}

const char *oit_method_gpu_absent(const oit_method_state *st)
{
    if (st->method->gpu_absent)
        return st->method->gpu_absent(st->impl);
    return st->timer ? oit_gpu_timer_absent(st->timer) : "not a GL method";
}

/* The frame whole, or in bands of rows (oit_method_render). */
static oit_status render_frame(oit_method_state *st, const oit_view *view, oit_image *out,
                               uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                               oit_error *err)
{
    const oit_method *m = st->method;
    int rows = view->height, split = 0;
    oit_status s = oit_clip_check(&view->clip, "section planes", err);
    if (s == OIT_OK && view->clip.count > 0 && !(m->flags & OIT_RENDER_METHOD_CLIP))
        s = oit_error_set(err, OIT_ERR_UNSUPPORTED,
                          "method %s cannot clip: section planes are not supported by it",
                          m->name);
    if (s == OIT_OK && m->pixel_bytes)
        s = oit_band_rows(view, m->pixel_bytes(st->impl, view), st->store_limit, &rows, err);
    if (s != OIT_OK)
        return s;
    if (rows >= view->height) {
        s = render_once(st, view, out, counts, ambiguous, stats, 0, &split, err);
        if (s == OIT_OK || split < 2 || view->height < 2)
            return s;
        rows = (view->height + split - 1) / split;
    }
    return render_bands(st, view, rows, out, counts, stats, err);
}

const char *oit_method_renderer(const oit_method_state *st)
{
    if (st->method->renderer)
        return st->method->renderer(st->impl);
    return st->gl ? oit_gl_renderer(st->gl) : "none";
}

const oit_method *oit_method_of(const oit_method_state *st)
{
    return st->method;
}

const void *oit_method_figures(const oit_method_state *st)
{
    return st->method->figures ? st->method->figures(st->impl) : NULL;
}
