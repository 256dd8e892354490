/* The interactive loop of viewer.h. Methods render into an oit_image in the
 * window's context; the last rendered image (upscaled when it is a preview)
 * gets the overlays (status line, help, messages, the open prompt) and is
 * uploaded to a texture and blitted to the default framebuffer. The loop
 * renders only when the view or a setting changed, and otherwise blocks in
 * glfwWaitEvents (X events), with a timeout when a preview is waiting for
 * its exact frame or a message for its expiry. */
#include "tools/oitstream/viewer_internal.h"

/* ---- messages ---- */

/* A note on screen (and on stdout) for MESSAGE_SECONDS: why a key did
 * nothing, why a method cannot run, what was opened. */
void viewer_say(viewer *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void viewer_say(viewer *v, const char *fmt, ...)
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

/* ---- the loop ---- */

static oit_status open_viewer(viewer *v, oit_error *err)
{
    const oit_viewer_desc *d = v->desc;
    v->options = d->options;
    if (d->options.source)
        v->stream = *(const oit_run_source *)d->options.source;
    snprintf(v->stream_path, sizeof v->stream_path, "%s", v->stream.path ? v->stream.path : "");
    v->stream.path = v->stream_path;
    v->options.source = &v->stream;
    v->mesh = d->mesh;
    v->pf = d->partfile;
    v->up_axis = d->up_axis >= 0 && d->up_axis <= 2 ? d->up_axis : 1;
    snprintf(v->model_name, sizeof v->model_name, "%s", d->model_path ? d->model_path : "");
    viewer_fit_scene(v);
    v->view.camera = d->camera;
    v->home = d->camera;
    v->view.shading = d->shading;
    v->clip.planes = d->clip;
    v->view.clip = d->clip;
    v->show_layers = d->show_layers;
    viewer_list_methods(v);
    int first = -1;
    for (int i = 0; i < v->method_count; i++)
        if (!strcmp(v->methods[i]->name, d->method))
            first = i;
    if (first < 0 || viewer_unavailable(v, v->methods[first]))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window: method %s cannot render this "
                             "input%s%s", d->method, first >= 0 ? ": it " : "",
                             first >= 0 ? viewer_unavailable(v, v->methods[first]) : "");
    oit_gl_desc gd = {.width = d->width, .height = d->height, .title = "oitstream"};
    oit_status s = oit_gl_create_window(&gd, &v->gl, err);
    if (s != OIT_OK)
        return s;
    v->win = oit_gl_window(v->gl);
    glfwSetWindowUserPointer(v->win, v);
    glfwSetKeyCallback(v->win, viewer_on_key);
    glfwSetCharCallback(v->win, viewer_on_char);
    glfwSetDropCallback(v->win, viewer_on_drop);
    glfwSetMouseButtonCallback(v->win, viewer_on_button);
    glfwSetCursorPosCallback(v->win, viewer_on_cursor);
    glfwSetScrollCallback(v->win, viewer_on_scroll);
    glfwSetWindowRefreshCallback(v->win, viewer_on_refresh);
    glfwSetFramebufferSizeCallback(v->win, viewer_on_resize);
    glfwGetCursorPos(v->win, &v->mouse_x, &v->mouse_y);
    for (int i = 0; i < v->method_count; i++) {
        const char *why = viewer_unavailable(v, v->methods[i]);
        if (i < KEYED_METHODS)
            printf("viewer: key %d: %s%s%s%s\n", (i + 1) % 10, v->methods[i]->name,
                   why ? " (not for this input: " : "", why ? why : "", why ? ")" : "");
        else
            printf("viewer: no key: %s (M/N cycle to it)\n", v->methods[i]->name);
    }
    return viewer_switch_method(v, first, err);
}

static void close_viewer(viewer *v)
{
    viewer_close_preview_method(v);
    if (v->state)
        oit_run_close(v->state);
    if (v->gl) {
        glDeleteFramebuffers(1, &v->fbo);
        glDeleteTextures(1, &v->tex);
    }
    oit_gl_destroy(v->gl);
    if (v->have_owned)
        v->desc->close_model(v->desc->model_ctx, &v->owned);
    free(v->counts);
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
        viewer_handle_key(v, v->keys[k]);
    v->key_count = 0;
    if (v->open_pending && !v->quit)
        viewer_open_entry(v);
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
            viewer_push_key(v, desc->script[i]);
        handle_input(v);
        if (v->quit || glfwWindowShouldClose(v->win))
            break;
        s = viewer_one_frame(v, SHOWN_EXACT, err);
    }
    return s;
}

/* The interactive loop: block until something happens; render a preview
 * while the camera moves, the exact frame once it is still for still_ms
 * (or at once after a discrete change), and only recompose for overlays. */
static oit_status run_interactive(viewer *v, oit_error *err)
{
    double still = (v->desc->still_ms > 0 ? v->desc->still_ms : DEFAULT_STILL_MS) / 1000.0;
    oit_status s = viewer_one_frame(v, SHOWN_EXACT, err);
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
            s = viewer_one_frame(v, SHOWN_EXACT, err);
        else if (v->moved)
            s = viewer_one_frame(v, SHOWN_PREVIEW, err);
        else if (v->shown_kind == SHOWN_PREVIEW && now >= v->last_move + still)
            s = viewer_one_frame(v, SHOWN_EXACT, err);
        else if (v->recompose || v->grab_pending)
            s = viewer_present(v, err);
    }
    return s;
}

oit_status oit_viewer_run(const oit_viewer_desc *desc, oit_error *err)
{
    viewer v;
    memset(&v, 0, sizeof v);
    v.desc = desc;
    v.has_epsilon = desc->options.threshold != NULL;
    v.epsilon = v.has_epsilon ? *desc->options.threshold : 0.0f;
    oit_status s = open_viewer(&v, err);
    int limit = frame_limit(desc);
    if (s == OIT_OK)
        s = limit > 0 ? run_bounded(&v, limit, err) : run_interactive(&v, err);
    if (s == OIT_OK) {
        printf("viewer: %d frames rendered (%d exact, %d preview), %d presented; status band %d "
               "rows; last: %s\n", v.frames, v.exact_frames, v.preview_frames, v.presents,
               v.status_rows, v.frames ? v.status : "none");
        viewer_write_stats(&v);
    }
    if (s == OIT_OK && desc->screenshot && !v.shot.rgba)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "--window-screenshot %s: no frame was shown",
                          desc->screenshot);
    if (s == OIT_OK && desc->screenshot && (s = oit_image_write_png(&v.shot, desc->screenshot, err)) == OIT_OK)
        printf("viewer: screenshot %s\n", desc->screenshot);
    close_viewer(&v);
    return s;
}
