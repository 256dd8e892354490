/* The streamer behind render/method.h (stream_method.h). */
#include "stream/stream_method.h"

#include <stdlib.h>

typedef struct stream_impl {
    oit_streamer *streamer;
    oit_stream_frame_stats stats;
} stream_impl;

static void stream_destroy(void *impl)
{
    stream_impl *m = impl;
    oit_streamer_destroy(m->streamer);
    free(m);
}

static oit_status stream_create(const oit_mesh *mesh, const oit_method_options *opt,
                                void **impl, oit_error *err)
{
    const oit_stream_options *so = opt ? opt->source : NULL;
    if (!so || !so->partfile)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method stream renders a part file "
                             "(.oitp, made by oitprep); convert the model first");
    stream_impl *m = calloc(1, sizeof *m);
    if (!m)
        return oit_error_set(err, OIT_ERR_NOMEM, "method stream: out of memory");
    oit_streamer_desc sd = so->desc;
    sd.K = opt->max_layers;
    sd.store_limit = opt->store_limit;
    if (opt->threshold)
        sd.epsilon = *opt->threshold;
    oit_status s = oit_streamer_desc_check(&sd, NULL, err);
    if (s == OIT_OK)
        s = oit_streamer_create(so->partfile, &sd, &m->streamer, err);
    if (s != OIT_OK) {
        free(m);
        return s;
    }
    *impl = m;
    return OIT_OK;
}

/* A banded frame's figures add up over its bands (oit_method_frame.band). */
static oit_status stream_render(void *impl, const oit_method_frame *f, oit_error *err)
{
    stream_impl *m = impl;
    oit_stream_frame_stats band = {0};
    oit_streamer_set_gpu_timer(m->streamer, f->timer);
    oit_status s = oit_streamer_render(m->streamer, f->view, f->out, f->stats, &band, err);
    if (f->band == 0)
        m->stats = band;
    else
        oit_stream_frame_stats_add(&m->stats, &band);
    return s;
}

static uint64_t stream_pixel_bytes(const void *impl, const oit_view *view)
{
    (void)impl;
    return oit_streamer_pixel_bytes(view);
}

static const void *stream_figures(const void *impl)
{
    return &((const stream_impl *)impl)->stats;
}

const oit_stream_frame_stats *oit_method_stream_stats(const oit_method_state *st)
{
    return oit_method_of(st) == &oit_method_stream ? oit_method_figures(st) : NULL;
}

const oit_method oit_method_stream = {
    .name = "stream",
    .flags = OIT_METHOD_GL | OIT_METHOD_PARTFILE | OIT_METHOD_EPSILON | OIT_METHOD_CLIP,
    .create = stream_create,
    .render = stream_render,
    .destroy = stream_destroy,
    .figures = stream_figures,
    .pixel_bytes = stream_pixel_bytes,
};
