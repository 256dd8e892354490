/* liboit's renderer (liboit_internal.h): its descriptor spelt onto the
 * streamer's and checked, its lifetime, and the scene it holds. */
#include "liboit/liboit_internal.h"

/* ---- renderer ---------------------------------------------------------- */

/* Frees r's GPU state for its scene and lets the scene go (the streamer
 * reads the scene's part file until it is destroyed). */
static void drop_scene(oit_renderer *r)
{
    oit_method_close(r->run);
    r->run = NULL;
    oit_streamer_destroy(r->streamer);
    r->streamer = NULL;
    oit_gpu_mesh_destroy(r->gpu_mesh);
    r->gpu_mesh = NULL;
    oit_lib_scene_unshare(r->scene);
    r->scene = NULL;
}

void oit_renderer_destroy(oit_renderer *r)
{
    if (!r)
        return;
    drop_scene(r);
    oit_gl_destroy(r->run_gl);
    oit_plugin_close(&r->reference_plugin);
    oit_dfb_destroy(r->dfb);
    oit_gpu_timer_destroy(r->timer);
    glDeleteProgram(r->blend_prog);
    oit_program_cache_close(r->programs);
    glDeleteVertexArrays(1, &r->vao);
    glDeleteSamplers(1, &r->depth_sampler);
    free(r);
}

/* How the streamer's errors and figures name its settings: as the fields
 * of oit_renderer_desc they come from (stream_desc). */
static const oit_streamer_names field_names = {
    .upload_budget = "oit_renderer_desc.upload_budget",
    .slot_budget = "oit_renderer_desc.slot_budget",
    .cache_budget = "oit_renderer_desc.cache_budget",
    .gpu_budget = "oit_renderer_desc.gpu_budget",
    .epsilon = "oit_renderer_desc.epsilon",
    .pack = "oit_renderer_desc.pack",
    .schedule = "oit_renderer_desc.schedule",
    .cache_off = "OIT_RENDER_CACHE_OFF",
    .store_budget = "oit_renderer_desc.store_budget",
    .capture = "oit_renderer_desc.capture"};

/* liboit's settings onto oit_streamer_desc, the one place it is built: the
 * streamer checks the values (oit_streamer_desc_check) and each scene adds
 * its K and share. */
static void stream_desc(const oit_renderer_desc *d, oit_streamer_desc *sd)
{
    memset(sd, 0, sizeof *sd);
    sd->names = &field_names;
    sd->capture = d->capture;
    sd->pack = d->pack;
    sd->upload_budget = d->upload_budget;
    sd->epsilon = d->epsilon == OIT_RENDER_EPSILON_ZERO ? 0.0f : d->epsilon;
    _Static_assert(OIT_RENDER_CACHE_OFF == OIT_STREAM_CACHE_OFF, "one spelling of 'no cache'");
    sd->cache_budget = d->cache_budget;
    sd->reader_threads = d->read_on_draw_thread
                             ? OIT_STREAM_READ_INLINE
                             : (int)(d->reader_threads > INT_MAX ? INT_MAX : d->reader_threads);
    sd->gpu_budget = d->gpu_budget;
    sd->schedule = d->schedule;
    sd->slot_budget = d->slot_budget;
    sd->store_budget = d->store_budget;
    sd->store_limit = d->binding_limit;
    sd->frames = d->frames;
}

/* One row of desc_ranges.h that liboit checks, on an integer field. */
static oit_status check_row(const oit_renderer_desc *d, const oit_desc_range *row,
                            oit_error *err)
{
    const char *p = (const char *)d + row->offset;
    long long v;
    if (row->type == OIT_DESC_U32) {
        uint32_t u;
        memcpy(&u, p, sizeof u);
        v = u;
    } else {
        int i;
        memcpy(&i, p, sizeof i);
        v = i;
    }
    if ((v == 0 && row->zero_default) || (v >= (long long)row->lo && v <= (long long)row->hi))
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_desc.%s = %lld: expected %s",
                         row->field, v, row->expect);
}

/* liboit's own checks (the rows of desc_ranges.h it owns), then the
 * streamer's (oit_streamer_desc_check) on the descriptor stream_desc
 * builds, which names the fields as liboit's. */
oit_status oit_renderer_desc_check(const oit_renderer_desc *d, oit_error *err)
{
    if (oit_lib_method_check(d->method, err) != OIT_OK)
        return OIT_ERR_ARGUMENT;
    for (size_t i = 0; i < OIT_DESC_RANGES; i++)
        if (oit_desc_ranges[i].liboit_checks && check_row(d, &oit_desc_ranges[i], err) != OIT_OK)
            return OIT_ERR_ARGUMENT;
    oit_streamer_desc sd;
    stream_desc(d, &sd);
    return oit_streamer_desc_check(&sd, err);
}

oit_status oit_renderer_create(const oit_renderer_desc *desc, oit_renderer **out, oit_error *err)
{
    *out = NULL;
    oit_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return oit_error_set(err, OIT_ERR_NOMEM, "oit_renderer_create: out of memory");
    if (desc)
        r->desc = *desc;
    oit_status bad = oit_renderer_desc_check(&r->desc, err);
    if (bad != OIT_OK) {
        free(r);
        return bad;
    }
    /* the caller's strings are not kept: the method's static name and the
     * cache's folder in use are read back */
    if (r->desc.method)
        r->desc.method = r->desc.method[0] ? oit_lib_method_find(r->desc.method)->name : NULL;
    stream_desc(&r->desc, &r->stream);
    oit_status st = oit_program_cache_open(r->desc.program_cache, &r->programs, err);
    r->desc.program_cache = r->programs ? oit_program_cache_dir(r->programs) : "off";
    r->stream.programs = r->programs;
    if (st != OIT_OK) {
        oit_renderer_destroy(r);
        return st;
    }
    *out = r;
    return OIT_OK;
}

oit_status oit_renderer_set_shading(oit_renderer *r, const oit_render_shading *shading,
                                    int see_through, oit_error *err)
{
    oit_renderer_desc d = r->desc;
    d.shading = *shading;
    d.see_through = see_through;
    oit_status st = oit_renderer_desc_check(&d, err);
    if (st == OIT_OK)
        r->desc = d;
    return st;
}

void oit_renderer_release_scene(oit_renderer *r, const oit_scene *scene)
{
    if (!r || !scene || r->scene != scene)
        return;
    drop_scene(r);
}

/* r takes a share of scene, whose GPU state it now holds. */
static void hold_scene(oit_renderer *r, oit_scene *scene)
{
    atomic_fetch_add(&scene->shares, 1u);
    r->scene = scene;
}

/* The GL objects of r's GL draws, made at the first (GL current): the
 * GPU timer that numbers them, the blend's vertex array and the depth
 * texture's sampler, and the device's name. */
oit_status oit_lib_gl_ready(oit_renderer *r, oit_error *err)
{
    if (r->timer)
        return OIT_OK;
    oit_status st = oit_gpu_timer_create(NULL, &r->timer, err);
    if (st != OIT_OK)
        return st;
    const char *dev = (const char *)glGetString(GL_RENDERER);
    snprintf(r->device, sizeof r->device, "%s", dev ? dev : "unknown");
    glCreateVertexArrays(1, &r->vao);
    glCreateSamplers(1, &r->depth_sampler);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return oit_gl_check("oit_renderer: its GL objects", err);
}

/* An in-core scene's GPU state: its method opened for images, or DFB and
 * the triangles for a blend into the caller's framebuffer (dfb only). */
static oit_status bind_in_core(oit_renderer *r, oit_scene *scene, int image, oit_error *err)
{
    if (image)
        return oit_lib_method_open(r, r->method, scene, err);
    if (strcmp(r->method->name, "dfb") != 0)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_renderer_desc.method = \"%s\" "
                             "draws images only (oit_renderer_draw_pixels); \"dfb\" blends "
                             "an in-core scene into a framebuffer", r->method->name);
    oit_status st = r->dfb ? OIT_OK : oit_dfb_create(&r->dfb, err);
    if (st == OIT_OK)
        st = oit_gpu_mesh_create(scene->mesh.tris, scene->mesh.count, 0, &r->gpu_mesh, err);
    return st;
}

/* (Re)builds the streamer, or an in-core scene's state for the draw's kind
 * (image or not), when r draws a scene it was not built for. r's share
 * keeps the scene it holds alive, so the address names one scene. */
oit_status oit_lib_bind_scene(oit_renderer *r, oit_scene *scene, int image, oit_error *err)
{
    if (r->scene == scene && (r->streamer || (image ? !!r->run : !!r->gpu_mesh)))
        return OIT_OK;
    if (r->scene != scene)
        drop_scene(r);
    if (!scene->pf) {
        oit_status st = bind_in_core(r, scene, image, err);
        if (st == OIT_OK && r->scene != scene)
            hold_scene(r, scene);
        /* the triangles went up: the next draw's bytes_uploaded */
        if (st == OIT_OK && (!image || r->method->flags & OIT_RENDER_METHOD_GL))
            r->pending_upload = (uint64_t)scene->mesh.count * sizeof(oit_triangle);
        return st;
    }
    oit_streamer_desc sd = r->stream;
    /* A file cut for more than the K-slot capture holds streams its parts as
     * wider than K, captured alone over tiles, as oitstream does. */
    sd.K = r->desc.K ? (int)r->desc.K : scene->info.K < 16 ? (int)scene->info.K : 16;
    sd.share_count = scene->info.share_count;
    sd.share_index = scene->info.share_index;
    oit_status st = oit_streamer_create(scene->pf, &sd, &r->streamer, err);
    if (st == OIT_OK)
        hold_scene(r, scene);
    return st;
}

/* bg: the background of a resolved image (oit_renderer_draw_image), NULL
 * for the default (white), which a blend over a framebuffer does not read. */
void oit_lib_make_shading(const oit_renderer *r, const oit_scene *scene, const float *bg,
                          oit_shading *s)
{
    const oit_render_shading *in = &r->desc.shading;
    memset(s, 0, sizeof *s);
    if (bg)
        memcpy(s->background, bg, sizeof s->background);
    s->mode =
        in->mode == OIT_RENDER_TRANSLUCENT ? OIT_SHADING_TRANSLUCENT : OIT_SHADING_TRANSPARENT;
    s->alpha = in->alpha;
    memcpy(s->default_rgb, in->default_rgb, sizeof s->default_rgb);
    s->absorption = in->absorption;
    s->colour_space =
        in->colour_space == OIT_RENDER_COLOUR_LINEAR ? OIT_COLOUR_LINEAR : OIT_COLOUR_SRGB;
    s->attributes = scene->info.attributes;
    s->see_through = r->desc.see_through;
    s->scene_scale = in->scene_scale > 0.0f
                         ? in->scene_scale
                         : oit_scene_scale(scene->info.bounds_min, scene->info.bounds_max);
    oit_shading_resolve_defaults(s);
}

void oit_renderer_get_desc(const oit_renderer *r, oit_renderer_desc *out)
{
    *out = r->desc;
    if (r->method)
        out->method = r->method->name;
    if (r->scene) {
        oit_shading s;
        oit_lib_make_shading(r, r->scene, NULL, &s);
        out->shading.alpha = s.alpha;
        memcpy(out->shading.default_rgb, s.default_rgb, sizeof out->shading.default_rgb);
        out->shading.absorption = s.absorption;
        out->shading.scene_scale = s.scene_scale;
        out->shading.colour_space =
            s.colour_space == OIT_COLOUR_LINEAR ? OIT_RENDER_COLOUR_LINEAR : OIT_RENDER_COLOUR_SRGB;
    }
    if (!r->streamer)
        return;
    oit_streamer_desc sd;
    oit_streamer_resolved_desc(r->streamer, &sd);
    out->K = (uint32_t)sd.K;
    out->upload_budget = sd.upload_budget;
    out->cache_budget = sd.cache_budget;
    out->gpu_budget = sd.gpu_budget;
    out->capture = sd.capture;
    out->read_on_draw_thread = sd.reader_threads == OIT_STREAM_READ_INLINE;
}
