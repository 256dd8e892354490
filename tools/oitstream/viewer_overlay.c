/* What the viewer draws over the image (viewer_internal.h): the status
 * line's fields, the help, messages and the open prompt, as text panels. */
#include "tools/oitstream/viewer_internal.h"

static const float kWhite[3] = {1.0f, 1.0f, 1.0f}, kPanel[3] = {0.08f, 0.08f, 0.12f},
                   kAmber[3] = {1.0f, 0.8f, 0.3f}, kGrey[3] = {0.6f, 0.6f, 0.6f};

/* ---- status ---- */

static void human(double x, char *buf, size_t cap)
{
    if (x >= 1e9)
        snprintf(buf, cap, "%.1fG", x / 1e9);
    else if (x >= 1e6)
        snprintf(buf, cap, "%.1fM", x / 1e6);
    else if (x >= 1e3)
        snprintf(buf, cap, "%.1fK", x / 1e3);
    else
        snprintf(buf, cap, "%.0f", x);
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
    const oit_render_method_info *m = v->methods[v->current];
    char key[8], num[16];
    viewer_key_label(v->current, key, sizeof key);
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
    const oit_draw_stats *ss = v->state && !(v->shown_kind == SHOWN_PREVIEW && v->pv_method)
                                   ? oit_run_stream_stats(v->state)
                                   : NULL;
    oit_renderer_desc ran = {0};
    if (ss)
        oit_run_stream_desc(v->state, &ran);
    if (ss) {
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
        if (ran.epsilon > 0.0f) {
            field(f, "eps %.3g", ran.epsilon);
            field(f, "skipped %llu", (unsigned long long)ss->parts_skipped);
        }
    }
    if (v->show_layers && (m->flags & OIT_RENDER_METHOD_COUNTS))
        field(f, "heat map");
    else if (v->show_layers) /* L on, kept for a method that counts */
        field(f, "heat map n/a");
    if (v->view.camera.projection == OIT_PROJ_ORTHOGRAPHIC)
        field(f, "ortho");
    if (v->view.clip.count > 0)
        field(f, "section planes %d", v->view.clip.count);
    field(f, "%c up", viewer_axis_name(v->up_axis));
    field(f, "H help");
    size_t used = 0;
    v->status[0] = '\0';
    for (int i = 0; i < f->n && used + 1 < sizeof v->status; i++)
        used += (size_t)snprintf(v->status + used, sizeof v->status - used, "%s%s", i ? "  " : "",
                                 f->text[i]);
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

/* The panel's width as panel_draw draws it. */
static int panel_width(const oit_image *img, const panel *p)
{
    int scale = overlay_scale(img), w = 0;
    for (int i = 0; i < p->n; i++) {
        int tw = oit_text_width(p->line[i], scale);
        w = tw > w ? tw : w;
    }
    return w + 6 * scale;
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
    panel_add(p, kWhite, "left drag       viewer_orbit");
    panel_add(p, kWhite, "right drag, wheel  viewer_zoom");
    panel_add(p, kWhite, "W A S D         viewer_fly forward, left, back, right");
    panel_add(p, kWhite, "Space, C        viewer_fly up, down");
    panel_add(p, kWhite, "1..9, 0         method (same key for every input):");
    int keyed = v->method_count < KEYED_METHODS ? v->method_count : KEYED_METHODS;
    for (int i = 0; i < keyed; i += 4) {
        char line[PANEL_LINE];
        size_t used = 0;
        for (int j = i; j < i + 4 && j < keyed; j++)
            used += (size_t)snprintf(
                line + used, sizeof line - used, "  %d %s%s%s", (j + 1) % 10, v->methods[j]->name,
                viewer_unavailable(v, v->methods[j]) ? " (-)" : "", j == v->current ? " *" : "");
        panel_add(p, kWhite, "   %s", line);
    }
    panel_add(p, kGrey, "                * current, (-) not for this input");
    char more[PANEL_LINE];
    size_t used = 0;
    more[0] = '\0';
    for (int j = keyed; j < v->method_count; j++)
        used += (size_t)snprintf(more + used, sizeof more - used, "%s%s%s", j > keyed ? ", " : "",
                                 v->methods[j]->name, j == v->current ? " *" : "");
    panel_add(p, kWhite, "M, N            next, previous method%s%s%s", used ? " (also " : "", more,
              used ? ")" : "");
    panel_add(p, kWhite, "L               layer heat map (dfb, reference, stream)");
    panel_add(p, kWhite, "T               transparent / translucent");
    panel_add(p, kWhite, "E               early termination (stream)");
    panel_add(p, kWhite, "U               up axis y, z, x (now %c)", viewer_axis_name(v->up_axis));
    panel_add(p, kWhite, "V               perspective / orthographic (now %s)",
              v->view.camera.projection == OIT_PROJ_ORTHOGRAPHIC ? "ortho" : "perspective");
    panel_add(p, kWhite, "X               section plane: one through the centre facing");
    panel_add(p, kWhite, "                you, or the planes off / on");
    panel_add(p, kWhite, "[, ]            move section plane 1 back, forward");
    panel_add(p, kWhite, "I, left click   the layers under the cursor (stdout too)");
    panel_add(p, kWhite, "R               reset the camera");
    panel_add(p, kWhite, "O               open a file: type its path, Enter");
    panel_add(p, kWhite, "                (or drop a file on the window)");
    panel_add(p, kWhite, "P               save the view, offscreen at --shot-size, to");
    panel_add(p, kWhite, "                the next free oitstream_NNN.png");
    panel_add(p, kWhite, "G               the same of the window as shown (overlays)");
    panel_add(p, kWhite, "Q, Esc          quit");
    panel_add(p, kGrey, "moving shows a preview; still for %d ms, the exact image",
              v->desc->still_ms > 0 ? v->desc->still_ms : DEFAULT_STILL_MS);
}

/* The pick's layers (viewer_pick.c), each row in its layer's colour, as
 * many as max_rows (at least 1) leaves room for. */
static void pick_panel(const viewer *v, panel *p, int max_rows)
{
    p->n = 0;
    panel_add(p, kAmber, "pick %d,%d: %zu layer%s (all on stdout)", v->pick_x,
              v->pick_y, v->pick_count, v->pick_count == 1 ? "" : "s");
    panel_add(p, kGrey, "  #  depth      alpha  T before  part   source");
    size_t most = max_rows < 1 ? 1 : max_rows < VIEWER_PICK_ROWS ? (size_t)max_rows
                                                                  : VIEWER_PICK_ROWS;
    size_t rows = v->pick_count < most ? v->pick_count : most;
    for (size_t i = 0; i < rows; i++) {
        const oit_pick_layer *l = &v->pick[i];
        char part[16] = "-";
        if (l->part != OIT_PICK_NO_PART)
            snprintf(part, sizeof part, "%u", l->part);
        panel_add(p, l->colour, "%3zu  %-9.5g  %.3f  %.4f    %-6s %llu", i, l->depth, l->alpha,
                  l->transmittance[0], part, (unsigned long long)l->source_triangle);
    }
    if (v->pick_count > rows)
        panel_add(p, kGrey, "  ... %zu more", v->pick_count - rows);
}

/* A cross on the picked pixel, in the shown image's scale. */
static void pick_marker(const viewer *v, oit_image *img)
{
    int x = (int)((v->pick_x + 0.5) * img->width / v->view.width);
    int y = (int)((v->pick_y + 0.5) * img->height / v->view.height);
    oit_text_box(img, x - 6, y, 5, 1, kAmber);
    oit_text_box(img, x + 2, y, 5, 1, kAmber);
    oit_text_box(img, x, y - 6, 1, 5, kAmber);
    oit_text_box(img, x, y + 2, 1, 5, kAmber);
}

/* v->shown: v->base with the status line, the help, the open prompt and
 * the current message drawn over it. */
oit_status viewer_compose(viewer *v, oit_error *err)
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
    if (v->picked) {
        pick_marker(v, img);
        if (!v->help) {
            /* the rows the image's height leaves below the status line,
             * less the panel's title, header and "more" lines */
            int line_h = oit_text_line_height(scale);
            pick_panel(v, &p, (img->height - v->status_rows - 12 * scale) / line_h - 3);
            /* at the side of the image away from the picked pixel */
            int left = (v->pick_x + 0.5) * 2.0 >= v->view.width;
            int x = left ? 4 * scale : img->width - panel_width(img, &p) - 4 * scale;
            panel_draw(img, &p, x > 0 ? x : 0, v->status_rows + 4 * scale, 0);
        }
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
