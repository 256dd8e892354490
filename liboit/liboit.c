/* The public embedding API (include/oit/liboit.h) over the streamer and
 * DFB: the caller's matrices become an oit_camera, the streamer (a part
 * file) or DFB (an in-core mesh) leaves the frame's per-pixel (C, T) state
 * in a GPU buffer, and one fullscreen pass blends it over the caller's
 * framebuffer. */
#include "liboit/liboit_internal.h"

/* An in-core draw's figures beside the capture's, for oit_draw_stats: its
 * packs are DFB's bands (dfb: a count pass and a store a band), the
 * triangles uploaded since the last draw, the peak with the mesh (which
 * fs->gpu_bytes_peak holds already). */
static void in_core_figures(oit_renderer *r, int dfb, const oit_frame_stats *fs,
                            oit_stream_frame_stats *ss)
{
    ss->packs = fs->batches;
    if (dfb)
        ss->draw_calls = 1 + (uint64_t)fs->batches;
    ss->bytes_uploaded = r->pending_upload;
    ss->gpu_bytes_peak = fs->gpu_bytes_peak;
    r->pending_upload = 0;
}

/* One band's (or the whole frame's) state: the scene through the streamer
 * or DFB into *state, its figures in *fs and *ss. */
static oit_status render_state(oit_renderer *r, const oit_scene *scene, const oit_view *v,
                               const oit_opaque_depth *opaque, GLuint *state,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    if (scene->pf) {
        r->bands++;
        oit_streamer_set_gpu_timer(r->streamer, r->timer);
        oit_streamer_set_opaque(r->streamer, opaque);
        return oit_streamer_render_gpu(r->streamer, v, state, fs, ss, err);
    }
    const oit_gpu_mesh *list[1] = {r->gpu_mesh};
    oit_dfb_set_opaque(r->dfb, opaque);
    oit_dfb_set_gpu_timer(r->dfb, r->timer);
    oit_status st = oit_dfb_render_state(r->dfb, list, 1, v, state, fs, err);
    fs->gpu_mesh_bytes = oit_gpu_mesh_bytes(r->gpu_mesh);
    fs->gpu_bytes_peak += fs->gpu_mesh_bytes;
    in_core_figures(r, 1, fs, ss);
    return st;
}

/* The frame in bands of rows whose state fits one storage binding
 * (view/render/gl/band.h; one band where it all fits, the view unchanged), each
 * rendered and blended over its rows of the viewport before the next
 * overwrites the state. The opaque depth's projection is narrowed to the
 * band as the camera is; the depth unit is bound only while a band is
 * captured, not while the blend draws into a target it may belong to. */
static oit_status draw_bands(oit_renderer *r, const oit_scene *scene, const oit_frame *frame,
                             const oit_view *view, oit_frame_stats *fs,
                             oit_stream_frame_stats *ss, oit_error *err)
{
    uint64_t px = scene->pf ? oit_streamer_pixel_bytes(view) : oit_dfb_pixel_bytes(view, 1);
    int rows = 0, h = view->height;
    oit_status st = oit_band_rows(view, px, r->desc.binding_limit, &rows, err);
    for (int y0 = 0; st == OIT_OK && y0 < h; y0 += rows) {
        int y1 = y0 + rows < h ? y0 + rows : h, gl_y = frame->viewport_y + h - y1;
        oit_view band = *view;
        oit_opaque_depth opaque = {.enabled = frame->depth_texture != 0,
                                   .origin = {frame->viewport_x, gl_y}};
        float proj[16];
        if (frame->camera)
            oit_camera_proj_matrix(&view->camera, (float)view->width / (float)h, proj);
        else
            memcpy(proj, frame->projection, sizeof proj);
        memcpy(opaque.proj, proj, sizeof opaque.proj);
        if (rows < h) {
            oit_view_band(view, y0, y1, &band);
            oit_band_projection(proj, h, y0, y1, opaque.proj);
        }
        depth_unit unit;
        if (opaque.enabled)
            oit_lib_depth_unit_bind(r, frame->depth_texture, &unit);
        oit_frame_stats bfs = {0};
        oit_stream_frame_stats bss = {0};
        GLuint state = 0;
        GLint keys_tex = oit_lib_keys_unit_save();
        st = render_state(r, scene, &band, &opaque, &state, &bfs, &bss, err);
        glBindTextureUnit(OIT_TEX_OPAQUE_KEYS, (GLuint)keys_tex);
        if (opaque.enabled)
            oit_lib_depth_unit_restore(&unit);
        if (st == OIT_OK)
            st = oit_lib_blend_ready(r, err);
        if (st == OIT_OK) {
            oit_lib_blend_over(r, frame, &band, frame->viewport_x, gl_y, state);
            st = oit_gl_check("oit_renderer_draw: blend", err);
        }
        /* fs and ss start at zero: adding the first band copies it. */
        oit_frame_stats_add(fs, &bfs);
        oit_stream_frame_stats_add(ss, &bss);
    }
    return st;
}

/* The figures of the draw's work and choices (oit_draw_stats, from
 * order_ms on) that the capture and the streamer report: 0 and NULL for an
 * in-core scene, whose ss DFB's branch of render_state leaves so. */
static void draw_stats_work(const oit_frame_stats *fs, const oit_stream_frame_stats *ss,
                            oit_draw_stats *out)
{
    out->order_ms = ss->order_ms;
    out->pack_ms = ss->pack_ms;
    out->auto_first_k = (uint32_t)ss->first_k;
    out->choice = ss->choice_path;
    out->choice_why = ss->choice_why;
    out->choice_first_k_ms = ss->choice_path ? ss->choice_ms[0] : -1.0;
    out->choice_counted_ms = ss->choice_path ? ss->choice_ms[1] : -1.0;
    out->front_first = (uint32_t)ss->front_first;
    out->second_pass_pixels = fs->second_pass_pixels;
    out->second_pass_packs = fs->second_pass_packs;
    out->capture = fs->capture;
    out->capture_k = fs->capture_k;
    out->capture_asked = ss->capture_asked;
    out->batches = fs->batches;
    out->host_waits = fs->host_waits;
    out->redraws = fs->redraws;
    out->deep_pixels = fs->deep_pixels;
    out->predicted_batches = fs->predicted_batches;
    out->reader_threads = (uint32_t)(ss->reader_threads > 0 ? ss->reader_threads : 0);
}

/* A part file's draw in one band is one streamer frame: the automatic
 * pack mode judges it on the draw's whole wall time and its GPU figure
 * (view/stream/choice.h); bands are judged each on its own time. */
static void frame_end(oit_renderer *r, const oit_scene *scene, oit_status st, double t0,
                      uint64_t gpu_tag)
{
    if (st == OIT_OK && scene->pf && r->streamer && r->bands == 1)
        oit_streamer_frame_end(r->streamer, oit_time_ms() - t0, gpu_tag);
}

/* The figures that are in, queued for oit_renderer_gpu_poll; the newest
 * also in r->gpu, for oit_draw_stats. */
static void gpu_take(oit_renderer *r)
{
    r->draws++;
    oit_gpu_times t;
    while (oit_gpu_timer_poll(r->timer, &t, 0)) {
        if (r->streamer)
            oit_streamer_gpu_figure(r->streamer, t.frame, t.ms);
        r->gpu = t;
        if (r->gpu_count == GPU_QUEUE) {
            r->gpu_head = (r->gpu_head + 1) % GPU_QUEUE;
            r->gpu_count--;
        }
        r->gpu_queue[(r->gpu_head + r->gpu_count++) % GPU_QUEUE] = t;
    }
}

int oit_renderer_gpu_poll(oit_renderer *r, oit_draw_gpu *out, int wait)
{
    oit_gpu_times t;
    if (!r || !out)
        return 0;
    if (r->gpu_count) {
        t = r->gpu_queue[r->gpu_head];
        r->gpu_head = (r->gpu_head + 1) % GPU_QUEUE;
        r->gpu_count--;
    } else if (!r->timer || !oit_gpu_timer_poll(r->timer, &t, wait)) {
        return 0;
    } else if (r->streamer) {
        oit_streamer_gpu_figure(r->streamer, t.frame, t.ms);
    }
    out->draw = t.frame;
    out->ms = t.ms;
    memcpy(out->phase_ms, t.phase_ms, sizeof out->phase_ms);
    return 1;
}

const char *oit_renderer_gpu_absent(const oit_renderer *r)
{
    if (!r)
        return "no renderer";
    if (r->method && !(r->method->flags & OIT_RENDER_METHOD_GL))
        return "the method draws without GL";
    return r->timer ? oit_gpu_timer_absent(r->timer) : NULL;
}

static oit_status name_scene(const oit_scene *scene, oit_status st, oit_error *err);
static void fill_stats(const oit_renderer *r, const oit_scene *scene, const oit_view *view,
                       const oit_frame_stats *fs, const oit_stream_frame_stats *ss,
                       double t0, oit_draw_stats *stats);

oit_status oit_renderer_draw(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                             oit_draw_stats *stats, oit_error *err)
{
    if (!r || !scene || !frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw: NULL argument");
    double t0 = oit_time_ms();
    oit_view view;
    oit_status st = oit_lib_frame_view(r, scene, frame, NULL, &view, err);
    if (st == OIT_OK && frame->depth_texture)
        st = oit_lib_check_depth_texture(frame, err);
    if (st != OIT_OK)
        return st;
    gl_saved saved;
    oit_lib_gl_save(&saved);
    oit_frame_stats fs = {0};
    oit_stream_frame_stats ss = {0};
    int empty = !scene->pf && scene->info.triangles == 0; /* in core: nothing to draw */
    st = oit_lib_method_for(r, scene, &r->method, err);
    if (st == OIT_OK)
        st = oit_lib_gl_ready(r, err);
    if (st == OIT_OK)
        st = empty ? OIT_OK : oit_lib_bind_scene(r, scene, 0, err);
    oit_gpu_timer_begin_frame(r->timer);
    r->bands = 0;
    if (st == OIT_OK && !empty)
        st = draw_bands(r, scene, frame, &view, &fs, &ss, err);
    frame_end(r, scene, st, t0, oit_gpu_timer_end_frame(r->timer));
    gpu_take(r);
    oit_lib_gl_restore(&saved);
    if (st != OIT_OK)
        return name_scene(scene, st, err);
    if (stats)
        fill_stats(r, scene, &view, &fs, &ss, t0, stats);
    return OIT_OK;
}

/* A failure's message starts with the scene's name. */
static oit_status name_scene(const oit_scene *scene, oit_status st, oit_error *err)
{
    const char *name = scene_name(scene);
    if (err && strncmp(err->message, name, strlen(name)) != 0)
        oit_error_prefix(err, name);
    return st;
}

/* oit_draw_stats of a draw, from the capture's and the streamer's figures. */
static void fill_stats(const oit_renderer *r, const oit_scene *scene, const oit_view *vp,
                       const oit_frame_stats *fsp, const oit_stream_frame_stats *ssp,
                       double t0, oit_draw_stats *stats)
{
    const oit_frame_stats fs = *fsp;
    const oit_stream_frame_stats ss = *ssp;
    const oit_view view = *vp;
    {
        *stats = (oit_draw_stats){.ms = oit_time_ms() - t0, .fragments = fs.fragments,
                                  .max_layers = fs.max_layers,
                                  .overflow_pixels = fs.overflow_pixels, .packs = ss.packs,
                                  .parts_drawn = ss.parts_drawn,
                                  .parts_culled = ss.parts_culled,
                                  .parts_skipped = ss.parts_skipped,
                                  .bytes_uploaded = ss.bytes_uploaded,
                                  .gpu_bytes_peak = ss.gpu_bytes_peak,
                                  .cache_hits = ss.cache_hits,
                                  .cache_bytes = ss.cache_bytes,
                                  .draw_calls = ss.draw_calls,
                                  .parts_clipped = ss.parts_clipped,
                                  .bytes_clipped = ss.bytes_clipped,
                                  .capture_slots = fs.capture_slots,
                                  .capture_slots_k = fs.capture_slots_k,
                                  .capture_fallback =
                                      r->streamer ? oit_streamer_capture_choice(r->streamer)->reason
                                                  : NULL,
                                  .gpu_frame = r->gpu.frame, .draw = r->draws,
                                  .method = r->method->name,
                                  .device = r->run ? oit_method_renderer(r->run) : r->device,
                                  .fragments_saturated = fs.fragments_saturated,
                                  .gpu_mesh_bytes = fs.gpu_mesh_bytes,
                                  .gpu_ms = r->gpu.frame ? r->gpu.ms : -1.0};
        memcpy(stats->gpu_phase_ms, r->gpu.phase_ms, sizeof stats->gpu_phase_ms);
        oit_stream_budget b = {0};
        if (scene->pf)
            oit_streamer_budget(r->streamer, &b);
        stats->gpu_budget = b.total;
        stats->ring_budget = b.ring;
        stats->cache_budget = b.cache;
        stats->capture_budget = b.capture;
        stats->store_budget = b.store;
        stats->gpu_free_bytes = b.free_bytes;
        stats->see_through = (uint32_t)view.shading.see_through;
        stats->opaque = (uint32_t)oit_shading_opaque(&view.shading);
        stats->resident = (uint32_t)b.resident;
        stats->budget_source = b.source;
        draw_stats_work(&fs, &ss, stats);
    }
}

/* One band's (or the whole frame's) image through the streamer's resolve,
 * as the tools' stream method renders it. */
static oit_status render_image(oit_renderer *r, const oit_view *v, oit_image *out,
                               uint32_t *counts, oit_frame_stats *fs,
                               oit_stream_frame_stats *ss, oit_error *err)
{
    static const oit_opaque_depth none = {0};
    r->bands++;
    oit_streamer_set_gpu_timer(r->streamer, r->timer);
    oit_streamer_set_opaque(r->streamer, &none);
    return oit_streamer_render_counts(r->streamer, v, out, counts, fs, ss, err);
}

/* A part file's image in bands of rows whose per-pixel state fits one
 * storage binding (view/render/gl/band.h), each copied into its rows of rgba,
 * as the method interface bands an in-core method's (view/render/method.c). */
static oit_status image_bands(oit_renderer *r, const oit_view *view, float *rgba,
                              uint32_t *counts, oit_frame_stats *fs, oit_stream_frame_stats *ss,
                              oit_error *err)
{
    uint64_t px = oit_streamer_pixel_bytes(view);
    int rows = 0, w = view->width, h = view->height;
    oit_status st = oit_band_rows(view, px, r->desc.binding_limit, &rows, err);
    for (int y0 = 0; st == OIT_OK && y0 < h; y0 += rows) {
        int y1 = y0 + rows < h ? y0 + rows : h;
        oit_view band = *view;
        if (rows < h)
            oit_view_band(view, y0, y1, &band);
        /* A frame of one band is read back into rgba itself (the stream
         * writes a given image in place, oit_image_reserve): no second
         * image to fault in and copy (the 1M plant at 1024x1024: ~50 ms a
         * frame on llvmpipe). */
        int direct = y0 == 0 && y1 == h;
        oit_image part = {0};
        if (direct)
            part = (oit_image){.width = w, .height = h, .rgba = rgba};
        oit_frame_stats bfs = {0};
        oit_stream_frame_stats bss = {0};
        st = render_image(r, &band, &part, counts ? counts + (size_t)y0 * w : NULL, &bfs,
                          &bss, err);
        if (st == OIT_OK && !direct)
            memcpy(rgba + (size_t)y0 * w * 4, part.rgba,
                   (size_t)w * (size_t)(y1 - y0) * 4 * sizeof *rgba);
        if (!direct)
            oit_image_free(&part);
        oit_frame_stats_add(fs, &bfs);
        oit_stream_frame_stats_add(ss, &bss);
    }
    return st;
}

/* An in-core scene's image through its method (view/render/method.h, which
 * bands it and times it on r's timer), written in place where the method
 * takes a given image (DFB, the capture), else copied. */
static oit_status run_pixels(oit_renderer *r, const oit_view *v, const oit_pixels_desc *px,
                             oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    oit_image img = {.width = v->width, .height = v->height, .rgba = px->rgba};
    oit_status st = oit_method_render(r->run, v, &img, px->counts, px->ambiguous, fs, err);
    if (st == OIT_OK && img.rgba != px->rgba)
        memcpy(px->rgba, img.rgba, (size_t)v->width * (size_t)v->height * 4 * sizeof *img.rgba);
    if (img.rgba != px->rgba)
        oit_image_free(&img);
    in_core_figures(r, !strcmp(r->method->name, "dfb"), fs, ss);
    return st;
}

/* The background alone, as a pixel no fragment reached resolves, with no
 * fragment counted and no pixel ambiguous. */
static void empty_image(const oit_view *view, const oit_pixels_desc *px)
{
    oit_pixel_state ps;
    float rgb[3];
    oit_pixel_begin(&ps);
    oit_pixel_end(&ps, &view->shading, rgb);
    size_t n = (size_t)view->width * (size_t)view->height;
    for (size_t i = 0; i < n; i++) {
        memcpy(px->rgba + 4 * i, rgb, sizeof rgb);
        px->rgba[4 * i + 3] = 1.0f;
    }
    if (px->counts)
        memset(px->counts, 0, n * sizeof *px->counts);
    if (px->ambiguous)
        memset(px->ambiguous, 0, n);
}

/* What a draw into memory is refused before any work: a depth texture, an
 * image too small, per-pixel figures the method has not. */
static oit_status pixels_check(const oit_renderer *r, const oit_frame *frame, const oit_view *v,
                               const oit_pixels_desc *px, oit_error *err)
{
    if (frame->depth_texture)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_renderer_draw_image: "
                             "oit_frame.depth_texture = %u: an image has no opaque depth; "
                             "draw into the caller's framebuffer (oit_renderer_draw)",
                             frame->depth_texture);
    size_t need = (size_t)v->width * (size_t)v->height * 4 * sizeof *px->rgba;
    if (px->rgba_bytes < need)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw_image: a %dx%d image "
                             "needs %zu bytes, rgba has %zu", v->width, v->height, need,
                             px->rgba_bytes);
    unsigned f = r->method->flags;
    if (px->counts && !(f & OIT_RENDER_METHOD_COUNTS))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_pixels_desc.counts: method \"%s\" "
                             "does not count fragments per pixel", r->method->name);
    if (px->ambiguous && !(f & OIT_RENDER_METHOD_AMBIGUITY))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_pixels_desc.ambiguous: method "
                             "\"%s\" does not flag ambiguous pixels", r->method->name);
    return OIT_OK;
}

/* The image of a GL method, the caller's GL state kept. */
static oit_status gl_pixels(oit_renderer *r, oit_scene *scene, const oit_view *view,
                            const oit_pixels_desc *px, double t0, oit_frame_stats *fs,
                            oit_stream_frame_stats *ss, oit_error *err)
{
    gl_saved saved;
    oit_lib_gl_save(&saved);
    oit_status st = oit_lib_gl_ready(r, err);
    if (st == OIT_OK)
        st = oit_lib_bind_scene(r, scene, 1, err);
    if (st == OIT_OK && scene->pf) {
        oit_gpu_timer_begin_frame(r->timer);
        r->bands = 0;
        st = image_bands(r, view, px->rgba, px->counts, fs, ss, err);
        frame_end(r, scene, st, t0, oit_gpu_timer_end_frame(r->timer));
    } else if (st == OIT_OK) {
        st = run_pixels(r, view, px, fs, ss, err);
    }
    gpu_take(r);
    oit_lib_gl_restore(&saved);
    return st;
}

oit_status oit_renderer_draw_pixels(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                                    const oit_pixels_desc *px, oit_draw_stats *stats,
                                    oit_error *err)
{
    if (!r || !scene || !frame || !px || !px->rgba)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw_pixels: NULL argument "
                             "(or a NULL rgba)");
    double t0 = oit_time_ms();
    oit_view view;
    oit_status st = oit_lib_method_for(r, scene, &r->method, err);
    if (st == OIT_OK)
        st = oit_lib_frame_view(r, scene, frame, px->background, &view, err);
    if (st == OIT_OK)
        st = pixels_check(r, frame, &view, px, err);
    if (st != OIT_OK)
        return st;
    oit_frame_stats fs = {0};
    oit_stream_frame_stats ss = {0};
    if (!scene->pf && scene->info.triangles == 0) { /* nothing in front of the background */
        r->draws++;
        empty_image(&view, px);
    } else if (r->method->flags & OIT_RENDER_METHOD_GL) {
        st = gl_pixels(r, scene, &view, px, t0, &fs, &ss, err);
    } else {
        st = oit_lib_bind_scene(r, scene, 1, err);
        if (st == OIT_OK)
            st = run_pixels(r, &view, px, &fs, &ss, err);
        r->draws++;
    }
    if (st != OIT_OK)
        return name_scene(scene, st, err);
    if (stats)
        fill_stats(r, scene, &view, &fs, &ss, t0, stats);
    return OIT_OK;
}

oit_status oit_renderer_prepare(oit_renderer *r, oit_scene *scene, oit_error *err)
{
    if (!r || !scene)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_prepare: NULL argument");
    oit_status st = oit_lib_method_for(r, scene, &r->method, err);
    int gl = st == OIT_OK && (r->method->flags & OIT_RENDER_METHOD_GL);
    gl_saved saved;
    if (gl)
        oit_lib_gl_save(&saved);
    if (gl)
        st = oit_lib_gl_ready(r, err);
    if (st == OIT_OK && (scene->pf || scene->info.triangles > 0))
        st = oit_lib_bind_scene(r, scene, 1, err);
    if (gl)
        oit_lib_gl_restore(&saved);
    return st == OIT_OK ? OIT_OK : name_scene(scene, st, err);
}

oit_status oit_renderer_draw_image(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                                   const float background[3], float *rgba, size_t rgba_bytes,
                                   oit_draw_stats *stats, oit_error *err)
{
    const oit_pixels_desc px = {.background = background, .rgba = rgba,
                                .rgba_bytes = rgba_bytes};
    return oit_renderer_draw_pixels(r, scene, frame, &px, stats, err);
}

oit_status oit_scene_share_order(oit_scene *scene, const oit_frame *frame, uint32_t *order,
                                 uint32_t order_count, oit_error *err)
{
    if (!scene || !frame || !order)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_share_order: NULL argument");
    uint32_t n = scene->info.share_count;
    if (order_count < n)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oit_scene_share_order: order holds "
                             "%u shares, the scene has %u", scene_name(scene), order_count, n);
    oit_view view;
    oit_status st = oit_lib_frame_camera(frame, &view, err);
    if (st == OIT_OK && !scene->share_set)
        order[0] = 0;
    else if (st == OIT_OK)
        st = oit_shares_view_order(scene->order, scene->share_set, &view, scene->ordered, order,
                                   err);
    if (st != OIT_OK)
        oit_error_prefix(err, scene_name(scene));
    return st;
}
