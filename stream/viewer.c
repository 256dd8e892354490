/* The interactive loop of viewer.h. Methods render into an oit_image in the
 * window's context; the image (or its heat map) gets the status line and is
 * uploaded to a texture and blitted to the default framebuffer. */
#include "stream/viewer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/gl_context.h"
#include "render/gl_util.h"
#include "render/image.h"
#include "stream/text_overlay.h"

#define GLFW_INCLUDE_NONE /* GL comes from gl_util.h (core profile prototypes) */
#include <GLFW/glfw3.h>

/* Keys 1..9 reach the first KEYED_METHODS; the rest only start with --method. */
enum { MAX_METHODS = 16, KEYED_METHODS = 9, KEY_QUEUE = 64, KEY_ESC = 27 };

typedef struct viewer {
    const oit_viewer_desc *desc;
    oit_gl *gl;
    GLFWwindow *win;
    const oit_render_method *methods[MAX_METHODS];
    int method_count, current;
    oit_method_state *state;
    oit_view view;
    float centre[3], radius; /* bounding sphere, for the clip planes */
    int show_layers, quit, drag;
    double mouse_x, mouse_y;
    char keys[KEY_QUEUE];
    int key_count;
    uint32_t *counts;
    oit_image frame, shown, shot;
    GLuint tex, fbo;
    int tex_w, tex_h;
    oit_frame_stats st;
    int frames, screenshots;
    int save_pending; /* P: save after the next frame is shown */
    float epsilon;    /* early termination the methods open with (E toggles) */
    char status[160];
} viewer;

/* ---- camera ---- */

static void sub3(const float a[3], const float b[3], float out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static float normalize3(float v[3])
{
    float n = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0.0f)
        for (int k = 0; k < 3; k++)
            v[k] /= n;
    return n;
}

/* Rotates v by angle (radians) about the unit axis (Rodrigues). */
static void rotate3(float v[3], const float axis[3], float angle)
{
    float c = cosf(angle), s = sinf(angle), kxv[3];
    float kdv = axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2];
    cross3(axis, v, kxv);
    for (int k = 0; k < 3; k++)
        v[k] = v[k] * c + kxv[k] * s + axis[k] * kdv * (1.0f - c);
}

/* Clip planes around the bounding sphere as seen from the current eye, so
 * that orbiting, zooming and flying never cut the model. */
static void fit_clip(viewer *v)
{
    oit_camera *c = &v->view.camera;
    float f[3], to_c[3];
    sub3(c->target, c->eye, f);
    normalize3(f);
    sub3(v->centre, c->eye, to_c);
    float dc = f[0] * to_c[0] + f[1] * to_c[1] + f[2] * to_c[2];
    float r = 1.05f * v->radius;
    c->zfar = dc + r > 0.0f ? dc + r : r;
    c->znear = fmaxf(dc - r, 1e-4f * c->zfar);
}

/* Left drag: azimuth about the up axis, elevation about the right axis,
 * kept short of the poles where the view would flip. */
static void orbit(viewer *v, double dx, double dy)
{
    oit_camera *c = &v->view.camera;
    float off[3], up[3] = {c->up[0], c->up[1], c->up[2]}, right[3];
    sub3(c->eye, c->target, off);
    normalize3(up);
    rotate3(off, up, (float)(-dx * 0.01));
    cross3(off, up, right);
    if (normalize3(right) > 0.0f) {
        float before[3] = {off[0], off[1], off[2]};
        rotate3(off, right, (float)(dy * 0.01));
        float len = sqrtf(off[0] * off[0] + off[1] * off[1] + off[2] * off[2]);
        float cosu = (off[0] * up[0] + off[1] * up[1] + off[2] * up[2]) / len;
        if (fabsf(cosu) > 0.995f)
            memcpy(off, before, sizeof off);
    }
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->target[k] + off[k];
}

static void zoom(viewer *v, double factor)
{
    oit_camera *c = &v->view.camera;
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->target[k] + (c->eye[k] - c->target[k]) * (float)factor;
}

/* One step of 5% of the eye-target distance along forward, right or up. */
static void fly(viewer *v, int forward, int right, int up_dir)
{
    oit_camera *c = &v->view.camera;
    float f[3], r[3], u[3] = {c->up[0], c->up[1], c->up[2]};
    sub3(c->target, c->eye, f);
    float step = 0.05f * normalize3(f);
    normalize3(u);
    cross3(f, u, r);
    normalize3(r);
    for (int k = 0; k < 3; k++) {
        float d = step * ((float)forward * f[k] + (float)right * r[k] + (float)up_dir * u[k]);
        c->eye[k] += d;
        c->target[k] += d;
    }
}

/* ---- input ---- */

static void push_key(viewer *v, char key)
{
    if (v->key_count < KEY_QUEUE)
        v->keys[v->key_count++] = key;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (action == GLFW_RELEASE)
        return;
    if ((key >= GLFW_KEY_A && key <= GLFW_KEY_Z) || (key >= GLFW_KEY_1 && key <= GLFW_KEY_9))
        push_key(v, (char)key); /* GLFW's codes for these are their ASCII capitals/digits */
    else if (key == GLFW_KEY_SPACE)
        push_key(v, ' ');
    else if (key == GLFW_KEY_ESCAPE)
        push_key(v, KEY_ESC);
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    viewer *v = glfwGetWindowUserPointer(w);
    int which = button == GLFW_MOUSE_BUTTON_LEFT ? 1 : button == GLFW_MOUSE_BUTTON_RIGHT ? 2 : 0;
    if (action == GLFW_PRESS && which)
        v->drag = which;
    else if (action == GLFW_RELEASE && which == v->drag)
        v->drag = 0;
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (v->drag == 1)
        orbit(v, x - v->mouse_x, y - v->mouse_y);
    else if (v->drag == 2)
        zoom(v, exp((y - v->mouse_y) * 0.01));
    v->mouse_x = x;
    v->mouse_y = y;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    zoom(glfwGetWindowUserPointer(w), pow(0.9, dy));
}

/* ---- methods ---- */

/* The table's methods that can render this input, in the table's order. */
static void list_methods(viewer *v)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_render_method_names(names, sizeof names);
    for (char *tok = strtok(names, "|"); tok && v->method_count < MAX_METHODS;
         tok = strtok(NULL, "|")) {
        const oit_render_method *m = oit_render_method_find(tok);
        if (m && (!m->needs_partfile || v->desc->partfile) &&
            (m->needs_partfile || v->desc->mesh->count > 0))
            v->methods[v->method_count++] = m;
    }
}

/* Opens method i in the window's context; on failure the current one stays. */
static oit_status switch_method(viewer *v, int i, oit_error *err)
{
    oit_method_options opt = v->desc->options;
    opt.gl = v->gl;
    opt.epsilon = v->epsilon;
    oit_method_state *st = NULL;
    oit_status s = v->methods[i]->open(v->desc->mesh, &opt, &st, err);
    if (s != OIT_OK)
        return s;
    if (v->state)
        v->methods[v->current]->close(v->state);
    v->state = st;
    v->current = i;
    printf("viewer: method %d: %s (%s)\n", i + 1, v->methods[i]->name,
           v->methods[i]->renderer(st));
    return OIT_OK;
}

static void key_method(viewer *v, int i)
{
    oit_error err = {0};
    if (i >= v->method_count)
        printf("viewer: no method %d (this input has %d)\n", i + 1, v->method_count);
    else if (i != v->current && switch_method(v, i, &err) != OIT_OK)
        printf("viewer: %s: %s\n", v->methods[i]->name, err.message);
}

static void save_screenshot(viewer *v)
{
    char path[64];
    oit_error err = {0};
    v->save_pending = 0;
    snprintf(path, sizeof path, "oitstream_%03d.png", v->screenshots++);
    if (oit_image_write_png(&v->shot, path, &err) != OIT_OK)
        printf("viewer: %s\n", err.message);
    else
        printf("viewer: screenshot %s\n", path);
}

/* E: early termination off, or on at --epsilon (1/255 when none was given:
 * an error no 8-bit display shows). Only the streamer uses it; the method
 * is reopened so that it takes effect from the next frame. */
static void toggle_epsilon(viewer *v)
{
    float on = v->desc->options.epsilon > 0.0f ? v->desc->options.epsilon : 1.0f / 255.0f;
    float was = v->epsilon;
    oit_error err = {0};
    v->epsilon = was > 0.0f ? 0.0f : on;
    if (switch_method(v, v->current, &err) != OIT_OK) {
        v->epsilon = was;
        printf("viewer: early termination: %s\n", err.message);
    } else if (v->epsilon > 0.0f) {
        printf("viewer: early termination on, epsilon %g%s\n", v->epsilon,
               v->methods[v->current]->stream_stats ? "" : " (used by the stream method only)");
    } else {
        printf("viewer: early termination off (exact)\n");
    }
}

static void toggle_shading(viewer *v)
{
    oit_shading *s = &v->view.shading;
    s->mode = s->mode == OIT_SHADING_TRANSPARENT ? OIT_SHADING_TRANSLUCENT
                                                 : OIT_SHADING_TRANSPARENT;
    oit_shading_resolve_defaults(s);
    printf("viewer: shading %s\n", s->mode == OIT_SHADING_TRANSPARENT ? "transparent" : "translucent");
}

static void handle_key(viewer *v, char key)
{
    switch (key) {
    case KEY_ESC: case 'Q': v->quit = 1; break;
    case 'W': fly(v, 1, 0, 0); break;
    case 'S': fly(v, -1, 0, 0); break;
    case 'D': fly(v, 0, 1, 0); break;
    case 'A': fly(v, 0, -1, 0); break;
    case ' ': fly(v, 0, 0, 1); break;
    case 'C': fly(v, 0, 0, -1); break;
    case 'R': v->view.camera = v->desc->camera; break;
    case 'T': toggle_shading(v); break;
    case 'P': v->save_pending = 1; break;
    case 'L':
        v->show_layers = !v->show_layers;
        printf("viewer: layer heat map %s%s\n", v->show_layers ? "on" : "off",
               v->show_layers && !v->methods[v->current]->has_counts
                   ? " (not available for this method: it counts no layers per pixel)" : "");
        break;
    case 'E':
        toggle_epsilon(v);
        break;
    default:
        if (key >= '1' && key <= '9')
            key_method(v, key - '1');
    }
}

/* ---- frames ---- */

static void human(double x, char *buf, size_t cap)
{
    if (x >= 1e9) snprintf(buf, cap, "%.1fG", x / 1e9);
    else if (x >= 1e6) snprintf(buf, cap, "%.1fM", x / 1e6);
    else if (x >= 1e3) snprintf(buf, cap, "%.1fK", x / 1e3);
    else snprintf(buf, cap, "%.0f", x);
}

static void format_status(viewer *v)
{
    const oit_render_method *m = v->methods[v->current];
    char frags[16], bytes[16];
    human((double)v->st.fragments, frags, sizeof frags);
    int n = snprintf(v->status, sizeof v->status, "%d:%s %.*fms %s frag %u lay ovf %llu%s",
                     v->current + 1, m->name, v->st.ms < 100.0 ? 1 : 0, v->st.ms, frags,
                     v->st.max_layers, (unsigned long long)v->st.overflow_pixels,
                     v->show_layers && m->has_counts ? " heat" : "");
    if (m->stream_stats && n > 0 && (size_t)n < sizeof v->status) {
        const oit_stream_frame_stats *ss = m->stream_stats(v->state);
        human((double)ss->bytes_uploaded, bytes, sizeof bytes);
        int k = snprintf(v->status + n, sizeof v->status - (size_t)n,
                         " %u packs %llu draws %sB up %llu hit", ss->packs,
                         (unsigned long long)ss->draw_calls, bytes,
                         (unsigned long long)ss->cache_hits);
        if (k > 0 && ss->epsilon > 0.0f && (size_t)(n + k) < sizeof v->status)
            snprintf(v->status + n + k, sizeof v->status - (size_t)(n + k), " eps %.3g skip %llu",
                     ss->epsilon, (unsigned long long)ss->parts_skipped);
    }
}

static oit_status resize_buffers(viewer *v, int w, int h, oit_error *err)
{
    if (w == v->view.width && h == v->view.height && v->counts)
        return OIT_OK;
    free(v->counts);
    v->counts = calloc((size_t)w * (size_t)h, sizeof *v->counts);
    if (!v->counts)
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot allocate %dx%d layer counts", w, h);
    v->view.width = w;
    v->view.height = h;
    return OIT_OK;
}

/* Renders the current view into v->shown: the colour image, or the heat
 * map where asked for and the method counts layers. */
static oit_status render_frame(viewer *v, oit_error *err)
{
    const oit_render_method *m = v->methods[v->current];
    int heat = v->show_layers && m->has_counts;
    fit_clip(v);
    oit_image_free(&v->frame);
    memset(&v->st, 0, sizeof v->st);
    oit_status s = m->render(v->state, &v->view, &v->frame, heat ? v->counts : NULL, NULL, &v->st,
                             err);
    oit_image_free(&v->shown);
    if (s == OIT_OK && heat)
        return oit_image_heatmap(v->counts, v->frame.width, v->frame.height, &v->shown, err);
    if (s == OIT_OK) {
        v->shown = v->frame;
        memset(&v->frame, 0, sizeof v->frame);
    }
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
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot allocate a %dx%d screenshot", w, h);
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

static oit_status present(viewer *v, int fb_w, int fb_h, int want_shot, oit_error *err)
{
    upload_texture(v, &v->shown);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, v->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST); /* the blit is clipped by it */
    glViewport(0, 0, fb_w, fb_h);
    glBlitFramebuffer(0, 0, v->shown.width, v->shown.height, 0, 0, fb_w, fb_h,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    oit_status s = oit_gl_check("viewer: presenting the frame", err);
    if (s == OIT_OK && want_shot)
        s = read_back(v, fb_w, fb_h, err);
    glfwSwapBuffers(v->win);
    return s;
}

static oit_status one_frame(viewer *v, int want_shot, oit_error *err)
{
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(v->win, &fb_w, &fb_h);
    if (fb_w <= 0 || fb_h <= 0)
        return OIT_OK; /* minimised: nothing to draw into */
    oit_status s = resize_buffers(v, fb_w, fb_h, err);
    if (s == OIT_OK)
        s = render_frame(v, err);
    if (s != OIT_OK)
        return s;
    format_status(v);
    if (v->desc->overlay)
        oit_text_status_line(&v->shown, v->status, v->shown.height >= 480 ? 2 : 1);
    glfwSetWindowTitle(v->win, v->status);
    s = present(v, fb_w, fb_h, want_shot, err);
    if (s == OIT_OK)
        v->frames++;
    return s;
}

/* ---- the loop ---- */

static oit_status open_viewer(viewer *v, oit_error *err)
{
    const oit_viewer_desc *d = v->desc;
    for (int k = 0; k < 3; k++) {
        v->centre[k] = 0.5f * (d->mesh->info.bounds_min[k] + d->mesh->info.bounds_max[k]);
        float half = 0.5f * (d->mesh->info.bounds_max[k] - d->mesh->info.bounds_min[k]);
        v->radius += half * half;
    }
    v->radius = v->radius > 0.0f && isfinite(v->radius) ? sqrtf(v->radius) : 1.0f;
    v->view.camera = d->camera;
    v->view.shading = d->shading;
    v->show_layers = d->show_layers;
    list_methods(v);
    int first = -1;
    for (int i = 0; i < v->method_count; i++)
        if (!strcmp(v->methods[i]->name, d->method))
            first = i;
    if (first < 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window: method %s cannot render this input",
                             d->method);
    oit_gl_desc gd = {.window = 1, .width = d->width, .height = d->height, .title = "oitstream"};
    oit_status s = oit_gl_create(&gd, &v->gl, err);
    if (s != OIT_OK)
        return s;
    v->win = oit_gl_window(v->gl);
    glfwSetWindowUserPointer(v->win, v);
    glfwSetKeyCallback(v->win, on_key);
    glfwSetMouseButtonCallback(v->win, on_button);
    glfwSetCursorPosCallback(v->win, on_cursor);
    glfwSetScrollCallback(v->win, on_scroll);
    glfwGetCursorPos(v->win, &v->mouse_x, &v->mouse_y);
    for (int i = 0; i < v->method_count; i++)
        if (i < KEYED_METHODS)
            printf("viewer: key %d: %s\n", i + 1, v->methods[i]->name);
        else
            printf("viewer: no key: %s (start it with --method)\n", v->methods[i]->name);
    return switch_method(v, first, err);
}

static void close_viewer(viewer *v)
{
    if (v->state)
        v->methods[v->current]->close(v->state);
    if (v->gl) {
        glDeleteFramebuffers(1, &v->fbo);
        glDeleteTextures(1, &v->tex);
    }
    oit_gl_destroy(v->gl);
    free(v->counts);
    oit_image_free(&v->frame);
    oit_image_free(&v->shown);
    oit_image_free(&v->shot);
}

static int frame_limit(const oit_viewer_desc *d)
{
    if (d->frames > 0)
        return d->frames;
    if (d->script)
        return (int)strlen(d->script);
    return d->screenshot ? 1 : 0;
}

oit_status oit_viewer_run(const oit_viewer_desc *desc, oit_error *err)
{
    viewer v;
    memset(&v, 0, sizeof v);
    v.desc = desc;
    v.epsilon = desc->options.epsilon;
    oit_status s = open_viewer(&v, err);
    int limit = frame_limit(desc);
    size_t script_len = desc->script ? strlen(desc->script) : 0;
    for (int i = 0; s == OIT_OK && (limit == 0 || i < limit); i++) {
        glfwPollEvents();
        if ((size_t)i < script_len)
            push_key(&v, desc->script[i]);
        for (int k = 0; k < v.key_count && !v.quit; k++)
            handle_key(&v, v.keys[k]);
        v.key_count = 0;
        if (v.quit || glfwWindowShouldClose(v.win))
            break;
        s = one_frame(&v, desc->screenshot || v.save_pending, err);
        if (s == OIT_OK && v.save_pending && v.shot.rgba)
            save_screenshot(&v);
    }
    if (s == OIT_OK)
        printf("viewer: %d frames; last: %s\n", v.frames, v.frames ? v.status : "none");
    if (s == OIT_OK && desc->screenshot && !v.shot.rgba)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "--window-screenshot %s: no frame was shown",
                          desc->screenshot);
    if (s == OIT_OK && desc->screenshot && (s = oit_image_write_png(&v.shot, desc->screenshot, err)) == OIT_OK)
        printf("viewer: screenshot %s\n", desc->screenshot);
    close_viewer(&v);
    return s;
}
