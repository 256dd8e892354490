/* liboit behind the method interface (method_stream.h). */
#include "tools/common/method_stream.h"

#include <stdlib.h>
#include <string.h>

#include "render/gl/gpu_timer.h"
#include "render/image/image.h"
#include "tools/common/flag_spelling.h"

typedef struct stream_impl {
    oit_scene *scene;
    oit_renderer *renderer; /* made at the first frame, anew when the shading changes */
    oit_renderer_desc desc; /* the options' settings; the shading of the renderer's frames */
    oit_draw_stats stats;   /* the last frame's, its bands added up */
    int drawn;              /* stats hold a frame */
} stream_impl;

static void stream_destroy(void *impl)
{
    stream_impl *m = impl;
    oit_renderer_destroy(m->renderer);
    oit_scene_close(m->scene);
    free(m);
}

static oit_status stream_create(const oit_mesh *mesh, const oit_method_options *opt,
                                void **impl, oit_error *err)
{
    (void)mesh;
    const oit_stream_source *so = opt ? opt->source : NULL;
    if (!so || !so->path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method stream renders a part file "
                             "(.oitp, made by oitprep); convert the model first");
    stream_impl *m = calloc(1, sizeof *m);
    if (!m)
        return oit_error_set(err, OIT_ERR_NOMEM, "method stream: out of memory");
    m->desc = so->desc;
    m->desc.K = opt->max_layers > 0 ? (uint32_t)opt->max_layers : 0;
    if (opt->threshold)
        m->desc.epsilon = *opt->threshold;
    m->desc.binding_limit = opt->store_limit;
    /* Parts are checked when first drawn, as the streamer always did. */
    oit_status s = oit_scene_open(so->path, &(oit_scene_desc){.defer_validation = 1}, &m->scene,
                                  err);
    if (s != OIT_OK) {
        free(m);
        return s;
    }
    *impl = m;
    return OIT_OK;
}

void oit_stream_shading(const oit_shading *in, oit_renderer_desc *d)
{
    d->shading.mode = in->mode == OIT_SHADING_TRANSLUCENT ? OIT_RENDER_TRANSLUCENT
                                                         : OIT_RENDER_TRANSPARENT;
    d->shading.alpha = in->alpha;
    memcpy(d->shading.default_rgb, in->default_rgb, sizeof d->shading.default_rgb);
    d->shading.absorption = in->absorption;
    d->shading.scene_scale = in->scene_scale;
    d->shading.colour_space = in->colour_space == OIT_COLOUR_LINEAR ? OIT_RENDER_COLOUR_LINEAR
                                                                   : OIT_RENDER_COLOUR_SRGB;
    d->see_through = in->see_through;
}

/* A renderer for the view's shading: liboit takes it at creation. */
static oit_status renderer_for(stream_impl *m, const oit_shading *shading, oit_error *err)
{
    oit_renderer_desc d = m->desc;
    oit_stream_shading(shading, &d);
    if (m->renderer && !memcmp(&d, &m->desc, sizeof d))
        return OIT_OK;
    oit_renderer_destroy(m->renderer);
    m->renderer = NULL;
    m->desc = d;
    return oit_renderer_create(&m->desc, &m->renderer, err);
}

oit_frame_camera oit_stream_camera(const oit_camera *c)
{
    oit_frame_camera f = {0};
    memcpy(f.eye, c->eye, sizeof f.eye);
    memcpy(f.target, c->target, sizeof f.target);
    memcpy(f.up, c->up, sizeof f.up);
    f.fovy_deg = c->fovy_deg;
    f.znear = c->znear;
    f.zfar = c->zfar;
    f.ortho_height = c->projection == OIT_PROJ_ORTHOGRAPHIC ? c->ortho_height : 0.0f;
    memcpy(f.window, c->window, sizeof f.window);
    return f;
}

void oit_stream_frame(const oit_view *v, oit_frame_camera *cam, oit_frame *fr)
{
    *cam = oit_stream_camera(&v->camera);
    *fr = (oit_frame){.viewport_width = v->width, .viewport_height = v->height,
                      .camera = cam, .clip_count = (uint32_t)v->clip.count};
    memcpy(fr->model, v->model, sizeof fr->model);
    for (int i = 0; i < v->clip.count && i < OIT_FRAME_CLIP_MAX; i++)
        memcpy(fr->clip[i], v->clip.plane[i], sizeof fr->clip[i]);
}

/* liboit's figures in the interface's (oit_frame_stats). */
static void frame_stats_of(const oit_draw_stats *d, oit_frame_stats *fs)
{
    memset(fs, 0, sizeof *fs);
    fs->ms = d->ms;
    fs->fragments = d->fragments;
    fs->max_layers = d->max_layers;
    fs->overflow_pixels = d->overflow_pixels;
    fs->gpu_bytes_peak = d->gpu_bytes_peak;
    fs->batches = d->batches;
    fs->second_pass_pixels = d->second_pass_pixels;
    fs->second_pass_packs = d->second_pass_packs;
    fs->host_waits = d->host_waits;
    fs->redraws = d->redraws;
    fs->deep_pixels = d->deep_pixels;
    fs->predicted_batches = d->predicted_batches;
    fs->capture = d->capture;
    fs->capture_k = d->capture_k;
    fs->capture_slots = d->capture_slots;
    fs->capture_slots_k = d->capture_slots_k;
    fs->gpu_frame = d->draw;
}

/* liboit's errors as the tools' users give the settings: by flag. */
static oit_status spelt(oit_status s, oit_error *err)
{
    if (s != OIT_OK)
        oit_flags_spell_error(err);
    return s;
}

static oit_status stream_render(void *impl, const oit_method_frame *f, oit_error *err)
{
    stream_impl *m = impl;
    const oit_view *v = f->view;
    oit_status s = renderer_for(m, &v->shading, err);
    if (s == OIT_OK)
        s = oit_image_alloc(f->out, v->width, v->height, err);
    if (s != OIT_OK)
        return spelt(s, err);
    oit_frame_camera cam;
    oit_frame fr;
    oit_stream_frame(v, &cam, &fr);
    size_t bytes = (size_t)v->width * (size_t)v->height * 4 * sizeof *f->out->rgba;
    s = oit_renderer_draw_image(m->renderer, m->scene, &fr, v->shading.background,
                                f->out->rgba, bytes, &m->stats, err);
    m->drawn = s == OIT_OK;
    if (s == OIT_OK && f->stats)
        frame_stats_of(&m->stats, f->stats);
    return spelt(s, err);
}

static int stream_gpu_poll(void *impl, oit_gpu_times *out, int wait)
{
    stream_impl *m = impl;
    oit_draw_gpu g;
    if (!m->renderer || !oit_renderer_gpu_poll(m->renderer, &g, wait))
        return 0;
    _Static_assert(OIT_DRAW_GPU_PHASES == OIT_GPU_PHASES, "one list of GPU phases");
    out->frame = g.draw;
    out->ms = g.ms;
    memcpy(out->phase_ms, g.phase_ms, sizeof out->phase_ms);
    return 1;
}

static const char *stream_gpu_absent(const void *impl)
{
    const stream_impl *m = impl;
    return m->renderer ? oit_renderer_gpu_absent(m->renderer) : NULL;
}

static const void *stream_figures(const void *impl)
{
    return impl;
}

const oit_draw_stats *oit_method_stream_stats(const oit_method_state *st)
{
    const stream_impl *m =
        oit_method_of(st) == &oit_method_stream ? oit_method_figures(st) : NULL;
    return m && m->drawn ? &m->stats : NULL;
}

int oit_method_stream_desc(const oit_method_state *st, oit_renderer_desc *out)
{
    const stream_impl *m =
        oit_method_of(st) == &oit_method_stream ? oit_method_figures(st) : NULL;
    if (!m || !m->renderer)
        return 0;
    oit_renderer_get_desc(m->renderer, out);
    return 1;
}

/* No pixel_bytes: liboit draws a frame too large for one storage binding
 * in bands itself. */
const oit_method oit_method_stream = {
    .name = "stream",
    .flags = OIT_METHOD_GL | OIT_METHOD_PARTFILE | OIT_METHOD_EPSILON | OIT_METHOD_CLIP,
    .create = stream_create,
    .render = stream_render,
    .destroy = stream_destroy,
    .figures = stream_figures,
    .gpu_poll = stream_gpu_poll,
    .gpu_absent = stream_gpu_absent,
};
