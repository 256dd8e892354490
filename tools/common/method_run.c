/* Every method through liboit (method_run.h). */
#include "tools/common/method_run.h"

#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "tools/common/flag_spelling.h"

struct oit_run {
    const oit_render_method_info *method;
    struct oit_gl *gl;      /* GL methods: the caller's or our own */
    int gl_own;
    oit_scene *scene;
    oit_renderer *renderer; /* made and prepared at open */
    oit_renderer_desc desc; /* the options' settings; the shading of the renderer's frames */
    oit_draw_stats stats;   /* the last frame's */
    int drawn;              /* stats hold a frame */
};

void oit_run_close(oit_run *run)
{
    if (!run)
        return;
    /* GL objects go before the context that owns them. */
    if (run->gl)
        oit_gl_make_current(run->gl, NULL);
    oit_renderer_destroy(run->renderer);
    oit_scene_close(run->scene);
    if (run->gl_own)
        oit_gl_destroy(run->gl);
    free(run);
}

/* The options as liboit's descriptor. A threshold of 0 is the method's
 * own zero, not its default (OIT_RENDER_EPSILON_ZERO; the stream's 0 is
 * both). */
static void run_desc(const oit_render_method_info *m, const oit_run_options *opt,
                     oit_renderer_desc *d)
{
    *d = opt && opt->source ? opt->source->desc : (oit_renderer_desc){0};
    d->method = m->name;
    if (!opt)
        return;
    d->K = opt->max_layers > 0 ? (uint32_t)opt->max_layers : 0;
    if (opt->threshold)
        d->epsilon = *opt->threshold != 0.0f              ? *opt->threshold
                     : m->flags & OIT_RENDER_METHOD_PART_FILE ? 0.0f
                                                          : OIT_RENDER_EPSILON_ZERO;
    d->ambiguity_px = opt->ambiguity_px;
    d->binding_limit = opt->store_limit;
}

static oit_status open_scene(oit_run *run, const oit_mesh *mesh, const oit_run_options *opt,
                             oit_error *err)
{
    const char *path = opt && opt->source ? opt->source->path : NULL;
    /* the file the mesh came from names it in a method's errors */
    if (!(run->method->flags & OIT_RENDER_METHOD_PART_FILE))
        return oit_scene_borrow_mesh(mesh, path, &run->scene, err);
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method %s renders a part file "
                             "(.oitp, made by oitprep); convert the model first",
                             run->method->name);
    /* Parts are checked when first drawn, as the streamer always did. */
    return oit_scene_open(path, &(oit_scene_desc){.defer_validation = 1}, &run->scene, err);
}

oit_status oit_run_open(const oit_render_method_info *m, const oit_mesh *mesh,
                        const oit_run_options *opt, oit_run **out, oit_error *err)
{
    *out = NULL;
    oit_run *run = calloc(1, sizeof *run);
    if (!run)
        return oit_error_set(err, OIT_ERR_NOMEM, "method %s: out of memory", m->name);
    run->method = m;
    run_desc(m, opt, &run->desc);
    oit_status s = oit_renderer_desc_check(&run->desc, err);
    if (s == OIT_OK && opt && opt->threshold && !(*opt->threshold >= 0.0f && *opt->threshold < 1.0f))
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_desc.epsilon = %g: expected a "
                          "threshold in [0, 1)", (double)*opt->threshold);
    if (s == OIT_OK && (m->flags & OIT_RENDER_METHOD_GL) && opt && opt->gl) {
        run->gl = opt->gl;
    } else if (s == OIT_OK && (m->flags & OIT_RENDER_METHOD_GL)) {
        run->gl_own = 1;
        s = oit_gl_create(&(oit_gl_desc){0}, &run->gl, err);
    }
    if (s == OIT_OK)
        s = open_scene(run, mesh, opt, err);
    /* What the method needs is built now, so that one this driver cannot
     * run fails at open, where the tools choose another. */
    if (s == OIT_OK)
        s = oit_renderer_create(&run->desc, &run->renderer, err);
    if (s == OIT_OK)
        s = oit_renderer_prepare(run->renderer, run->scene, err);
    if (s != OIT_OK) {
        oit_flags_spell_error(err);
        oit_run_close(run);
        return s;
    }
    *out = run;
    return OIT_OK;
}

void oit_run_shading(const oit_shading *in, oit_renderer_desc *d)
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

oit_frame_camera oit_run_camera(const oit_camera *c)
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

void oit_run_frame(const oit_view *v, oit_frame_camera *cam, oit_frame *fr)
{
    *cam = oit_run_camera(&v->camera);
    *fr = (oit_frame){.viewport_width = v->width, .viewport_height = v->height,
                      .camera = cam, .clip_count = (uint32_t)v->clip.count};
    memcpy(fr->model, v->model, sizeof fr->model);
    for (int i = 0; i < v->clip.count && i < OIT_FRAME_CLIP_MAX; i++)
        memcpy(fr->clip[i], v->clip.plane[i], sizeof fr->clip[i]);
}

/* The renderer's shading made the view's where it differs. */
static oit_status shading_for(oit_run *run, const oit_shading *shading, oit_error *err)
{
    oit_renderer_desc d = run->desc;
    oit_run_shading(shading, &d);
    if (!memcmp(&d.shading, &run->desc.shading, sizeof d.shading) &&
        d.see_through == run->desc.see_through)
        return OIT_OK;
    run->desc = d;
    return oit_renderer_set_shading(run->renderer, &d.shading, d.see_through, err);
}

/* liboit's figures in the tools' (oit_frame_stats). */
static void frame_stats_of(const oit_run *run, const oit_draw_stats *d, oit_frame_stats *fs)
{
    *fs = (oit_frame_stats){
        .ms = d->ms, .fragments = d->fragments, .max_layers = d->max_layers,
        .overflow_pixels = d->overflow_pixels, .gpu_bytes_peak = d->gpu_bytes_peak,
        .gpu_mesh_bytes = d->gpu_mesh_bytes, .batches = d->batches,
        .second_pass_pixels = d->second_pass_pixels, .second_pass_packs = d->second_pass_packs,
        .deep_pixels = d->deep_pixels, .predicted_batches = d->predicted_batches,
        .fragments_saturated = d->fragments_saturated, .capture = d->capture,
        .capture_k = d->capture_k, .capture_slots = d->capture_slots,
        .capture_slots_k = d->capture_slots_k, .host_waits = d->host_waits,
        .redraws = d->redraws,
        .gpu_frame = run->method->flags & OIT_RENDER_METHOD_GL ? d->draw : 0};
}

/* The frame through liboit into out (allocated here), in the run's own
 * context, which the driver's debug messages are then checked in. */
static oit_status draw(oit_run *run, const oit_view *v, oit_image *out, uint32_t *counts,
                       uint8_t *ambiguous, oit_error *err)
{
    oit_status s = oit_image_alloc(out, v->width, v->height, err);
    if (s != OIT_OK)
        return s;
    oit_frame_camera cam;
    oit_frame fr;
    oit_run_frame(v, &cam, &fr);
    unsigned f = run->method->flags;
    oit_pixels_desc px = {.background = v->shading.background, .rgba = out->rgba,
                          .rgba_bytes = (size_t)v->width * (size_t)v->height * 4 *
                                        sizeof *out->rgba,
                          .counts = f & OIT_RENDER_METHOD_COUNTS ? counts : NULL,
                          .ambiguous = f & OIT_RENDER_METHOD_AMBIGUITY ? ambiguous : NULL};
    s = oit_renderer_draw_pixels(run->renderer, run->scene, &fr, &px, &run->stats, err);
    if (s == OIT_OK)
        s = oit_gl_debug_check(run->gl, run->method->name, err);
    if (s != OIT_OK)
        oit_image_free(out);
    return s;
}

oit_status oit_run_render(oit_run *run, const oit_view *v, oit_image *out, uint32_t *counts,
                          uint8_t *ambiguous, oit_frame_stats *stats, oit_error *err)
{
    oit_status s = run->gl ? oit_gl_make_current(run->gl, err) : OIT_OK;
    if (s == OIT_OK)
        s = shading_for(run, &v->shading, err);
    if (s == OIT_OK)
        s = draw(run, v, out, counts, ambiguous, err);
    run->drawn = s == OIT_OK;
    if (s == OIT_OK && stats)
        frame_stats_of(run, &run->stats, stats);
    if (s != OIT_OK)
        oit_flags_spell_error(err);
    return s;
}

const char *oit_run_renderer(const oit_run *run)
{
    if (run->drawn && run->stats.device)
        return run->stats.device;
    return run->gl ? oit_gl_renderer(run->gl) : "none";
}

const oit_render_method_info *oit_run_method(const oit_run *run)
{
    return run->method;
}

int oit_run_gpu_poll(oit_run *run, oit_gpu_times *out, int wait)
{
    oit_draw_gpu g;
    if (!run->renderer || !oit_renderer_gpu_poll(run->renderer, &g, wait))
        return 0;
    _Static_assert(OIT_DRAW_GPU_PHASES == OIT_GPU_PHASES, "one list of GPU phases");
    out->frame = g.draw;
    out->ms = g.ms;
    memcpy(out->phase_ms, g.phase_ms, sizeof out->phase_ms);
    return 1;
}

const char *oit_run_gpu_absent(const oit_run *run)
{
    if (!(run->method->flags & OIT_RENDER_METHOD_GL))
        return "not a GL method";
    return run->renderer ? oit_renderer_gpu_absent(run->renderer) : NULL;
}

const oit_draw_stats *oit_run_stream_stats(const oit_run *run)
{
    int part_file = !!(run->method->flags & OIT_RENDER_METHOD_PART_FILE);
    return part_file && run->drawn ? &run->stats : NULL;
}

int oit_run_stream_desc(const oit_run *run, oit_renderer_desc *out)
{
    if (!(run->method->flags & OIT_RENDER_METHOD_PART_FILE) || !run->renderer)
        return 0;
    oit_renderer_get_desc(run->renderer, out);
    return 1;
}
