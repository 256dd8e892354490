/* The interactive loop of viewer.h. Methods render into an oit_image in the
 * window's context; the last rendered image (upscaled when it is a preview)
 * gets the overlays (status line, help, messages, the open prompt) and is
 * uploaded to a texture and blitted to the default framebuffer. The loop
 * renders only when the view or a setting changed, and otherwise blocks in
 * glfwWaitEvents (X events), with a timeout when a preview is waiting for
 * its exact frame or a message for its expiry. */
#include "tools/oitstream/viewer.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/vec.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_util.h"
#include "render/gl/gl_window.h"
#include "render/gl/gpu_timer.h"
#include "render/image/image.h"
#include "tools/common/paths.h"
#include "tools/oitstream/stats_json.h"
#include "tools/oitstream/viewer_clip.h"
#include "plot/text_overlay.h"
#include "stream/stream_method.h"

#define GLFW_INCLUDE_NONE /* GL comes from gl_util.h (core profile prototypes) */
#include <GLFW/glfw3.h>

/* Keys 1..9, 0 reach the first KEYED_METHODS of the table; M/N cycle all. */
enum { MAX_METHODS = 16, KEYED_METHODS = 10, KEY_QUEUE = 64, KEY_ESC = 27 };
enum { SHOWN_NONE = 0, SHOWN_EXACT = 1, SHOWN_PREVIEW = 2 };
enum { DEFAULT_STILL_MS = 200, PREVIEW_MAX_SCALE = 4 };
/* auto: preview when an exact frame takes longer than this (25 fps) */
#define AUTO_PREVIEW_MS 40.0
#define MESSAGE_SECONDS 5.0

typedef struct viewer {
    const oit_viewer_desc *desc;
    oit_method_options options; /* desc's, with the current scene's part file and K */
    oit_stream_options stream;  /* options.stream points here */
    oit_gl *gl;
    GLFWwindow *win;
    const oit_method *methods[MAX_METHODS]; /* the whole table, in its order */
    int method_count, current;
    oit_method_state *state;
    const oit_method *pv_method; /* wboit/unsorted preview, opened when first needed */
    oit_method_state *pv_state;
    /* the scene shown: the caller's, or one O opened (owned) */
    const oit_mesh *mesh;
    oit_partfile *pf;
    oit_viewer_scene owned;
    int have_owned;
    char model_name[512];
    oit_view view;
    oit_camera home; /* R's */
    oit_viewer_clip clip; /* section planes: X, [ and ] (viewer_clip.h) */
    int up_axis;
    float centre[3], radius; /* bounding sphere, for the clip planes */
    int show_layers, quit, drag;
    double mouse_x, mouse_y;
    char keys[KEY_QUEUE];
    int key_count;
    uint32_t *counts;
    size_t counts_cap;
    oit_image frame, base, shown, shot;
    GLuint tex, fbo;
    int tex_w, tex_h;
    oit_frame_stats st;
    /* The newest GPU time polled from gpu_state (a frame or two behind the
     * one shown: timer queries are read without waiting); frame 0: none. */
    oit_gpu_times gpu;
    const oit_method_state *gpu_state;
    const char *gpu_absent;
    int frames, exact_frames, preview_frames, presents, screenshots;
    int save_pending; /* P: save the next presented image */
    float epsilon;    /* early termination the methods open with (E toggles) */
    /* what needs doing: moved (camera: preview), changed (exact now),
     * recompose (overlays only: no rendering) */
    int moved, changed, recompose;
    double last_move;
    int shown_kind, shown_scale; /* what the image is; its preview's scale */
    int preview_scale;
    double preview_ms_at[PREVIEW_MAX_SCALE + 2]; /* the last preview's ms at each scale */
    double last_exact_wall_ms, last_preview_wall_ms, last_wall_ms;
    double last_present_ms; /* overlays, upload, blit and swap of the last image shown */
    int help;
    int entering, skip_char, open_pending;
    char entry[512];
    size_t entry_len;
    char message[400];
    double message_until;
    int status_rows;
    char status[512]; /* the fields on one line: the title and the summary */
} viewer;

static const float kWhite[3] = {1.0f, 1.0f, 1.0f}, kPanel[3] = {0.08f, 0.08f, 0.12f},
                   kAmber[3] = {1.0f, 0.8f, 0.3f}, kGrey[3] = {0.6f, 0.6f, 0.6f};

/* ---- camera ---- */

/* Rotates v by angle (radians) about the unit axis (Rodrigues). */
static void rotate3(float v[3], const float axis[3], float angle)
{
    float c = cosf(angle), s = sinf(angle), kxv[3];
    float kdv = oit_dot3f(axis, v);
    oit_cross3f(axis, v, kxv);
    for (int k = 0; k < 3; k++)
        v[k] = v[k] * c + kxv[k] * s + axis[k] * kdv * (1.0f - c);
}

/* Clip planes around the bounding sphere as seen from the current eye, so
 * that orbiting, zooming and flying never cut the model. */
static void fit_clip(viewer *v)
{
    oit_camera *c = &v->view.camera;
    float f[3], to_c[3];
    oit_sub3f(c->target, c->eye, f);
    oit_normalize3f(f);
    oit_sub3f(v->centre, c->eye, to_c);
    float dc = oit_dot3f(f, to_c);
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
    oit_sub3f(c->eye, c->target, off);
    oit_normalize3f(up);
    rotate3(off, up, (float)(-dx * 0.01));
    oit_cross3f(off, up, right);
    if (oit_normalize3f(right) > 0.0f) {
        float before[3] = {off[0], off[1], off[2]};
        rotate3(off, right, (float)(dy * 0.01));
        float cosu = oit_dot3f(off, up) / sqrtf(oit_dot3f(off, off));
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
    oit_sub3f(c->target, c->eye, f);
    float step = 0.05f * oit_normalize3f(f);
    oit_normalize3f(u);
    oit_cross3f(f, u, r);
    oit_normalize3f(r);
    for (int k = 0; k < 3; k++) {
        float d = step * ((float)forward * f[k] + (float)right * r[k] + (float)up_dir * u[k]);
        c->eye[k] += d;
        c->target[k] += d;
    }
}

/* ---- messages ---- */

/* A note on screen (and on stdout) for MESSAGE_SECONDS: why a key did
 * nothing, why a method cannot run, what was opened. */
static void say(viewer *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(viewer *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->message, sizeof v->message, fmt, ap);
    va_end(ap);
    printf("viewer: %s\n", v->message);
    fflush(stdout);
    v->message_until = glfwGetTime() + MESSAGE_SECONDS;
    v->recompose = 1;
}

/* ---- input ---- */

static void push_key(viewer *v, char key)
{
    if (v->key_count < KEY_QUEUE)
        v->keys[v->key_count++] = key;
}

static void moved(viewer *v)
{
    v->moved = 1;
    v->last_move = glfwGetTime();
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    if (action == GLFW_RELEASE)
        return;
    if (v->entering) { /* the open prompt: characters come from on_char */
        if (key == GLFW_KEY_ESCAPE) {
            v->entering = 0;
            v->recompose = 1;
        } else if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) {
            v->entering = 0;
            v->open_pending = 1;
        } else if (key == GLFW_KEY_BACKSPACE && v->entry_len > 0) {
            v->entry[--v->entry_len] = '\0';
            v->recompose = 1;
        }
        return;
    }
    if (key == GLFW_KEY_O && action == GLFW_PRESS) {
        /* at once, so that what is typed next lands in the prompt */
        v->entering = 1;
        v->skip_char = 1; /* the 'o' of this key press */
        v->entry_len = 0;
        v->entry[0] = '\0';
        v->recompose = 1;
        return;
    }
    if ((key >= GLFW_KEY_A && key <= GLFW_KEY_Z) || (key >= GLFW_KEY_0 && key <= GLFW_KEY_9))
        push_key(v, (char)key); /* GLFW's codes for these are their ASCII capitals/digits */
    else if (key == GLFW_KEY_SPACE)
        push_key(v, ' ');
    else if (key == GLFW_KEY_LEFT_BRACKET || key == GLFW_KEY_RIGHT_BRACKET)
        push_key(v, (char)key); /* '[' and ']' in ASCII */
    else if (key == GLFW_KEY_ESCAPE)
        push_key(v, KEY_ESC);
}

static void on_char(GLFWwindow *w, unsigned int codepoint)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (v->skip_char) {
        v->skip_char = 0;
        return;
    }
    if (v->entering) {
        if (codepoint >= 32 && codepoint < 127 && v->entry_len + 1 < sizeof v->entry) {
            v->entry[v->entry_len++] = (char)codepoint;
            v->entry[v->entry_len] = '\0';
            v->recompose = 1;
        }
    } else if (codepoint == '?') {
        push_key(v, '?');
    }
}

static void on_drop(GLFWwindow *w, int count, const char **paths)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (count < 1)
        return;
    snprintf(v->entry, sizeof v->entry, "%s", paths[0]);
    v->entry_len = strlen(v->entry);
    v->entering = 0;
    v->open_pending = 1;
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
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
    if (v->drag == 1 && (x != v->mouse_x || y != v->mouse_y)) {
        orbit(v, x - v->mouse_x, y - v->mouse_y);
        moved(v);
    } else if (v->drag == 2 && y != v->mouse_y) {
        zoom(v, exp((y - v->mouse_y) * 0.01));
        moved(v);
    }
    v->mouse_x = x;
    v->mouse_y = y;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    viewer *v = glfwGetWindowUserPointer(w);
    zoom(v, pow(0.9, dy));
    moved(v);
}

static void on_refresh(GLFWwindow *w)
{
    ((viewer *)glfwGetWindowUserPointer(w))->recompose = 1; /* exposed: show it again */
}

static void on_resize(GLFWwindow *w, int width, int height)
{
    (void)width;
    (void)height;
    moved(glfwGetWindowUserPointer(w)); /* a preview at the new size, then exact */
}

/* ---- methods ---- */

/* The whole table, in its order, so that a key means one method for every
 * input; what this input cannot use is refused with its reason. */
static void list_methods(viewer *v)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_method_names(names, sizeof names);
    for (char *tok = strtok(names, "|"); tok && v->method_count < MAX_METHODS;
         tok = strtok(NULL, "|")) {
        const oit_method *m = oit_method_find(tok);
        if (m)
            v->methods[v->method_count++] = m;
    }
}

/* Why this input cannot use m, or NULL when it can. */
static const char *unavailable(const viewer *v, const oit_method *m)
{
    if ((m->flags & OIT_METHOD_PARTFILE) && !v->pf)
        return "needs a part file (.oitp): convert the model with oitprep, then open "
               "the .oitp with O";
    if (!(m->flags & OIT_METHOD_PARTFILE) && v->mesh->count == 0)
        return "renders triangles in core, and this input has none";
    return NULL;
}

static void key_label(int i, char *buf, size_t cap)
{
    if (i < KEYED_METHODS)
        snprintf(buf, cap, "%d", (i + 1) % 10);
    else
        snprintf(buf, cap, "M/N");
}

static void close_preview_method(viewer *v)
{
    if (v->pv_state)
        oit_method_close(v->pv_state);
    v->pv_state = NULL;
    v->pv_method = NULL;
    v->gpu_state = NULL;
}

/* Opens method i in the window's context; on failure the current one stays. */
static oit_status switch_method(viewer *v, int i, oit_error *err)
{
    const char *why = unavailable(v, v->methods[i]);
    if (why)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s", why);
    oit_method_options opt = v->options;
    opt.gl = v->gl;
    opt.epsilon = v->epsilon;
    oit_method_state *st = NULL;
    oit_status s = oit_method_open(v->methods[i], v->mesh, &opt, &st, err);
    if (s != OIT_OK)
        return s;
    if (v->state)
        oit_method_close(v->state);
    v->state = st;
    v->gpu_state = NULL; /* a new state may take the old one's address */
    v->current = i;
    v->last_exact_wall_ms = 0.0; /* the new method's speed is not known yet */
    v->preview_scale = 0;
    memset(v->preview_ms_at, 0, sizeof v->preview_ms_at);
    v->changed = 1;
    char key[8];
    key_label(i, key, sizeof key);
    printf("viewer: method %s: %s (%s)\n", key, v->methods[i]->name, oit_method_renderer(st));
    fflush(stdout);
    return OIT_OK;
}

static void key_method(viewer *v, int i)
{
    oit_error err = {0};
    char key[8];
    key_label(i, key, sizeof key);
    if (i >= v->method_count)
        say(v, "no method on key %s (there are %d)", key, v->method_count);
    else if (i != v->current && switch_method(v, i, &err) != OIT_OK)
        say(v, "%s %s cannot run %s: %s", key, v->methods[i]->name,
            err.status == OIT_ERR_UNSUPPORTED && unavailable(v, v->methods[i]) ? "on this input"
                                                                                : "here",
            err.message);
}

/* M (dir 1) and N (dir -1): the next method that opens, saying why the
 * ones passed over could not. */
static void cycle_method(viewer *v, int dir)
{
    for (int step = 1; step < v->method_count; step++) {
        int i = ((v->current + dir * step) % v->method_count + v->method_count) % v->method_count;
        oit_error err = {0};
        if (unavailable(v, v->methods[i]))
            continue;
        if (switch_method(v, i, &err) == OIT_OK)
            return;
        say(v, "%s cannot run here: %s", v->methods[i]->name, err.message);
    }
}

/* P: the next oitstream_NNN.png that does not exist yet, so that no run
 * of the viewer replaces an earlier one's screenshot. */
static void save_screenshot(viewer *v)
{
    char path[64];
    oit_error err = {0};
    v->save_pending = 0;
    if (oit_output_reserve_numbered("oitstream", "png", &v->screenshots, path, sizeof path,
                                    &err) != OIT_OK) {
        say(v, "screenshot: %s", err.message);
        return;
    }
    if (oit_image_write_png(&v->shot, path, &err) != OIT_OK) {
        remove(path);
        say(v, "screenshot: %s", err.message);
    } else {
        printf("viewer: screenshot %s\n", path);
    }
    fflush(stdout);
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
        say(v, "early termination: %s", err.message);
    } else if (v->epsilon > 0.0f && !v->methods[v->current]->stream_stats) {
        say(v, "early termination on, epsilon %g (used by the stream method only)", v->epsilon);
    } else if (v->epsilon > 0.0f) {
        printf("viewer: early termination on, epsilon %g\n", v->epsilon);
    } else {
        printf("viewer: early termination off (exact)\n");
    }
    fflush(stdout);
}

static void toggle_shading(viewer *v)
{
    oit_shading *s = &v->view.shading;
    s->mode = s->mode == OIT_SHADING_TRANSPARENT ? OIT_SHADING_TRANSLUCENT
                                                 : OIT_SHADING_TRANSPARENT;
    oit_shading_resolve_defaults(s);
    printf("viewer: shading %s\n", s->mode == OIT_SHADING_TRANSPARENT ? "transparent" : "translucent");
    v->changed = 1;
}

static const char axis_name[3] = {'x', 'y', 'z'};

/* The bounding sphere and the framing of the current scene. */
static void fit_scene(viewer *v)
{
    const oit_mesh_info *info = &v->mesh->info;
    v->radius = 0.0f;
    for (int k = 0; k < 3; k++) {
        v->centre[k] = 0.5f * (info->bounds_min[k] + info->bounds_max[k]);
        float half = 0.5f * (info->bounds_max[k] - info->bounds_min[k]);
        v->radius += half * half;
    }
    v->radius = v->radius > 0.0f && isfinite(v->radius) ? sqrtf(v->radius) : 1.0f;
}

static void default_camera(viewer *v)
{
    oit_camera_default_up(&v->home, v->mesh->info.bounds_min, v->mesh->info.bounds_max,
                          v->desc->azimuth, v->desc->elevation, v->up_axis);
    v->view.camera = v->home;
}

/* U: y -> z -> x -> y, framing the model anew. */
static void cycle_up(viewer *v)
{
    v->up_axis = v->up_axis == 1 ? 2 : v->up_axis == 2 ? 0 : 1;
    default_camera(v);
    printf("viewer: up axis %c\n", axis_name[v->up_axis]);
    v->changed = 1;
}

/* O / a dropped file: the model in v->entry replaces the one shown. */
static void open_entry(viewer *v)
{
    v->open_pending = 0;
    v->recompose = 1;
    if (!v->entry[0])
        return;
    if (!v->desc->open_model) {
        say(v, "cannot open %s: this viewer was started without a loader", v->entry);
        return;
    }
    oit_viewer_scene scene;
    memset(&scene, 0, sizeof scene);
    oit_error err = {0};
    printf("viewer: opening %s\n", v->entry);
    fflush(stdout);
    if (v->desc->open_model(v->desc->model_ctx, v->entry, &scene, &err) != OIT_OK) {
        say(v, "cannot open %s: %s", v->entry, err.message);
        return;
    }
    /* Methods go before the triangles and the file they read. */
    close_preview_method(v);
    if (v->state)
        oit_method_close(v->state);
    v->state = NULL;
    if (v->have_owned)
        v->desc->close_model(v->desc->model_ctx, &v->owned);
    v->owned = scene;
    v->have_owned = 1;
    v->mesh = &v->owned.mesh;
    v->pf = v->owned.partfile;
    v->stream.partfile = v->pf;
    if (scene.max_layers > 0)
        v->options.max_layers = scene.max_layers;
    snprintf(v->model_name, sizeof v->model_name, "%s", v->entry);
    fit_scene(v);
    v->view.shading.attributes = v->mesh->info.attributes;
    v->view.shading.scene_scale = oit_scene_scale(v->mesh->info.bounds_min, v->mesh->info.bounds_max);
    default_camera(v);
    /* The default method of the file's kind, as on the command line. */
    const char *want = v->pf ? "stream" : "dfb";
    int first = 0;
    for (int i = 0; i < v->method_count; i++)
        if (!strcmp(v->methods[i]->name, want))
            first = i;
    if (switch_method(v, first, &err) != OIT_OK) {
        say(v, "opened %s, but %s cannot run here: %s", v->entry, want, err.message);
        v->quit = 1; /* no method left to show it with */
        return;
    }
    say(v, "opened %s: %llu triangles%s, method %s", v->entry,
        (unsigned long long)v->mesh->info.triangles, v->pf ? " (part file)" : "",
        v->methods[v->current]->name);
}

static void handle_key(viewer *v, char key)
{
    switch (key) {
    case KEY_ESC: case 'Q': v->quit = 1; break;
    case 'W': fly(v, 1, 0, 0); moved(v); break;
    case 'S': fly(v, -1, 0, 0); moved(v); break;
    case 'D': fly(v, 0, 1, 0); moved(v); break;
    case 'A': fly(v, 0, -1, 0); moved(v); break;
    case ' ': fly(v, 0, 0, 1); moved(v); break;
    case 'C': fly(v, 0, 0, -1); moved(v); break;
    case 'R': v->view.camera = v->home; v->changed = 1; break;
    case 'T': toggle_shading(v); break;
    case 'U': cycle_up(v); break;
    case 'P': v->save_pending = 1; v->recompose = 1; break;
    case 'M': cycle_method(v, 1); break;
    case 'N': cycle_method(v, -1); break;
    case 'H': case '?': v->help = !v->help; v->recompose = 1; break;
    case 'O': /* from a script; the window's own O key opens the prompt at once */
        v->entering = 1;
        v->entry_len = 0;
        v->entry[0] = '\0';
        v->recompose = 1;
        break;
    case 'L':
        v->show_layers = !v->show_layers;
        v->changed = 1;
        if (v->show_layers && !(v->methods[v->current]->flags & OIT_METHOD_COUNTS))
            say(v, "layer heat map: %s counts no layers per pixel (1 dfb and 2 reference do)",
                v->methods[v->current]->name);
        else
            printf("viewer: layer heat map %s\n", v->show_layers ? "on" : "off");
        break;
    case 'E':
        toggle_epsilon(v);
        break;
    default: {
        char note[200];
        int plane = oit_viewer_clip_key(&v->clip, key, &v->view.camera, v->centre, v->radius,
                                        v->mesh->info.origin, note, sizeof note);
        if (plane > 0) { /* the status line counts the planes; the plane goes to stdout */
            v->view.clip = oit_viewer_clip_shown(&v->clip);
            v->changed = 1;
            printf("viewer: %s\n", note);
        } else if (plane < 0) {
            say(v, "%s", note);
        } else if (key >= '0' && key <= '9')
            key_method(v, key == '0' ? 9 : key - '1');
        else
            say(v, "key %c does nothing (H lists the keys)", key);
    }
    }
}

/* ---- status ---- */

static void human(double x, char *buf, size_t cap)
{
    if (x >= 1e9) snprintf(buf, cap, "%.1fG", x / 1e9);
    else if (x >= 1e6) snprintf(buf, cap, "%.1fM", x / 1e6);
    else if (x >= 1e3) snprintf(buf, cap, "%.1fK", x / 1e3);
    else snprintf(buf, cap, "%.0f", x);
}

enum { MAX_FIELDS = 20, FIELD_LEN = 48 };

typedef struct fields {
    char text[MAX_FIELDS][FIELD_LEN];
    int n;
} fields;

static void field(fields *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void field(fields *f, const char *fmt, ...)
{
    if (f->n >= MAX_FIELDS)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(f->text[f->n++], FIELD_LEN, fmt, ap);
    va_end(ap);
}

/* The named figures of the last rendered frame. */
static void status_fields(viewer *v, fields *f)
{
    const oit_method *m = v->methods[v->current];
    char key[8], num[16];
    key_label(v->current, key, sizeof key);
    f->n = 0;
    if (v->current < KEYED_METHODS)
        field(f, "%s %s", key, m->name);
    else
        field(f, "%s", m->name);
    if (v->shown_kind == SHOWN_PREVIEW && v->shown_scale > 1)
        field(f, "preview 1/%d res", v->shown_scale);
    else if (v->shown_kind == SHOWN_PREVIEW)
        field(f, "preview %s", v->pv_method ? v->pv_method->name : m->name);
    else
        field(f, "exact");
    field(f, "frame %.*f ms", v->st.ms < 100.0 ? 1 : 0, v->st.ms);
    if (v->gpu_absent)
        field(f, "gpu n/a");
    else if (v->gpu.frame)
        field(f, "gpu %.*f ms", v->gpu.ms < 100.0 ? 1 : 0, v->gpu.ms);
    human((double)v->st.fragments, num, sizeof num);
    field(f, "fragments %s", num);
    if (!(v->shown_kind == SHOWN_PREVIEW && v->pv_method)) { /* wboit, unsorted count no layers */
        field(f, "layers %u", v->st.max_layers);
        field(f, "overflow %llu", (unsigned long long)v->st.overflow_pixels);
    }
    if (m->stream_stats && v->state && !(v->shown_kind == SHOWN_PREVIEW && v->pv_method)) {
        const oit_stream_frame_stats *ss = oit_method_stream_stats(v->state);
        field(f, "packs %u", ss->packs);
        /* which K-slot fill ran (--capture): "slots stencil x8", "slots array" */
        if (v->st.capture_slots && v->st.capture_slots_k)
            field(f, "slots %s x%u", v->st.capture_slots, v->st.capture_slots_k);
        else if (v->st.capture_slots)
            field(f, "slots %s", v->st.capture_slots);
        field(f, "draws %llu", (unsigned long long)ss->draw_calls);
        double up = (double)ss->bytes_uploaded;
        if (up >= 1e3) {
            human(up, num, sizeof num); /* "2.3K": 2.3 KB */
            field(f, "uploaded %.*s %cB", (int)strlen(num) - 1, num, num[strlen(num) - 1]);
        } else {
            field(f, "uploaded %.0f B", up);
        }
        field(f, "cache hits %llu", (unsigned long long)ss->cache_hits);
        if (ss->epsilon > 0.0f) {
            field(f, "eps %.3g", ss->epsilon);
            field(f, "skipped %llu", (unsigned long long)ss->parts_skipped);
        }
    }
    if (v->show_layers && (m->flags & OIT_METHOD_COUNTS))
        field(f, "heat map");
    if (v->view.clip.count > 0)
        field(f, "section planes %d", v->view.clip.count);
    field(f, "%c up", axis_name[v->up_axis]);
    field(f, "H help");
    size_t used = 0;
    v->status[0] = '\0';
    for (int i = 0; i < f->n && used + 1 < sizeof v->status; i++)
        used += (size_t)snprintf(v->status + used, sizeof v->status - used, "%s%s",
                                 i ? "  " : "", f->text[i]);
}

/* ---- overlays ---- */

enum { MAX_PANEL_LINES = 40, PANEL_LINE = 160 };

typedef struct panel {
    char line[MAX_PANEL_LINES][PANEL_LINE];
    const float *colour[MAX_PANEL_LINES];
    int n;
} panel;

static void panel_add(panel *p, const float *colour, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void panel_add(panel *p, const float *colour, const char *fmt, ...)
{
    if (p->n >= MAX_PANEL_LINES)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->line[p->n], PANEL_LINE, fmt, ap);
    va_end(ap);
    p->colour[p->n++] = colour;
}

/* text broken at spaces into lines of at most width characters */
static void panel_wrap(panel *p, const float *colour, const char *text, int width)
{
    if (width < 8)
        width = 8;
    while (*text && p->n < MAX_PANEL_LINES) {
        int len = (int)strlen(text), cut = len;
        if (len > width) {
            cut = width;
            while (cut > 0 && text[cut] != ' ')
                cut--;
            if (cut == 0)
                cut = width;
        }
        panel_add(p, colour, "%.*s", cut, text);
        text += cut;
        while (*text == ' ')
            text++;
    }
}

static int overlay_scale(const oit_image *img)
{
    return img->height >= 480 && img->width >= 640 ? 2 : 1;
}

/* Draws the panel's lines on a dark box at (x, y); bottom: y is its lower edge. */
static void panel_draw(oit_image *img, const panel *p, int x, int y, int bottom)
{
    int scale = overlay_scale(img), line_h = oit_text_line_height(scale), w = 0;
    for (int i = 0; i < p->n; i++) {
        int tw = oit_text_width(p->line[i], scale);
        w = tw > w ? tw : w;
    }
    int pad = 3 * scale, h = p->n * line_h + 2 * pad;
    if (bottom)
        y -= h;
    oit_text_box(img, x, y, w + 2 * pad, h, kPanel);
    for (int i = 0; i < p->n; i++)
        oit_text_draw(img, x + pad, y + pad + i * line_h + 2 * scale, p->line[i], p->colour[i],
                      scale);
}

static void help_panel(const viewer *v, panel *p)
{
    p->n = 0;
    panel_add(p, kAmber, "oitstream viewer: keys (H or ? closes this)");
    panel_add(p, kWhite, "left drag       orbit");
    panel_add(p, kWhite, "right drag, wheel  zoom");
    panel_add(p, kWhite, "W A S D         fly forward, left, back, right");
    panel_add(p, kWhite, "Space, C        fly up, down");
    panel_add(p, kWhite, "1..9, 0         method (same key for every input):");
    int keyed = v->method_count < KEYED_METHODS ? v->method_count : KEYED_METHODS;
    for (int i = 0; i < keyed; i += 4) {
        char line[PANEL_LINE];
        size_t used = 0;
        for (int j = i; j < i + 4 && j < keyed; j++)
            used += (size_t)snprintf(line + used, sizeof line - used, "  %d %s%s%s", (j + 1) % 10,
                                     v->methods[j]->name, unavailable(v, v->methods[j]) ? " (-)" : "",
                                     j == v->current ? " *" : "");
        panel_add(p, kWhite, "   %s", line);
    }
    panel_add(p, kGrey, "                * current, (-) not for this input");
    char more[PANEL_LINE];
    size_t used = 0;
    more[0] = '\0';
    for (int j = keyed; j < v->method_count; j++)
        used += (size_t)snprintf(more + used, sizeof more - used, "%s%s%s", j > keyed ? ", " : "",
                                 v->methods[j]->name, j == v->current ? " *" : "");
    panel_add(p, kWhite, "M, N            next, previous method%s%s%s", used ? " (also " : "",
              more, used ? ")" : "");
    panel_add(p, kWhite, "L               layer heat map (dfb, reference)");
    panel_add(p, kWhite, "T               transparent / translucent");
    panel_add(p, kWhite, "E               early termination (stream)");
    panel_add(p, kWhite, "U               up axis y, z, x (now %c)", axis_name[v->up_axis]);
    panel_add(p, kWhite, "X               section plane: one through the centre facing");
    panel_add(p, kWhite, "                you, or the planes off / on");
    panel_add(p, kWhite, "[, ]            move section plane 1 back, forward");
    panel_add(p, kWhite, "R               reset the camera");
    panel_add(p, kWhite, "O               open a file: type its path, Enter");
    panel_add(p, kWhite, "                (or drop a file on the window)");
    panel_add(p, kWhite, "P               save the next free oitstream_NNN.png");
    panel_add(p, kWhite, "Q, Esc          quit");
    panel_add(p, kGrey, "moving shows a preview; still for %d ms, the exact image",
              v->desc->still_ms > 0 ? v->desc->still_ms : DEFAULT_STILL_MS);
}

/* v->shown: v->base with the status line, the help, the open prompt and
 * the current message drawn over it. */
static oit_status compose(viewer *v, oit_error *err)
{
    if (!v->shown.rgba || v->shown.width != v->base.width || v->shown.height != v->base.height) {
        oit_image_free(&v->shown);
        oit_status s = oit_image_alloc(&v->shown, v->base.width, v->base.height, err);
        if (s != OIT_OK)
            return s;
    }
    memcpy(v->shown.rgba, v->base.rgba,
           (size_t)v->base.width * (size_t)v->base.height * 4 * sizeof(float));
    oit_image *img = &v->shown;
    int scale = overlay_scale(img), chars = (img->width - 12 * scale) / (6 * scale);
    fields f;
    status_fields(v, &f);
    v->status_rows = 0;
    if (v->desc->overlay) {
        const char *ptr[MAX_FIELDS];
        for (int i = 0; i < f.n; i++)
            ptr[i] = f.text[i];
        v->status_rows = oit_text_status_fields(img, ptr, f.n, img->height >= 480 ? 2 : 1);
    }
    panel p;
    if (v->help) {
        help_panel(v, &p);
        panel_draw(img, &p, 4 * scale, v->status_rows + 4 * scale, 0);
    }
    int bottom = img->height - 4 * scale;
    if (v->entering) {
        p.n = 0;
        char line[sizeof v->entry + 16];
        snprintf(line, sizeof line, "open: %s_", v->entry);
        /* the end of a long path, where the typing is */
        size_t len = strlen(line), max = chars > 8 ? (size_t)chars : 8;
        panel_add(&p, kWhite, "%s", len > max ? line + len - max : line);
        panel_add(&p, kGrey, "Enter opens, Esc cancels");
        panel_draw(img, &p, 4 * scale, bottom, 1);
        bottom -= p.n * oit_text_line_height(scale) + 10 * scale;
    }
    if (v->message[0]) {
        p.n = 0;
        panel_wrap(&p, kAmber, v->message, chars);
        panel_draw(img, &p, 4 * scale, bottom, 1);
    }
    return OIT_OK;
}

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
        return oit_error_set(err, OIT_ERR_NOMEM, "viewer: cannot allocate %dx%d layer counts", w, h);
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
    case OIT_PREVIEW_OFF: return 0;
    case OIT_PREVIEW_LOWRES: return 1;
    case OIT_PREVIEW_WBOIT: case OIT_PREVIEW_UNSORTED: return 2;
    default: return v->last_exact_wall_ms > AUTO_PREVIEW_MS ? 1 : 0;
    }
}

static oit_status open_preview_method(viewer *v, oit_error *err)
{
    if (v->pv_state)
        return OIT_OK;
    const oit_method *m = oit_method_find(preview_method_name(v->desc->preview));
    if (!m)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "viewer: no preview method");
    oit_method_options opt = v->options;
    opt.gl = v->gl;
    opt.epsilon = -1.0f;
    oit_status s = oit_method_open(m, v->mesh, &opt, &v->pv_state, err);
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
    ms[f] = ms[f] > 0.0 ? 0.5 * (ms[f] + wall_ms) : wall_ms; /* smoothed: frames vary with the view */
    wall_ms = ms[f];
    if (wall_ms > 45.0 && f < PREVIEW_MAX_SCALE &&
        (f == 2 || ms[f - 1] == 0.0 || ms[f] < 0.75 * ms[f - 1]) &&
        !(ms[f + 1] > 0.0 && ms[f + 1] > 0.85 * ms[f]))
        v->preview_scale = f + 1;
    else if (f > 2 && (wall_ms < 15.0 || (wall_ms > 45.0 && ms[f - 1] > 0.0 &&
                                          ms[f] > 0.85 * ms[f - 1])))
        v->preview_scale = f - 1;
}

/* Renders the current view into v->base at the window's size: exact, or
 * (kind SHOWN_PREVIEW) the preview. */
static oit_status render_frame(viewer *v, int fb_w, int fb_h, int kind, oit_error *err)
{
    const oit_method *m = v->methods[v->current];
    oit_method_state *state = v->state;
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
    int heat = v->show_layers && (m->flags & OIT_METHOD_COUNTS);
    oit_status s = heat ? ensure_counts(v, w, h, err) : OIT_OK;
    if (s != OIT_OK)
        return s;
    v->view.width = w;
    v->view.height = h;
    fit_clip(v);
    double t0 = glfwGetTime();
    oit_image_free(&v->frame);
    memset(&v->st, 0, sizeof v->st);
    s = oit_method_render(state, &v->view, &v->frame, heat ? v->counts : NULL, NULL, &v->st, err);
    if (v->gpu_state != state)
        memset(&v->gpu, 0, sizeof v->gpu);
    v->gpu_state = state;
    v->gpu_absent = oit_method_gpu_absent(state);
    for (oit_gpu_times g; oit_method_gpu_poll(state, &g, 0);)
        v->gpu = g;
    oit_image img = {0};
    if (s == OIT_OK && heat) {
        s = oit_image_heatmap(v->counts, v->frame.width, v->frame.height, &img, err);
    } else if (s == OIT_OK) {
        img = v->frame;
        memset(&v->frame, 0, sizeof v->frame);
    }
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

/* Composes the overlays over the last rendered image and shows it; no
 * rendering. */
static oit_status present(viewer *v, int want_shot, oit_error *err)
{
    if (!v->base.rgba)
        return OIT_OK;
    double t0 = glfwGetTime();
    oit_status s = compose(v, err);
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
    glBlitFramebuffer(0, 0, v->shown.width, v->shown.height, 0, 0, fb_w, fb_h,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    s = oit_gl_check("viewer: presenting the frame", err);
    if (s == OIT_OK && (want_shot || v->save_pending))
        s = read_back(v, fb_w, fb_h, err);
    char title[sizeof v->model_name + sizeof v->status + 16];
    snprintf(title, sizeof title, "oitstream %s: %s", v->model_name, v->status);
    glfwSetWindowTitle(v->win, title);
    glfwSwapBuffers(v->win);
    v->last_present_ms = (glfwGetTime() - t0) * 1000.0;
    v->presents++;
    v->recompose = 0;
    if (s == OIT_OK && v->save_pending && v->shot.rgba)
        save_screenshot(v);
    return s;
}

/* --stats with --window: the counters, rewritten (atomically) after every
 * frame, so that a test or a script can read them while the window runs. */
static void write_stats(viewer *v)
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
    char up[2] = {axis_name[v->up_axis], 0};
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
static oit_status one_frame(viewer *v, int kind, int want_shot, oit_error *err)
{
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(v->win, &fb_w, &fb_h);
    v->moved = 0;
    v->changed = 0;
    if (fb_w <= 0 || fb_h <= 0)
        return OIT_OK; /* minimised: nothing to draw into (restoring it resizes: on_resize) */
    oit_status s = render_frame(v, fb_w, fb_h, kind, err);
    if (s == OIT_OK)
        s = present(v, want_shot, err);
    if (s == OIT_OK)
        write_stats(v);
    return s;
}

/* ---- the loop ---- */

static oit_status open_viewer(viewer *v, oit_error *err)
{
    const oit_viewer_desc *d = v->desc;
    v->options = d->options;
    if (d->options.stream)
        v->stream = *d->options.stream;
    v->options.stream = &v->stream;
    v->mesh = d->mesh;
    v->pf = d->partfile;
    v->up_axis = d->up_axis >= 0 && d->up_axis <= 2 ? d->up_axis : 1;
    snprintf(v->model_name, sizeof v->model_name, "%s", d->model_path ? d->model_path : "");
    fit_scene(v);
    v->view.camera = d->camera;
    v->home = d->camera;
    v->view.shading = d->shading;
    v->clip.planes = d->clip;
    v->view.clip = d->clip;
    v->show_layers = d->show_layers;
    list_methods(v);
    int first = -1;
    for (int i = 0; i < v->method_count; i++)
        if (!strcmp(v->methods[i]->name, d->method))
            first = i;
    if (first < 0 || unavailable(v, v->methods[first]))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window: method %s cannot render this "
                             "input%s%s", d->method, first >= 0 ? ": it " : "",
                             first >= 0 ? unavailable(v, v->methods[first]) : "");
    oit_gl_desc gd = {.width = d->width, .height = d->height, .title = "oitstream"};
    oit_status s = oit_gl_create_window(&gd, &v->gl, err);
    if (s != OIT_OK)
        return s;
    v->win = oit_gl_window(v->gl);
    glfwSetWindowUserPointer(v->win, v);
    glfwSetKeyCallback(v->win, on_key);
    glfwSetCharCallback(v->win, on_char);
    glfwSetDropCallback(v->win, on_drop);
    glfwSetMouseButtonCallback(v->win, on_button);
    glfwSetCursorPosCallback(v->win, on_cursor);
    glfwSetScrollCallback(v->win, on_scroll);
    glfwSetWindowRefreshCallback(v->win, on_refresh);
    glfwSetFramebufferSizeCallback(v->win, on_resize);
    glfwGetCursorPos(v->win, &v->mouse_x, &v->mouse_y);
    for (int i = 0; i < v->method_count; i++) {
        const char *why = unavailable(v, v->methods[i]);
        if (i < KEYED_METHODS)
            printf("viewer: key %d: %s%s%s%s\n", (i + 1) % 10, v->methods[i]->name,
                   why ? " (not for this input: " : "", why ? why : "", why ? ")" : "");
        else
            printf("viewer: no key: %s (M/N cycle to it)\n", v->methods[i]->name);
    }
    return switch_method(v, first, err);
}

static void close_viewer(viewer *v)
{
    close_preview_method(v);
    if (v->state)
        oit_method_close(v->state);
    if (v->gl) {
        glDeleteFramebuffers(1, &v->fbo);
        glDeleteTextures(1, &v->tex);
    }
    oit_gl_destroy(v->gl);
    if (v->have_owned)
        v->desc->close_model(v->desc->model_ctx, &v->owned);
    free(v->counts);
    oit_image_free(&v->frame);
    oit_image_free(&v->base);
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

static void handle_input(viewer *v)
{
    for (int k = 0; k < v->key_count && !v->quit; k++)
        handle_key(v, v->keys[k]);
    v->key_count = 0;
    if (v->open_pending && !v->quit)
        open_entry(v);
}

/* --window-frames / --window-script / --window-screenshot: one exact frame
 * an iteration, a script key before each. */
static oit_status run_bounded(viewer *v, int limit, oit_error *err)
{
    const oit_viewer_desc *desc = v->desc;
    size_t script_len = desc->script ? strlen(desc->script) : 0;
    oit_status s = OIT_OK;
    for (int i = 0; s == OIT_OK && i < limit; i++) {
        glfwPollEvents();
        if ((size_t)i < script_len)
            push_key(v, desc->script[i]);
        handle_input(v);
        if (v->quit || glfwWindowShouldClose(v->win))
            break;
        s = one_frame(v, SHOWN_EXACT, desc->screenshot != NULL, err);
    }
    return s;
}

/* The interactive loop: block until something happens; render a preview
 * while the camera moves, the exact frame once it is still for still_ms
 * (or at once after a discrete change), and only recompose for overlays. */
static oit_status run_interactive(viewer *v, oit_error *err)
{
    double still = (v->desc->still_ms > 0 ? v->desc->still_ms : DEFAULT_STILL_MS) / 1000.0;
    oit_status s = one_frame(v, SHOWN_EXACT, 0, err);
    while (s == OIT_OK && !v->quit && !glfwWindowShouldClose(v->win)) {
        if (!v->moved && !v->changed && !v->recompose && !v->open_pending) {
            double now = glfwGetTime(), wake = INFINITY;
            if (v->shown_kind == SHOWN_PREVIEW)
                wake = v->last_move + still;
            if (v->message_until > 0.0 && v->message_until < wake)
                wake = v->message_until;
            if (isinf(wake))
                glfwWaitEvents();
            else if (wake > now)
                glfwWaitEventsTimeout(wake - now);
        }
        glfwPollEvents(); /* the rest of a burst of motion: one frame for all of it */
        handle_input(v);
        if (v->quit || glfwWindowShouldClose(v->win))
            break;
        double now = glfwGetTime();
        if (v->message_until > 0.0 && now >= v->message_until) {
            v->message[0] = '\0';
            v->message_until = 0.0;
            v->recompose = 1;
        }
        if (v->changed)
            s = one_frame(v, SHOWN_EXACT, 0, err);
        else if (v->moved)
            s = one_frame(v, SHOWN_PREVIEW, 0, err);
        else if (v->shown_kind == SHOWN_PREVIEW && now >= v->last_move + still)
            s = one_frame(v, SHOWN_EXACT, 0, err);
        else if (v->recompose || v->save_pending)
            s = present(v, 0, err);
    }
    return s;
}

oit_status oit_viewer_run(const oit_viewer_desc *desc, oit_error *err)
{
    viewer v;
    memset(&v, 0, sizeof v);
    v.desc = desc;
    v.epsilon = desc->options.epsilon;
    oit_status s = open_viewer(&v, err);
    int limit = frame_limit(desc);
    if (s == OIT_OK)
        s = limit > 0 ? run_bounded(&v, limit, err) : run_interactive(&v, err);
    if (s == OIT_OK) {
        printf("viewer: %d frames rendered (%d exact, %d preview), %d presented; status band %d "
               "rows; last: %s\n", v.frames, v.exact_frames, v.preview_frames, v.presents,
               v.status_rows, v.frames ? v.status : "none");
        write_stats(&v);
    }
    if (s == OIT_OK && desc->screenshot && !v.shot.rgba)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "--window-screenshot %s: no frame was shown",
                          desc->screenshot);
    if (s == OIT_OK && desc->screenshot && (s = oit_image_write_png(&v.shot, desc->screenshot, err)) == OIT_OK)
        printf("viewer: screenshot %s\n", desc->screenshot);
    close_viewer(&v);
    return s;
}
