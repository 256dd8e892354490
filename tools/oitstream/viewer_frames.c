/* The viewer's frames (viewer_internal.h): the exact frame or a preview
 * (lower resolution or another method) rendered, upscaled, uploaded and
 * shown, and --stats rewritten after each. */
#include "tools/oitstream/viewer_internal.h"

/* ---- frames ---- */

static oit_status ensure_counts(viewer *v, int w, int h, oit_error *err)
{
    size_t need = (size_t)w * (size_t)h;
    if (need <= v->counts_cap)
        return OIT_OK;
    free(v->counts);
    v->counts_cap = 0;
    v->counts = calloc(need, sizeof *v->counts);
    if (!v->counts)
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot allocate %dx%d layer counts", w,
                             h);
    v->counts_cap = need;
    return OIT_OK;
}

/* Bilinear upscale of src to w x h (pixel centres aligned), into dst. */
static oit_status upscale(const oit_image *src, int w, int h, oit_image *dst, oit_error *err)
{
    oit_status s = oit_image_alloc(dst, w, h, err);
    if (s != OIT_OK)
        return s;
    int *x0 = malloc(sizeof *x0 * (size_t)w);
    float *fx = malloc(sizeof *fx * (size_t)w);
    if (!x0 || !fx) {
        free(x0);
        free(fx);
        oit_image_free(dst);
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot upscale to %dx%d", w, h);
    }
    for (int x = 0; x < w; x++) {
        float sx = ((float)x + 0.5f) * (float)src->width / (float)w - 0.5f;
        sx = sx < 0.0f ? 0.0f : sx;
        x0[x] = (int)sx < src->width - 1 ? (int)sx : src->width - 1;
        fx[x] = x0[x] < src->width - 1 ? sx - (float)x0[x] : 0.0f;
    }
    for (int y = 0; y < h; y++) {
        float sy = ((float)y + 0.5f) * (float)src->height / (float)h - 0.5f;
        sy = sy < 0.0f ? 0.0f : sy;
        int y0 = (int)sy < src->height - 1 ? (int)sy : src->height - 1;
        float fy = y0 < src->height - 1 ? sy - (float)y0 : 0.0f;
        int y1 = y0 < src->height - 1 ? y0 + 1 : y0;
        const float *r0 = src->rgba + (size_t)y0 * (size_t)src->width * 4;
        const float *r1 = src->rgba + (size_t)y1 * (size_t)src->width * 4;
        float *out = dst->rgba + (size_t)y * (size_t)w * 4;
        for (int x = 0; x < w; x++) {
            int a = x0[x], b = a < src->width - 1 ? a + 1 : a;
            float t = fx[x];
            for (int c = 0; c < 4; c++) {
                float top = r0[a * 4 + c] + (r0[b * 4 + c] - r0[a * 4 + c]) * t;
                float bot = r1[a * 4 + c] + (r1[b * 4 + c] - r1[a * 4 + c]) * t;
                out[x * 4 + c] = top + (bot - top) * fy;
            }
        }
    }
    free(x0);
    free(fx);
    return OIT_OK;
}

static const char *preview_method_name(oit_viewer_preview p)
{
    return p == OIT_PREVIEW_WBOIT ? "wboit" : p == OIT_PREVIEW_UNSORTED ? "unsorted" : NULL;
}

/* Whether moving shows a preview, and which: 1 lowres, 2 another method. */
static int preview_kind(const viewer *v)
{
    switch (v->desc->preview) {
    case OIT_PREVIEW_OFF:
        return 0;
    case OIT_PREVIEW_LOWRES:
        return 1;
    case OIT_PREVIEW_WBOIT:
    case OIT_PREVIEW_UNSORTED:
        return 2;
    default:
        return v->last_exact_wall_ms > AUTO_PREVIEW_MS ? 1 : 0;
    }
}

static oit_status open_preview_method(viewer *v, oit_error *err)
{
    if (v->pv_state)
        return OIT_OK;
    const oit_render_method_info *m = oit_method_find(preview_method_name(v->desc->preview));
    if (!m)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "viewer: no preview method");
    oit_run_options opt = v->options;
    opt.gl = v->gl;
    opt.threshold = NULL;
    oit_status s = oit_run_open(m, v->mesh, &opt, &v->pv_state, err);
    if (s == OIT_OK)
        v->pv_method = m;
    return s;
}

/* The adaptive preview scale: frames near 30 ms. */
static int first_preview_scale(const viewer *v)
{
    int f = (int)ceil(sqrt(v->last_exact_wall_ms / 30.0));
    return f < 2 ? 2 : f > PREVIEW_MAX_SCALE ? PREVIEW_MAX_SCALE : f;
}

/* After a preview at scale f took wall_ms: coarser while frames are slower
 * than 45 ms and the last step down in resolution paid (at least 25% less
 * time; below that the frame is bound by geometry, not pixels, and a
 * coarser one only blurs), finer when under 15 ms or when the coarser scale
 * proved no faster than this one. Times are smoothed per scale. */
static void adapt_preview_scale(viewer *v, double wall_ms)
{
    int f = v->preview_scale;
    double *ms = v->preview_ms_at;
    ms[f] =
        ms[f] > 0.0 ? 0.5 * (ms[f] + wall_ms) : wall_ms; /* smoothed: frames vary with the view */
    wall_ms = ms[f];
    if (wall_ms > 45.0 && f < PREVIEW_MAX_SCALE &&
        (f == 2 || ms[f - 1] == 0.0 || ms[f] < 0.75 * ms[f - 1]) &&
        !(ms[f + 1] > 0.0 && ms[f + 1] > 0.85 * ms[f]))
        v->preview_scale = f + 1;
    else if (f > 2 &&
             (wall_ms < 15.0 || (wall_ms > 45.0 && ms[f - 1] > 0.0 && ms[f] > 0.85 * ms[f - 1])))
        v->preview_scale = f - 1;
}

/* view through state: its image into *out, or with counts (a method that
 * counts) its layer heat map; the frame's figures into st (may be NULL). */
static oit_status render_shown(oit_run *state, const oit_view *view, uint32_t *counts,
                               oit_frame_stats *st, oit_image *out, oit_error *err)
{
    oit_image img = {0};
    oit_status s = oit_run_render(state, view, &img, counts, NULL, st, err);
    if (s == OIT_OK && counts) {
        s = oit_image_heatmap(counts, img.width, img.height, out, err);
        oit_image_free(&img);
    } else if (s == OIT_OK) {
        *out = img;
    }
    return s;
}

/* Renders the current view into v->base at the window's size: exact, or
 * (kind SHOWN_PREVIEW) the preview. */
static oit_status render_frame(viewer *v, int fb_w, int fb_h, int kind, oit_error *err)
{
    const oit_render_method_info *m = v->methods[v->current];
    oit_run *state = v->state;
    int pk = kind == SHOWN_PREVIEW ? preview_kind(v) : 0, scale = 1;
    if (kind == SHOWN_PREVIEW && pk == 0)
        kind = SHOWN_EXACT;
    if (pk == 2) {
        oit_status s = open_preview_method(v, err);
        if (s != OIT_OK)
            return s;
        m = v->pv_method;
        state = v->pv_state;
    } else if (pk == 1) {
        if (v->preview_scale < 2)
            v->preview_scale = first_preview_scale(v);
        scale = v->preview_scale;
    }
    int w = fb_w / scale > 0 ? fb_w / scale : 1, h = fb_h / scale > 0 ? fb_h / scale : 1;
    int heat = v->show_layers && (m->flags & OIT_RENDER_METHOD_COUNTS);
    oit_status s = heat ? ensure_counts(v, w, h, err) : OIT_OK;
    if (s != OIT_OK)
        return s;
    v->view.width = w;
    v->view.height = h;
    viewer_fit_clip(v);
    double t0 = glfwGetTime();
    memset(&v->st, 0, sizeof v->st);
    oit_image img = {0};
    s = render_shown(state, &v->view, heat ? v->counts : NULL, &v->st, &img, err);
    if (v->gpu_state != state)
        memset(&v->gpu, 0, sizeof v->gpu);
    v->gpu_state = state;
    v->gpu_absent = oit_run_gpu_absent(state);
    for (oit_gpu_times g; oit_run_gpu_poll(state, &g, 0);)
        v->gpu = g;
    if (s == OIT_OK && scale > 1) {
        oit_image big = {0};
        s = upscale(&img, fb_w, fb_h, &big, err);
        oit_image_free(&img);
        img = big;
    }
    if (s != OIT_OK) {
        oit_image_free(&img);
        return s;
    }
    oit_image_free(&v->base);
    v->base = img;
    double wall = (glfwGetTime() - t0) * 1000.0;
    v->last_wall_ms = wall;
    v->frames++;
    v->shown_kind = kind;
    v->shown_scale = scale;
    if (kind == SHOWN_EXACT) {
        v->exact_frames++;
        v->last_exact_wall_ms = wall;
    } else {
        v->preview_frames++;
        v->last_preview_wall_ms = wall;
        if (pk == 1)
            adapt_preview_scale(v, wall);
    }
    v->view.width = fb_w;
    v->view.height = fb_h;
    return OIT_OK;
}

/* P's image: the current view with the current method at width x height,
 * rendered offscreen (not the window's image: exact even while a preview
 * is shown, no overlay; the heat map where it is on), as oitstream --size
 * --view of that view renders it. */
oit_status viewer_render_shot(viewer *v, int width, int height, oit_image *out, oit_error *err)
{
    const oit_render_method_info *m = v->methods[v->current];
    int heat = v->show_layers && (m->flags & OIT_RENDER_METHOD_COUNTS);
    uint32_t *counts = heat ? malloc((size_t)width * (size_t)height * sizeof *counts) : NULL;
    if (heat && !counts)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate %dx%d layer counts", width,
                             height);
    viewer_fit_clip(v); /* the camera may have moved since the last frame */
    oit_view view = v->view;
    view.width = width;
    view.height = height;
    oit_status s = render_shown(v->state, &view, counts, NULL, out, err);
    free(counts);
    return s;
}

static void upload_texture(viewer *v, const oit_image *img)
{
    if (!v->tex || v->tex_w != img->width || v->tex_h != img->height) {
        glDeleteTextures(1, &v->tex);
        glGenTextures(1, &v->tex);
        glBindTexture(GL_TEXTURE_2D, v->tex);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, img->width, img->height);
        v->tex_w = img->width;
        v->tex_h = img->height;
        if (!v->fbo)
            glGenFramebuffers(1, &v->fbo);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, v->fbo);
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, v->tex, 0);
    }
    /* The methods may leave an upload ring bound; a bound unpack buffer
     * would turn the pointer below into an offset. */
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, v->tex);
    /* The image's row 0 is the top; GL's is the bottom: upload flipped. */
    for (int y = 0; y < img->height; y++)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, img->height - 1 - y, img->width, 1, GL_RGBA, GL_FLOAT,
                        img->rgba + 4 * (size_t)y * (size_t)img->width);
}

/* Reads the back buffer (what the next swap shows) into v->shot. */
static oit_status read_back(viewer *v, int w, int h, oit_error *err)
{
    unsigned char *px = malloc((size_t)w * (size_t)h * 4);
    oit_image_free(&v->shot);
    if (!px || oit_image_alloc(&v->shot, w, h, err) != OIT_OK) {
        free(px);
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot allocate a %dx%d screenshot", w,
                             h);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (int y = 0; y < h; y++)
        for (size_t i = 0; i < (size_t)w * 4; i++)
            v->shot.rgba[(size_t)y * (size_t)w * 4 + i] =
                px[(size_t)(h - 1 - y) * (size_t)w * 4 + i] / 255.0f;
    free(px);
    return oit_gl_check("viewer: reading the window back", err);
}

/* Composes the overlays over the last rendered image and shows it; no
 * rendering. With --window-screenshot each image shown is read back, so
 * that the last one is there to write when the loop stops; G's, once. */
oit_status viewer_present(viewer *v, oit_error *err)
{
    if (!v->base.rgba)
        return OIT_OK;
    double t0 = glfwGetTime();
    oit_status s = viewer_compose(v, err);
    if (s != OIT_OK)
        return s;
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(v->win, &fb_w, &fb_h);
    if (fb_w <= 0 || fb_h <= 0)
        return OIT_OK;
    upload_texture(v, &v->shown);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, v->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST); /* the blit is clipped by it */
    glViewport(0, 0, fb_w, fb_h);
    glBlitFramebuffer(0, 0, v->shown.width, v->shown.height, 0, 0, fb_w, fb_h, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    s = oit_gl_check("viewer: presenting the frame", err);
    if (s == OIT_OK && (v->desc->screenshot || v->grab_pending))
        s = read_back(v, fb_w, fb_h, err);
    char title[sizeof v->model_name + sizeof v->status + 16];
    snprintf(title, sizeof title, "oitstream %s: %s", v->model_name, v->status);
    glfwSetWindowTitle(v->win, title);
    glfwSwapBuffers(v->win);
    v->last_present_ms = (glfwGetTime() - t0) * 1000.0;
    v->presents++;
    v->recompose = 0;
    if (s == OIT_OK && v->grab_pending && v->shot.rgba)
        viewer_save_window(v);
    return s;
}

/* --stats with --window: the counters, rewritten (atomically) after every
 * frame, so that a test or a script can read them while the window runs. */
void viewer_write_stats(viewer *v)
{
    const char *path = v->desc->stats_path;
    if (!path)
        return;
    char tmp[4096], view[512];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return;
    oit_stats_format_view(&v->view.camera, v->mesh->info.origin, view, sizeof view);
    int preview = v->shown_kind == SHOWN_PREVIEW;
    char up[2] = {viewer_axis_name(v->up_axis), 0};
    oit_json w;
    oit_json_init(&w, f, tmp);
    const oit_json_uint_member counts[] = {{"frames_rendered", (unsigned)v->frames},
                                           {"exact_frames", (unsigned)v->exact_frames},
                                           {"preview_frames", (unsigned)v->preview_frames},
                                           {"presented", (unsigned)v->presents}};
    oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
    OIT_JSON_UINTS(&w, counts);
    oit_json_string(&w, "shown", preview ? "preview" : "exact");
    oit_json_int(&w, "preview_scale", preview ? v->shown_scale : 1);
    oit_json_string(&w, "method", v->methods[v->current]->name);
    oit_json_int(&w, "width", v->view.width);
    oit_json_int(&w, "height", v->view.height);
    oit_json_fixed(&w, "frame_ms", v->last_wall_ms, 3);
    oit_json_fixed(&w, "last_exact_ms", v->last_exact_wall_ms, 3);
    oit_json_fixed(&w, "last_preview_ms", v->last_preview_wall_ms, 3);
    oit_json_fixed(&w, "present_ms", v->last_present_ms, 3);
    oit_json_string(&w, "up", up);
    oit_json_string(&w, "view", view);
    oit_json_end(&w);
    /* a file that failed to write is not renamed over the last good one */
    if (oit_json_close(&w, NULL) == OIT_OK)
        rename(tmp, path);
}

/* Renders (kind) and shows the frame. */
oit_status viewer_one_frame(viewer *v, int kind, oit_error *err)
{
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(v->win, &fb_w, &fb_h);
    v->moved = 0;
    v->changed = 0;
    if (fb_w <= 0 || fb_h <= 0)
        return OIT_OK; /* minimised: nothing to draw into (restoring it resizes: viewer_on_resize)
                        */
    oit_status s = render_frame(v, fb_w, fb_h, kind, err);
    if (s == OIT_OK)
        s = viewer_present(v, err);
    if (s == OIT_OK)
        viewer_write_stats(v);
    return s;
}
