/* JSON writer for oitstream --stats (stats_json.h). */
#include "tools/oitstream/stats_json.h"

#include "base/json.h"
#include "tools/common/flag_spelling.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

void oit_stats_format_view(const oit_camera *c, const double origin[3], char *buf, size_t cap)
{
    double o[3] = {0, 0, 0};
    if (origin)
        memcpy(o, origin, sizeof o);
    snprintf(buf, cap, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
             o[0] + c->eye[0], o[1] + c->eye[1], o[2] + c->eye[2], o[0] + c->target[0],
             o[1] + c->target[1], o[2] + c->target[2],
             c->up[0], c->up[1], c->up[2], c->fovy_deg, c->znear,
             isinf(c->zfar) ? 2.0f * c->znear + 1.0f : c->zfar);
    /* The projection, as --view's fields (view.h, oit_camera_parse). */
    size_t n = strlen(buf);
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC && n < cap)
        n += (size_t)snprintf(buf + n, cap - n, ":ortho=%.9g", c->ortho_height);
    if ((c->window[0] != 0.0f || c->window[1] != 0.0f || c->window[2] != 0.0f ||
         c->window[3] != 0.0f) && n < cap)
        n += (size_t)snprintf(buf + n, cap - n, ":window=%.9g,%.9g,%.9g,%.9g", c->window[0],
                              c->window[1], c->window[2], c->window[3]);
    if (isinf(c->zfar) && n < cap)
        snprintf(buf + n, cap - n, ":far=inf");
}

void oit_stats_format_clip(const oit_clip *clip, const double origin[3], char *buf, size_t cap)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < clip->count && n < cap; i++) {
        const float *p = clip->plane[i];
        /* Positions are relative to origin (oit_clip_add_text). */
        double d = p[3];
        if (origin)
            d -= p[0] * origin[0] + p[1] * origin[1] + p[2] * origin[2];
        n += (size_t)snprintf(buf + n, cap - n, "%s%.9g,%.9g,%.9g,%.17g", i ? ";" : "", p[0],
                              p[1], p[2], d);
    }
}

static void put_frame(oit_json *w, const oit_stats_frame *fr)
{
    const oit_frame_stats *s = &fr->st;
    const oit_draw_stats *t = &fr->stream;
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_string(w, "method", fr->method ? fr->method : "");
    oit_json_string(w, "view", fr->view);
    if (fr->clip[0])
        oit_json_string(w, "clip", fr->clip);
    const oit_json_uint_member frame[] = {
        {"fragments", s->fragments}, {"max_layers", s->max_layers},
        {"overflow_pixels", s->overflow_pixels}, {"gpu_bytes_peak", s->gpu_bytes_peak},
        {"gpu_mesh_bytes", s->gpu_mesh_bytes},
        {"batches", s->batches}, {"second_pass_pixels", s->second_pass_pixels},
        {"second_pass_packs", s->second_pass_packs}, {"deep_pixels", s->deep_pixels},
        {"predicted_batches", s->predicted_batches},
        {"host_waits", s->host_waits}, {"redraws", s->redraws},
        {"fragments_saturated", s->fragments_saturated}};
    const oit_json_uint_member parts[] = {
        {"packs", t->packs}, {"parts_drawn", t->parts_drawn}, {"parts_culled", t->parts_culled},
        {"parts_skipped", t->parts_skipped}, {"parts_clipped", t->parts_clipped},
        {"bytes_clipped", t->bytes_clipped}, {"bytes_uploaded", t->bytes_uploaded},
        {"cache_hits", t->cache_hits}, {"cache_bytes", t->cache_bytes}};
    oit_json_fixed(w, "ms", isfinite(s->ms) ? s->ms : -1.0, 3);
    /* -1: not timed on the GPU (the run's gpu_timer says why) */
    oit_json_fixed(w, "gpu_ms", fr->has_gpu ? fr->gpu.ms : -1.0, 3);
    if (fr->has_gpu) {
        oit_json_begin_object(w, "gpu_phase_ms", OIT_JSON_INLINE);
        for (int p = 0; p < OIT_GPU_PHASES; p++)
            oit_json_fixed(w, oit_gpu_phase_name((oit_gpu_phase)p), fr->gpu.phase_ms[p], 3);
        oit_json_end(w);
    }
    OIT_JSON_UINTS(w, frame);
    if (s->capture) {
        oit_json_string(w, "capture", s->capture);
        oit_json_uint(w, "capture_k", s->capture_k);
    }
    if (s->capture_slots) {
        oit_json_string(w, "capture_slots", s->capture_slots);
        oit_json_uint(w, "capture_slots_k", s->capture_slots_k);
    }
    if (fr->has_stream) {
        OIT_JSON_UINTS(w, parts);
        oit_json_general(w, "epsilon", fr->epsilon, 9);
        oit_json_uint(w, "draw_calls", t->draw_calls);
        oit_json_fixed(w, "order_ms", t->order_ms, 3);
        oit_json_fixed(w, "pack_ms", t->pack_ms, 3);
        oit_json_int(w, "auto_first_k", (int)t->auto_first_k);
        oit_json_int(w, "front_first", (int)t->front_first);
        if (t->choice) {
            oit_json_string(w, "choice", t->choice);
            oit_json_string(w, "choice_why", t->choice_why ? t->choice_why : "");
            oit_json_fixed(w, "choice_first_k_ms", t->choice_first_k_ms, 3);
            oit_json_fixed(w, "choice_counted_ms", t->choice_counted_ms, 3);
        }
        if (t->capture_asked) {
            oit_json_string(w, "capture_asked", t->capture_asked);
            oit_json_string(w, "capture_fallback",
                            t->capture_fallback ? t->capture_fallback : "");
        }
        oit_json_int(w, "reader_threads", (int)t->reader_threads);
    }
    oit_json_end(w);
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the n figures at v (sorted in place); -1 for none. */
static double median(double *v, size_t n)
{
    if (n == 0)
        return -1.0;
    qsort(v, n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Warm medians: every frame but the first (which compiles, allocates and
 * uploads), or the only one. which: -2 wall ms, -1 gpu ms, else a phase. */
static double warm_median(const oit_stats_run *run, int which, double *tmp)
{
    size_t n = 0;
    for (size_t i = run->frame_count > 1 ? 1 : 0; i < run->frame_count; i++) {
        const oit_stats_frame *fr = &run->frames[i];
        if (which == -2)
            tmp[n++] = fr->st.ms;
        else if (fr->has_gpu)
            tmp[n++] = which == -1 ? fr->gpu.ms : fr->gpu.phase_ms[which];
    }
    return median(tmp, n);
}

/* The memory the streamer chose and where its total came from. */
static void put_budget(oit_json *w, const oit_draw_stats *b)
{
    oit_json_begin_object(w, "budget", OIT_JSON_INLINE);
    oit_json_uint(w, "gpu_budget", b->gpu_budget);
    oit_json_uint(w, "ring", b->ring_budget);
    oit_json_uint(w, "cache", b->cache_budget);
    oit_json_uint(w, "capture", b->capture_budget);
    oit_json_uint(w, "store", b->store_budget);
    oit_json_int(w, "resident", (int)b->resident);
    oit_json_uint(w, "driver_free", b->gpu_free_bytes);
    oit_json_string(w, "source", b->budget_source ? oit_flag_of(b->budget_source) : "");
    oit_json_end(w);
}

static void put_summary(oit_json *w, const oit_stats_run *run)
{
    double *tmp = malloc((run->frame_count + 1) * sizeof *tmp);
    if (!tmp)
        return;
    oit_json_begin_object(w, "summary", OIT_JSON_INLINE);
    oit_json_uint(w, "warm_frames", run->frame_count > 1 ? run->frame_count - 1 : run->frame_count);
    oit_json_fixed(w, "ms_median", warm_median(run, -2, tmp), 3);
    oit_json_fixed(w, "gpu_ms_median", warm_median(run, -1, tmp), 3);
    if (!run->gpu_absent) {
        oit_json_begin_object(w, "gpu_phase_ms_median", OIT_JSON_INLINE);
        for (int p = 0; p < OIT_GPU_PHASES; p++)
            oit_json_fixed(w, oit_gpu_phase_name((oit_gpu_phase)p), warm_median(run, p, tmp), 3);
        oit_json_end(w);
    }
    oit_json_end(w);
    free(tmp);
}

oit_status oit_stats_json_write(const char *path, const oit_stats_run *run, oit_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open for writing", path);
    oit_json w;
    oit_json_init(&w, f, path);
    oit_json_begin_object(&w, NULL, OIT_JSON_BLOCK);
    oit_json_string(&w, "model", run->model ? run->model : "");
    oit_json_uint(&w, "triangles", run->triangles);
    oit_json_string(&w, "renderer", run->renderer ? run->renderer : "");
    oit_json_int(&w, "width", run->width);
    oit_json_int(&w, "height", run->height);
    oit_json_int(&w, "opaque", run->opaque);
    oit_json_int(&w, "see_through", run->see_through);
    oit_json_string(&w, "gpu_timer", run->gpu_absent ? run->gpu_absent : "GL timestamp queries");
    put_summary(&w, run);
    if (run->frame_count > 0 && run->frames[0].has_stream)
        put_budget(&w, &run->frames[0].stream);
    oit_json_begin_array(&w, "frames", OIT_JSON_BLOCK);
    for (size_t i = 0; i < run->frame_count; i++)
        put_frame(&w, &run->frames[i]);
    oit_json_end(&w);
    oit_json_end(&w);
    return oit_json_close(&w, err);
}
