/* The viewer's input (viewer_internal.h): GLFW's callbacks queue keys and
 * move the camera; keys switch methods, shading, early termination, the
 * up axis, open files and take screenshots. */
#include "tools/oitstream/viewer_internal.h"

/* ---- input ---- */

void viewer_push_key(viewer *v, char key)
{
    if (v->key_count < KEY_QUEUE)
        v->keys[v->key_count++] = key;
}

void viewer_moved(viewer *v)
{
    v->picked = 0; /* its layers were another view's */
    v->moved = 1;
    v->last_move = glfwGetTime();
}

void viewer_on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    if (action == GLFW_RELEASE)
        return;
    if (v->entering) { /* the open prompt: characters come from viewer_on_char */
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
        viewer_push_key(v, (char)key); /* GLFW's codes for these are their ASCII capitals/digits */
    else if (key == GLFW_KEY_SPACE)
        viewer_push_key(v, ' ');
    else if (key == GLFW_KEY_LEFT_BRACKET || key == GLFW_KEY_RIGHT_BRACKET)
        viewer_push_key(v, (char)key); /* '[' and ']' in ASCII */
    else if (key == GLFW_KEY_ESCAPE)
        viewer_push_key(v, KEY_ESC);
}

void viewer_on_char(GLFWwindow *w, unsigned int codepoint)
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
        viewer_push_key(v, '?');
    }
}

void viewer_on_drop(GLFWwindow *w, int count, const char **paths)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (count < 1)
        return;
    snprintf(v->entry, sizeof v->entry, "%s", paths[0]);
    v->entry_len = strlen(v->entry);
    v->entering = 0;
    v->open_pending = 1;
}

void viewer_on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    int which = button == GLFW_MOUSE_BUTTON_LEFT ? 1 : button == GLFW_MOUSE_BUTTON_RIGHT ? 2 : 0;
    if (which == 1 && (action == GLFW_PRESS || action == GLFW_RELEASE))
        viewer_pick_button(v, action == GLFW_PRESS);
    if (action == GLFW_PRESS && which)
        v->drag = which;
    else if (action == GLFW_RELEASE && which == v->drag)
        v->drag = 0;
}

void viewer_on_cursor(GLFWwindow *w, double x, double y)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (v->drag == 1 && (x != v->mouse_x || y != v->mouse_y)) {
        viewer_orbit(v, x - v->mouse_x, y - v->mouse_y);
        viewer_moved(v);
    } else if (v->drag == 2 && y != v->mouse_y) {
        viewer_zoom(v, exp((y - v->mouse_y) * 0.01));
        viewer_moved(v);
    }
    v->mouse_x = x;
    v->mouse_y = y;
}

void viewer_on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    viewer *v = glfwGetWindowUserPointer(w);
    viewer_zoom(v, pow(0.9, dy));
    viewer_moved(v);
}

void viewer_on_refresh(GLFWwindow *w)
{
    ((viewer *)glfwGetWindowUserPointer(w))->recompose = 1; /* exposed: show it again */
}

void viewer_on_resize(GLFWwindow *w, int width, int height)
{
    (void)width;
    (void)height;
    viewer_moved(glfwGetWindowUserPointer(w)); /* a preview at the new size, then exact */
}

/* ---- methods ---- */

/* The whole table, in its order, so that a key means one method for every
 * input; what this input cannot use is refused with its reason. */
void viewer_list_methods(viewer *v)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_method_names(names, sizeof names);
    for (char *tok = strtok(names, "|"); tok && v->method_count < MAX_METHODS;
         tok = strtok(NULL, "|")) {
        const oit_render_method_info *m = oit_method_find(tok);
        if (m)
            v->methods[v->method_count++] = m;
    }
}

/* Why this input cannot use m, or NULL when it can. */
const char *viewer_unavailable(const viewer *v, const oit_render_method_info *m)
{
    if ((m->flags & OIT_RENDER_METHOD_PART_FILE) && !v->pf)
        return "needs a part file (.oitp): convert the model with oitprep, then open "
               "the .oitp with O";
    if (!(m->flags & OIT_RENDER_METHOD_PART_FILE) && v->mesh->count == 0)
        return "renders triangles in core, and this input has none";
    return NULL;
}

void viewer_key_label(int i, char *buf, size_t cap)
{
    if (i < KEYED_METHODS)
        snprintf(buf, cap, "%d", (i + 1) % 10);
    else
        snprintf(buf, cap, "M/N");
}

void viewer_close_preview_method(viewer *v)
{
    if (v->pv_state)
        oit_run_close(v->pv_state);
    v->pv_state = NULL;
    v->pv_method = NULL;
    v->gpu_state = NULL;
}

/* Opens method i in the window's context; on failure the current one stays. */
oit_status viewer_switch_method(viewer *v, int i, oit_error *err)
{
    const char *why = viewer_unavailable(v, v->methods[i]);
    if (why)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s", why);
    oit_run_options opt = v->options;
    opt.gl = v->gl;
    opt.threshold = v->has_epsilon ? &v->epsilon : NULL;
    oit_run *st = NULL;
    oit_status s = oit_run_open(v->methods[i], v->mesh, &opt, &st, err);
    if (s != OIT_OK)
        return s;
    if (v->state)
        oit_run_close(v->state);
    v->state = st;
    v->gpu_state = NULL; /* a new state may take the old one's address */
    v->current = i;
    v->last_exact_wall_ms = 0.0; /* the new method's speed is not known yet */
    v->preview_scale = 0;
    memset(v->preview_ms_at, 0, sizeof v->preview_ms_at);
    v->changed = 1;
    char key[8];
    viewer_key_label(i, key, sizeof key);
    printf("viewer: method %s: %s (%s)\n", key, v->methods[i]->name, oit_run_renderer(st));
    fflush(stdout);
    return OIT_OK;
}

static void key_method(viewer *v, int i)
{
    oit_error err = {0};
    char key[8];
    viewer_key_label(i, key, sizeof key);
    if (i >= v->method_count)
        viewer_say(v, "no method on key %s (there are %d)", key, v->method_count);
    else if (i != v->current && viewer_switch_method(v, i, &err) != OIT_OK)
        viewer_say(v, "%s %s cannot run %s: %s", key, v->methods[i]->name,
                   err.status == OIT_ERR_UNSUPPORTED && viewer_unavailable(v, v->methods[i])
                       ? "on this input"
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
        if (viewer_unavailable(v, v->methods[i]))
            continue;
        if (viewer_switch_method(v, i, &err) == OIT_OK)
            return;
        viewer_say(v, "%s cannot run here: %s", v->methods[i]->name, err.message);
    }
}

/* P: the current view rendered offscreen at --shot-size (the window's size
 * without it) into the next oitstream_NNN.png that does not exist yet, so
 * that no run of the viewer replaces an earlier one's screenshot; stdout
 * names it with its size and the view as --view takes it. */
void viewer_save_screenshot(viewer *v)
{
    int w = v->desc->shot_width, h = v->desc->shot_height;
    if (w <= 0 || h <= 0)
        glfwGetFramebufferSize(v->win, &w, &h);
    char path[64], view[512];
    oit_error err = {0};
    oit_image img = {0};
    oit_status s = viewer_render_shot(v, w, h, &img, &err);
    if (s == OIT_OK)
        s = oit_output_reserve_numbered("oitstream", "png", &v->screenshots, path, sizeof path,
                                        &err);
    if (s == OIT_OK && (s = oit_image_write_png(&img, path, &err)) != OIT_OK)
        remove(path);
    oit_image_free(&img);
    if (s != OIT_OK) {
        viewer_say(v, "screenshot: %s", err.message);
        return;
    }
    oit_stats_format_view(&v->view.camera, v->mesh->info.origin, view, sizeof view);
    printf("viewer: screenshot %s %dx%d --view %s\n", path, w, h, view);
    fflush(stdout);
}

/* G: the window's next image as shown (overlays, a preview) into the next
 * free oitstream_NNN.png, as P names its. */
void viewer_save_window(viewer *v)
{
    char path[64];
    oit_error err = {0};
    v->grab_pending = 0;
    oit_status s = oit_output_reserve_numbered("oitstream", "png", &v->screenshots, path,
                                               sizeof path, &err);
    if (s == OIT_OK && (s = oit_image_write_png(&v->shot, path, &err)) != OIT_OK)
        remove(path);
    if (s != OIT_OK)
        viewer_say(v, "window screenshot: %s", err.message);
    else
        printf("viewer: screenshot %s %dx%d (the window)\n", path, v->shot.width,
               v->shot.height);
    fflush(stdout);
}

/* E: early termination off, or on at --epsilon (1/255 when none was given:
 * an error no 8-bit display shows). Only the streamer uses it; the method
 * is reopened so that it takes effect from the next frame. */
static void toggle_epsilon(viewer *v)
{
    const float *given = v->desc->options.threshold;
    float on = given && *given > 0.0f ? *given : 1.0f / 255.0f;
    float was = v->epsilon;
    int had = v->has_epsilon;
    oit_error err = {0};
    v->epsilon = had && was > 0.0f ? 0.0f : on;
    v->has_epsilon = 1;
    if (viewer_switch_method(v, v->current, &err) != OIT_OK) {
        v->epsilon = was;
        v->has_epsilon = had;
        viewer_say(v, "early termination: %s", err.message);
    } else if (v->epsilon > 0.0f && !(v->methods[v->current]->flags & OIT_RENDER_METHOD_PART_FILE)) {
        viewer_say(v, "early termination on, epsilon %g (used by the stream method only)",
                   v->epsilon);
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
    s->mode =
        s->mode == OIT_SHADING_TRANSPARENT ? OIT_SHADING_TRANSLUCENT : OIT_SHADING_TRANSPARENT;
    oit_shading_resolve_defaults(s);
    printf("viewer: shading %s\n",
           s->mode == OIT_SHADING_TRANSPARENT ? "transparent" : "translucent");
    v->changed = 1;
}


/* L: the fragments-per-pixel heat map of the methods that count them; on
 * one that counts none the image stays and the overlay says so, naming
 * the keys of those that do. */
static void toggle_heat_map(viewer *v)
{
    v->show_layers = !v->show_layers;
    v->changed = 1;
    if (!v->show_layers || (v->methods[v->current]->flags & OIT_RENDER_METHOD_COUNTS)) {
        printf("viewer: layer heat map %s\n", v->show_layers ? "on" : "off");
        return;
    }
    char which[160] = "", key[8];
    size_t used = 0;
    for (int i = 0; i < v->method_count && used < sizeof which; i++) {
        if (!(v->methods[i]->flags & OIT_RENDER_METHOD_COUNTS))
            continue;
        viewer_key_label(i, key, sizeof key);
        used += (size_t)snprintf(which + used, sizeof which - used, "%s%s %s", used ? ", " : "",
                                 key, v->methods[i]->name);
    }
    viewer_say(v, "layer heat map: %s counts no fragments per pixel (%s do)",
               v->methods[v->current]->name, which);
}

/* The bounding sphere and the framing of the current scene. */
void viewer_fit_scene(viewer *v)
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
    printf("viewer: up axis %c\n", viewer_axis_name(v->up_axis));
    v->changed = 1;
}

/* O / a dropped file: the model in v->entry replaces the one shown. */
void viewer_open_entry(viewer *v)
{
    v->open_pending = 0;
    v->recompose = 1;
    if (!v->entry[0])
        return;
    if (!v->desc->open_model) {
        viewer_say(v, "cannot open %s: this viewer was started without a loader", v->entry);
        return;
    }
    oit_viewer_scene scene;
    memset(&scene, 0, sizeof scene);
    oit_error err = {0};
    printf("viewer: opening %s\n", v->entry);
    fflush(stdout);
    if (v->desc->open_model(v->desc->model_ctx, v->entry, &scene, &err) != OIT_OK) {
        viewer_say(v, "cannot open %s: %s", v->entry, err.message);
        return;
    }
    /* Methods go before the triangles and the file they read. */
    viewer_close_preview_method(v);
    if (v->state)
        oit_run_close(v->state);
    v->state = NULL;
    if (v->have_owned)
        v->desc->close_model(v->desc->model_ctx, &v->owned);
    v->owned = scene;
    v->have_owned = 1;
    v->mesh = &v->owned.mesh;
    v->pf = v->owned.partfile;
    snprintf(v->stream_path, sizeof v->stream_path, "%s", v->entry);
    if (scene.max_layers > 0)
        v->options.max_layers = scene.max_layers;
    snprintf(v->model_name, sizeof v->model_name, "%s", v->entry);
    viewer_fit_scene(v);
    v->view.shading.attributes = v->mesh->info.attributes;
    v->view.shading.scene_scale =
        oit_scene_scale(v->mesh->info.bounds_min, v->mesh->info.bounds_max);
    default_camera(v);
    /* The default method of the file's kind, as on the command line. */
    const char *want = v->pf ? "stream" : "dfb";
    int first = 0;
    for (int i = 0; i < v->method_count; i++)
        if (!strcmp(v->methods[i]->name, want))
            first = i;
    if (viewer_switch_method(v, first, &err) != OIT_OK) {
        viewer_say(v, "opened %s, but %s cannot run here: %s", v->entry, want, err.message);
        v->quit = 1; /* no method left to show it with */
        return;
    }
    viewer_say(v, "opened %s: %llu triangles%s, method %s", v->entry,
               (unsigned long long)v->mesh->info.triangles, v->pf ? " (part file)" : "",
               v->methods[v->current]->name);
}

void viewer_handle_key(viewer *v, char key)
{
    switch (key) {
    case KEY_ESC:
    case 'Q':
        v->quit = 1;
        break;
    case 'W':
        viewer_fly(v, 1, 0, 0);
        viewer_moved(v);
        break;
    case 'S':
        viewer_fly(v, -1, 0, 0);
        viewer_moved(v);
        break;
    case 'D':
        viewer_fly(v, 0, 1, 0);
        viewer_moved(v);
        break;
    case 'A':
        viewer_fly(v, 0, -1, 0);
        viewer_moved(v);
        break;
    case ' ':
        viewer_fly(v, 0, 0, 1);
        viewer_moved(v);
        break;
    case 'C':
        viewer_fly(v, 0, 0, -1);
        viewer_moved(v);
        break;
    case 'R':
        v->view.camera = v->home;
        v->changed = 1;
        break;
    case 'T':
        toggle_shading(v);
        break;
    case 'U':
        cycle_up(v);
        break;
    case 'V':
        viewer_toggle_ortho(v);
        v->changed = 1;
        break;
    case 'P':
        viewer_save_screenshot(v);
        break;
    case 'G':
        v->grab_pending = 1;
        v->recompose = 1;
        break;
    case 'M':
        cycle_method(v, 1);
        break;
    case 'N':
        cycle_method(v, -1);
        break;
    case 'H':
    case '?':
        v->help = !v->help;
        v->recompose = 1;
        break;
    case 'O': /* from a script; the window's own O key opens the prompt at once */
        v->entering = 1;
        v->entry_len = 0;
        v->entry[0] = '\0';
        v->recompose = 1;
        break;
    case 'I':
        viewer_pick_at(v, v->mouse_x, v->mouse_y);
        break;
    case 'L':
        toggle_heat_map(v);
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
            viewer_say(v, "%s", note);
        } else if (key >= '0' && key <= '9')
            key_method(v, key == '0' ? 9 : key - '1');
        else
            viewer_say(v, "key %c does nothing (H lists the keys)", key);
    }
    }
}
