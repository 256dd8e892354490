/* JSON writer for oitstream --stats (stats_json.h). */
#include "tools/oitstream/stats_json.h"

#include "base/json.h"

#include <math.h>
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

static void put_frame(oit_json *w, const oit_stats_frame *fr)
{
    const oit_frame_stats *s = &fr->st;
    const oit_stream_frame_stats *t = &fr->stream;
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_string(w, "method", fr->method ? fr->method : "");
    oit_json_string(w, "view", fr->view);
    const oit_json_uint_member frame[] = {
        {"fragments", s->fragments}, {"max_layers", s->max_layers},
        {"overflow_pixels", s->overflow_pixels}, {"gpu_bytes_peak", s->gpu_bytes_peak},
        {"batches", s->batches}, {"second_pass_pixels", s->second_pass_pixels},
        {"second_pass_packs", s->second_pass_packs},
        {"fragments_saturated", s->fragments_saturated}};
    const oit_json_uint_member parts[] = {
        {"packs", t->packs}, {"parts_drawn", t->parts_drawn}, {"parts_culled", t->parts_culled},
        {"parts_skipped", t->parts_skipped}, {"bytes_uploaded", t->bytes_uploaded},
        {"cache_hits", t->cache_hits}, {"cache_bytes", t->cache_bytes}};
    oit_json_fixed(w, "ms", isfinite(s->ms) ? s->ms : -1.0, 3);
    OIT_JSON_UINTS(w, frame);
    if (s->capture) {
        oit_json_string(w, "capture", s->capture);
        oit_json_uint(w, "capture_k", s->capture_k);
    }
    if (fr->has_stream) {
        OIT_JSON_UINTS(w, parts);
        oit_json_general(w, "epsilon", t->epsilon, 9);
        oit_json_uint(w, "draw_calls", t->draw_calls);
        oit_json_fixed(w, "order_ms", t->order_ms, 3);
        oit_json_fixed(w, "pack_ms", t->pack_ms, 3);
        oit_json_int(w, "auto_first_k", t->first_k);
        oit_json_int(w, "front_first", t->front_first);
        oit_json_int(w, "reader_threads", t->reader_threads);
    }
    oit_json_end(w);
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
    oit_json_begin_array(&w, "frames", OIT_JSON_BLOCK);
    for (size_t i = 0; i < run->frame_count; i++)
        put_frame(&w, &run->frames[i]);
    oit_json_end(&w);
    oit_json_end(&w);
    return oit_json_close(&w, err);
}
