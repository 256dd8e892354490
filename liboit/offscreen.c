/* Offscreen rendering (include/oit/offscreen.h): a headless context of its
 * own, an RGBA32F framebuffer cleared to the background, oit_renderer_draw
 * into it, and a readback flipped to image order. */
#include "oit/offscreen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/shade.h"
#include "view/render/image/view.h"

struct oit_offscreen {
    oit_gl *gl;
    oit_renderer *renderer;
    GLuint fbo, tex;
    int width, height; /* of tex; 0: none yet */
    float *readback;   /* width * height * 4 */
    int linear;        /* the renderer composites in linear light */
};

void oit_offscreen_destroy(oit_offscreen *o)
{
    if (!o)
        return;
    if (o->gl && oit_gl_make_current(o->gl, NULL) == OIT_OK) {
        oit_renderer_destroy(o->renderer);
        glDeleteFramebuffers(1, &o->fbo);
        glDeleteTextures(1, &o->tex);
    }
    oit_gl_destroy(o->gl);
    free(o->readback);
    free(o);
}

oit_status oit_offscreen_create(const oit_offscreen_desc *desc, oit_offscreen **out,
                                oit_error *err)
{
    if (!out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_create: out is NULL");
    *out = NULL;
    oit_offscreen *o = calloc(1, sizeof *o);
    if (!o)
        return oit_error_set(err, OIT_ERR_NOMEM, "oit_offscreen_create: out of memory");
    oit_status s = oit_gl_create(NULL, &o->gl, err);
    if (s == OIT_OK)
        s = oit_renderer_create(desc ? &desc->renderer : NULL, &o->renderer, err);
    o->linear = desc && desc->renderer.shading.colour_space == OIT_RENDER_COLOUR_LINEAR;
    if (s != OIT_OK) {
        oit_error_prefix(err, "oit_offscreen_create");
        oit_offscreen_destroy(o);
        return s;
    }
    *out = o;
    return OIT_OK;
}

void oit_offscreen_release_scene(oit_offscreen *o, const oit_scene *scene)
{
    if (o && scene && oit_gl_make_current(o->gl, NULL) == OIT_OK)
        oit_renderer_release_scene(o->renderer, scene);
}

const char *oit_offscreen_gl_renderer(const oit_offscreen *o)
{
    return o ? oit_gl_renderer(o->gl) : "";
}

void oit_offscreen_get_desc(const oit_offscreen *o, oit_offscreen_desc *out)
{
    oit_renderer_get_desc(o->renderer, &out->renderer);
}

/* The colour target, reallocated when the size changes. */
static oit_status ensure_target(oit_offscreen *o, int w, int h, oit_error *err)
{
    if (o->width == w && o->height == h)
        return OIT_OK;
    glDeleteFramebuffers(1, &o->fbo);
    glDeleteTextures(1, &o->tex);
    free(o->readback);
    o->fbo = o->tex = 0;
    o->width = o->height = 0;
    o->readback = malloc((size_t)w * h * 4 * sizeof *o->readback);
    if (!o->readback)
        return oit_error_set(err, OIT_ERR_NOMEM, "oit_offscreen_render: cannot allocate "
                             "%dx%d pixels", w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &o->tex);
    glTextureStorage2D(o->tex, 1, GL_RGBA32F, w, h);
    oit_gl_poison_texture(o->tex, GL_RGBA32F);
    glCreateFramebuffers(1, &o->fbo);
    glNamedFramebufferTexture(o->fbo, GL_COLOR_ATTACHMENT0, o->tex, 0);
    oit_status s = oit_gl_check("oit_offscreen_render: framebuffer", err);
    if (s == OIT_OK &&
        glCheckNamedFramebufferStatus(o->fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        s = oit_error_set(err, OIT_ERR_GL, "oit_offscreen_render: a %dx%d RGBA32F "
                          "framebuffer is incomplete", w, h);
    if (s == OIT_OK) {
        o->width = w;
        o->height = h;
    }
    return s;
}

/* The bounding sphere of the scene (the unit sphere for empty bounds). */
static void bounding_sphere(const oit_scene_info *info, double c[3], double *r)
{
    double r2 = 0.0;
    int ok = isfinite(info->bounds_min[0]) && isfinite(info->bounds_max[0]) &&
             info->bounds_min[0] <= info->bounds_max[0];
    for (int k = 0; k < 3; k++) {
        double lo = ok ? info->bounds_min[k] : -1.0, hi = ok ? info->bounds_max[k] : 1.0;
        c[k] = 0.5 * (lo + hi);
        r2 += 0.25 * (hi - lo) * (hi - lo);
    }
    *r = r2 > 0.0 ? sqrt(r2) : 1.0;
}

static int is_zero(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (v[i] != 0.0f)
            return 0;
    return 1;
}

/* The internal axis number (view/render/image/view.h: 0 x, 1 y, 2 z) of a public one. */
static int axis_of(oit_up_axis up)
{
    return up == OIT_UP_Z ? 2 : up == OIT_UP_X ? 0 : 1;
}

/* The axis an up vector without eye and target names: 0 is y, else it
 * must point along +x, +y or +z. */
static oit_status up_axis_of_vector(const float up[3], oit_up_axis *out, oit_error *err)
{
    static const oit_up_axis axes[3] = {OIT_UP_X, OIT_UP_Y, OIT_UP_Z};
    *out = OIT_UP_Y;
    if (is_zero(up, 3))
        return OIT_OK;
    for (int k = 0; k < 3; k++)
        if (up[k] > 0.0f && isfinite(up[k]) && up[(k + 1) % 3] == 0.0f &&
            up[(k + 2) % 3] == 0.0f) {
            *out = axes[k];
            return OIT_OK;
        }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view.up = (%g, %g, %g) without "
                         "eye and target: the default view turns about an axis, so up must "
                         "point along +x, +y or +z (or give eye and target)",
                         up[0], up[1], up[2]);
}

static void default_camera(const oit_scene_info *info, oit_up_axis up, float azimuth_deg,
                           float elevation_deg, oit_camera *cam)
{
    oit_camera_default_up(cam, info->bounds_min, info->bounds_max, azimuth_deg,
                          elevation_deg, axis_of(up));
}

oit_status oit_offscreen_default_view(const oit_scene *scene, oit_up_axis up,
                                      float azimuth_deg, float elevation_deg,
                                      oit_offscreen_view *view, oit_error *err)
{
    if (!scene || !view)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_default_view: NULL argument");
    if (up != OIT_UP_Y && up != OIT_UP_Z && up != OIT_UP_X)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_default_view: up = %d is "
                             "not an oit_up_axis", (int)up);
    if (!isfinite(azimuth_deg))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_default_view: azimuth %g "
                             "is not a finite angle", azimuth_deg);
    if (!(elevation_deg >= -90.0f && elevation_deg <= 90.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_default_view: elevation "
                             "%g is outside [-90, 90]", elevation_deg);
    oit_scene_info info;
    oit_status s = oit_scene_get_info(scene, &info, err);
    if (s != OIT_OK)
        return s;
    oit_camera cam;
    default_camera(&info, up, azimuth_deg, elevation_deg, &cam);
    view->use_matrices = 0;
    memcpy(view->eye, cam.eye, sizeof view->eye);
    memcpy(view->target, cam.target, sizeof view->target);
    memcpy(view->up, cam.up, sizeof view->up);
    view->fovy_deg = cam.fovy_deg;
    view->znear = cam.znear;
    view->zfar = cam.zfar;
    return OIT_OK;
}

/* The default view moved along its direction so that the bounding sphere
 * fills fovy_deg as it filled the default 45 degrees, its planes fitted
 * again. */
static void refit_fovy(const oit_scene_info *info, float fovy_deg, oit_camera *cam)
{
    double c[3], r, d[3], len = 0.0;
    bounding_sphere(info, c, &r);
    for (int k = 0; k < 3; k++) {
        d[k] = (double)cam->eye[k] - cam->target[k];
        len += d[k] * d[k];
    }
    len = sqrt(len);
    double dist = r / sin(0.5 * fovy_deg * 3.14159265358979323846 / 180.0);
    for (int k = 0; k < 3; k++)
        cam->eye[k] = (float)(cam->target[k] + d[k] / len * dist);
    cam->fovy_deg = fovy_deg;
    cam->znear = (float)fmax(dist - 1.05 * r, 1e-4 * dist);
    cam->zfar = (float)(dist + 1.05 * r);
}

static oit_status make_frame(const oit_scene *scene, const oit_offscreen_view *v,
                             oit_frame *f, oit_error *err)
{
    f->viewport_width = v->width;
    f->viewport_height = v->height;
    f->clip_count = v->clip_count;
    memcpy(f->clip, v->clip, sizeof f->clip);
    if (v->use_matrices) {
        memcpy(f->view, v->view, sizeof f->view);
        memcpy(f->projection, v->projection, sizeof f->projection);
        return OIT_OK;
    }
    oit_scene_info info;
    oit_status s = oit_scene_get_info(scene, &info, err);
    if (s != OIT_OK)
        return s;
    oit_camera cam;
    int look_at = !is_zero(v->eye, 3) || !is_zero(v->target, 3);
    if (!look_at) {
        oit_up_axis up = (oit_up_axis)info.up_axis;
        if (!is_zero(v->up, 3))
            s = up_axis_of_vector(v->up, &up, err);
        if (s != OIT_OK)
            return s;
        default_camera(&info, up, 0.0f, 20.0f, &cam);
        if (v->fovy_deg != 0.0f) {
            if (!(v->fovy_deg > 0.0f && v->fovy_deg < 180.0f))
                return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view.fovy_deg = "
                                     "%g is outside (0, 180)", v->fovy_deg);
            refit_fovy(&info, v->fovy_deg, &cam);
        }
        if (v->znear != 0.0f || v->zfar != 0.0f) {
            cam.znear = v->znear;
            cam.zfar = v->zfar;
            if (!(cam.znear > 0.0f && cam.zfar > cam.znear && isfinite(cam.zfar)))
                return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view: znear %g, "
                                     "zfar %g: need 0 < znear < zfar < inf", cam.znear,
                                     cam.zfar);
        }
    } else {
        double d2 = 0.0;
        for (int k = 0; k < 3; k++)
            d2 += ((double)v->eye[k] - v->target[k]) * ((double)v->eye[k] - v->target[k]);
        if (!(d2 > 0.0))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view: eye and target "
                                 "are the same point (%g, %g, %g): no view direction",
                                 v->eye[0], v->eye[1], v->eye[2]);
        memset(&cam, 0, sizeof cam);
        memcpy(cam.eye, v->eye, sizeof cam.eye);
        memcpy(cam.target, v->target, sizeof cam.target);
        if (is_zero(v->up, 3))
            cam.up[1] = 1.0f;
        else
            memcpy(cam.up, v->up, sizeof cam.up);
        cam.fovy_deg = v->fovy_deg != 0.0f ? v->fovy_deg : 45.0f;
        if (!(cam.fovy_deg > 0.0f && cam.fovy_deg < 180.0f))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view.fovy_deg = %g is "
                                 "outside (0, 180)", v->fovy_deg);
        if (v->znear == 0.0f && v->zfar == 0.0f) {
            double c[3], r, e2 = 0.0;
            bounding_sphere(&info, c, &r);
            for (int k = 0; k < 3; k++)
                e2 += (v->eye[k] - c[k]) * (v->eye[k] - c[k]);
            double e = sqrt(e2);
            cam.znear = (float)fmax(e - 1.05 * r, 1e-4 * fmax(e, r));
            cam.zfar = (float)(e + 1.05 * r);
        } else {
            cam.znear = v->znear;
            cam.zfar = v->zfar;
        }
        if (!(cam.znear > 0.0f && cam.zfar > cam.znear && isfinite(cam.zfar)))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view: znear %g, zfar "
                                 "%g: need 0 < znear < zfar < inf", cam.znear, cam.zfar);
    }
    oit_camera_view_matrix(&cam, f->view);
    oit_camera_proj_matrix(&cam, (float)v->width / (float)v->height, f->projection);
    return OIT_OK;
}

static unsigned char to_byte(float v)
{
    if (!(v > 0.0f)) return 0; /* also NaN */
    if (v >= 1.0f) return 255;
    return (unsigned char)lrintf(v * 255.0f);
}

/* A method that draws images only (oit_renderer_desc.method: neither the
 * stream nor DFB, which blend into the target). */
static int image_only(const oit_offscreen *o)
{
    oit_renderer_desc d;
    oit_renderer_get_desc(o->renderer, &d);
    return d.method && strcmp(d.method, "stream") != 0 && strcmp(d.method, "dfb") != 0;
}

/* Such a method's frame through oit_renderer_draw_image (row 0 at the
 * top, sRGB-encoded, over an opaque background) into the pixels. */
static oit_status render_image(oit_offscreen *o, oit_scene *scene, const oit_offscreen_view *view,
                               const oit_frame *frame, void *pixels, oit_draw_stats *stats,
                               oit_error *err)
{
    int w = view->width, h = view->height;
    if (view->format == OIT_PIXELS_PREMUL32F ||
        (!is_zero(view->background, 4) && view->background[3] < 1.0f))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_offscreen_view: this method draws "
                             "images over an opaque background only, not %s",
                             view->format == OIT_PIXELS_PREMUL32F ? "OIT_PIXELS_PREMUL32F"
                                                                 : "background[3] < 1");
    size_t n = (size_t)w * h * 4;
    oit_status s = oit_renderer_draw_image(o->renderer, scene, frame,
                                           is_zero(view->background, 4) ? NULL : view->background,
                                           o->readback, n * sizeof *o->readback, stats, err);
    if (s == OIT_OK && view->format == OIT_PIXELS_RGBA8)
        for (size_t i = 0; i < n; i++)
            ((unsigned char *)pixels)[i] = to_byte(o->readback[i]);
    else if (s == OIT_OK)
        memcpy(pixels, o->readback, n * sizeof *o->readback);
    return s;
}

oit_status oit_offscreen_render(oit_offscreen *o, oit_scene *scene,
                                const oit_offscreen_view *view, void *pixels,
                                size_t pixels_bytes, oit_draw_stats *stats, oit_error *err)
{
    if (!o || !scene || !view || !pixels)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_render: NULL argument");
    int w = view->width, h = view->height;
    if (w <= 0 || h <= 0 || w > 32768 || h > 32768)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view: size %dx%d is "
                             "outside 1..32768 a side", w, h);
    if (view->format != OIT_PIXELS_RGBA8 && view->format != OIT_PIXELS_RGBA32F &&
        view->format != OIT_PIXELS_PREMUL32F)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view.format = %d is not an "
                             "oit_pixel_format", (int)view->format);
    size_t comp = view->format == OIT_PIXELS_RGBA8 ? 1 : sizeof(float);
    size_t need = (size_t)w * h * 4 * comp;
    if (pixels_bytes < need)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_render: a %dx%d %s image "
                             "needs %zu bytes, the buffer has %zu", w, h,
                             comp == 1 ? "RGBA8" : "float RGBA", need, pixels_bytes);
    oit_frame frame = {0};
    oit_status s = make_frame(scene, view, &frame, err);
    if (s == OIT_OK)
        s = oit_gl_make_current(o->gl, err);
    if (s == OIT_OK) {
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        if (w > max_size || h > max_size)
            s = oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_view: size %dx%d exceeds "
                              "this GL's %d pixels a side", w, h, max_size);
    }
    if (s == OIT_OK)
        s = ensure_target(o, w, h, err);
    if (s != OIT_OK)
        return s;
    if (image_only(o))
        return render_image(o, scene, view, &frame, pixels, stats, err);
    /* The frame alone: over transparent black, liboit.h's Result leaves
     * C and 1 - t. */
    int premul = view->format == OIT_PIXELS_PREMUL32F;
    float bg[4];
    int all_zero = is_zero(view->background, 4);
    for (int c = 0; c < 4; c++)
        bg[c] = premul ? 0.0f : all_zero ? 1.0f : fmaxf(view->background[c], 0.0f);
    /* Linear light: the float target holds linear values (GL does not
     * encode into a float target), so the background is decoded here and
     * the result encoded after readback (offscreen.h). */
    for (int c = 0; c < 3 && o->linear; c++)
        bg[c] = (float)oit_srgb_decode(bg[c]);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
    glClearNamedFramebufferfv(o->fbo, GL_COLOR, 0, bg);
    frame.framebuffer = o->fbo;
    s = oit_renderer_draw(o->renderer, scene, &frame, stats, err);
    if (s != OIT_OK)
        return s;
    glGetTextureImage(o->tex, 0, GL_RGBA, GL_FLOAT,
                      (GLsizei)((size_t)w * h * 4 * sizeof *o->readback), o->readback);
    s = oit_gl_check("oit_offscreen_render: readback", err);
    if (s == OIT_OK)
        s = oit_gl_debug_check(o->gl, "oit_offscreen_render", err);
    if (s != OIT_OK)
        return s;
    size_t row = (size_t)w * 4;
    if (o->linear && !premul)
        for (size_t i = 0; i < (size_t)w * h * 4; i++)
            if (i % 4 != 3)
                o->readback[i] = (float)oit_srgb_encode(o->readback[i]);
    for (int y = 0; y < h; y++) {
        const float *src = o->readback + (size_t)(h - 1 - y) * row;
        if (comp == 1) {
            unsigned char *dst = (unsigned char *)pixels + (size_t)y * row;
            for (size_t i = 0; i < row; i++)
                dst[i] = to_byte(src[i]);
        } else {
            memcpy((float *)pixels + (size_t)y * row, src, row * sizeof *src);
        }
    }
    return OIT_OK;
}

oit_status oit_offscreen_pick(oit_offscreen *o, oit_scene *scene, const oit_offscreen_view *view,
                              int x, int y, oit_pick_layer *layers, size_t capacity,
                              size_t *count, oit_error *err)
{
    if (!o || !scene || !view)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_offscreen_pick: NULL argument");
    oit_frame frame = {0};
    oit_status s = make_frame(scene, view, &frame, err);
    if (s == OIT_OK)
        s = oit_renderer_pick(o->renderer, scene, &frame, x, y, layers, capacity, count, err);
    return s;
}
