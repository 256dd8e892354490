/* Charts drawn into images (chart.h). */
#include "view/plot/chart.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "view/plot/text_overlay.h"

enum {
    TEXT_SCALE = 2,   /* 12 px a character, 14 px high: readable at 100% */
    PAD = 16,         /* image border */
    GAP = 10,         /* between a tick label and its neighbours */
    TICK = 6,         /* tick mark length, outwards */
    LINE_H = 22,      /* a note or legend line */
    MARKER_R = 5,     /* marker half size */
    MIN_PLOT = 100    /* smallest plot area side worth drawing */
};

static const float ink[3] = {0.1f, 0.1f, 0.1f};
static const float grid_grey[3] = {0.88f, 0.88f, 0.88f};

/* ---- axes: ranges, ticks, labels ---- */

static double nice_step(double span)
{
    double raw = span / 5.0;
    double mag = pow(10.0, floor(log10(raw)));
    double f = raw / mag;
    return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

static void fit_log(oit_chart_axis *a, double lo, double hi)
{
    int lo_ok = isfinite(lo) && lo > 0.0, hi_ok = isfinite(hi) && hi > 0.0;
    if (!lo_ok && !hi_ok) {
        a->lo = 1.0;
        a->hi = 10.0;
        return;
    }
    if (!lo_ok) lo = hi;
    if (!hi_ok) hi = lo;
    /* a twentieth of a decade's margin keeps markers off the frame */
    a->lo = pow(10.0, floor(log10(fmin(lo, hi)) - 0.05));
    a->hi = pow(10.0, ceil(log10(fmax(lo, hi)) + 0.05));
    if (a->hi <= a->lo)
        a->hi = a->lo * 10.0;
}

static void fit_linear(oit_chart_axis *a, double lo, double hi, int include_zero)
{
    if (!isfinite(lo)) lo = hi;
    if (!isfinite(hi)) hi = lo;
    if (!isfinite(lo)) lo = hi = 0.0;
    if (lo > hi) {
        double t = lo;
        lo = hi;
        hi = t;
    }
    if (include_zero) {
        lo = fmin(lo, 0.0);
        hi = fmax(hi, 0.0);
    }
    if (hi - lo <= 1e-12 * fmax(fabs(lo), fabs(hi))) {
        double pad = lo != 0.0 ? fabs(lo) * 0.5 : 1.0;
        hi += pad;
        lo = include_zero && lo >= 0.0 ? lo : lo - pad;
    }
    /* a margin keeps markers off the frame, except at a 0 asked for */
    double pad = 0.03 * (hi - lo);
    lo = include_zero && lo == 0.0 ? lo : lo - pad;
    hi = include_zero && hi == 0.0 ? hi : hi + pad;
    double step = nice_step(hi - lo);
    a->lo = floor(lo / step + 1e-9) * step;
    a->hi = ceil(hi / step - 1e-9) * step;
}

void oit_chart_axis_fit(oit_chart_axis *a, double data_lo, double data_hi, int include_zero)
{
    if (a->scale == OIT_CHART_LOG10)
        fit_log(a, data_lo, data_hi);
    else
        fit_linear(a, data_lo, data_hi, include_zero);
}

static int log_ticks(const oit_chart_axis *a, double *t, int cap)
{
    int klo = (int)ceil(log10(a->lo) - 1e-9), khi = (int)floor(log10(a->hi) + 1e-9);
    int decades = khi - klo + 1, n = 0;
    if (decades <= 2) {
        static const double mult[3] = {1.0, 2.0, 5.0};
        for (int k = klo - 1; k <= khi; k++)
            for (int m = 0; m < 3 && n < cap; m++) {
                double v = mult[m] * pow(10.0, k);
                if (v >= a->lo * (1 - 1e-9) && v <= a->hi * (1 + 1e-9))
                    t[n++] = v;
            }
        return n;
    }
    int stride = decades > 10 ? (decades + 7) / 8 : 1;
    for (int k = klo; k <= khi && n < cap; k += stride)
        t[n++] = pow(10.0, k);
    return n;
}

static int linear_ticks(const oit_chart_axis *a, double *t, int cap)
{
    double step = nice_step(a->hi - a->lo);
    double first = ceil(a->lo / step - 1e-9);
    int n = 0;
    for (int i = 0; n < cap; i++) {
        double v = (first + i) * step;
        if (v > a->hi + step * 1e-9)
            break;
        t[n++] = fabs(v) < step * 1e-9 ? 0.0 : v;
    }
    return n;
}

int oit_chart_ticks(const oit_chart_axis *a, double *ticks, int cap)
{
    if (!(a->lo < a->hi) || (a->scale == OIT_CHART_LOG10 && !(a->lo > 0.0)))
        return 0;
    return a->scale == OIT_CHART_LOG10 ? log_ticks(a, ticks, cap) : linear_ticks(a, ticks, cap);
}

void oit_chart_tick_label(const oit_chart_axis *a, double v, char *buf, size_t cap)
{
    if (a->scale == OIT_CHART_LOG10) {
        int k = (int)floor(log10(v) + 1e-9);
        double m = v / pow(10.0, k);
        if (k >= -4 && k <= 5)
            snprintf(buf, cap, "%g", v);
        else if (fabs(m - 1.0) < 1e-6)
            snprintf(buf, cap, "1e%d", k);
        else
            snprintf(buf, cap, "%.0fe%d", m, k);
        return;
    }
    double step = nice_step(a->hi - a->lo);
    if (v != 0.0 && (fabs(v) >= 1e6 || fabs(v) < 1e-4)) {
        snprintf(buf, cap, "%.3g", v);
        return;
    }
    int decimals = step >= 1.0 ? 0 : (int)ceil(-log10(step) - 1e-9);
    snprintf(buf, cap, "%.*f", decimals, v);
}

/* 0..1 along the axis; NAN where the value cannot be placed on it. */
static double axis_fraction(const oit_chart_axis *a, double v)
{
    if (!isfinite(v))
        return NAN;
    if (a->scale == OIT_CHART_LOG10)
        return v > 0.0 ? (log10(v) - log10(a->lo)) / (log10(a->hi) - log10(a->lo)) : NAN;
    return (v - a->lo) / (a->hi - a->lo);
}

/* ---- pixels ---- */


static void fill_rect(oit_image *img, int x0, int y0, int x1, int y1, const float rgb[3])
{
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++)
            oit_image_put_rgb(img, x, y, rgb);
}

static int inside(const oit_chart_rect *r, int x, int y)
{
    return x >= r->x0 && x <= r->x1 && y >= r->y0 && y <= r->y1;
}

/* Bresenham from (x0,y0) to (x1,y1), 2 pixels wide, only inside clip (NULL:
 * the whole image); dashed lines keep their phase in *phase. */
static void segment(oit_image *img, const oit_chart_rect *clip, int x0, int y0, int x1, int y1,
                    const float rgb[3], int dashed, int *phase)
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int e = dx + dy;
    for (;;) {
        int on = !dashed || (*phase)++ % 14 < 8;
        for (int k = 0; on && k < 4; k++) {
            int px = x0 + (k & 1), py = y0 + (k >> 1);
            if (!clip || inside(clip, px, py))
                oit_image_put_rgb(img, px, py, rgb);
        }
        if (x0 == x1 && y0 == y1)
            break;
        int e2 = 2 * e;
        if (e2 >= dy) { e += dy; x0 += sx; }
        if (e2 <= dx) { e += dx; y0 += sy; }
    }
}

static void marker_at(oit_image *img, int cx, int cy, oit_chart_marker shape, const float rgb[3])
{
    const int r = MARKER_R;
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            int ax = abs(dx), ay = abs(dy), on = 0;
            switch (shape) {
            case OIT_CHART_CIRCLE: on = dx * dx + dy * dy <= r * r + 1; break;
            case OIT_CHART_SQUARE: on = ax <= r - 1 && ay <= r - 1; break;
            case OIT_CHART_TRIANGLE: on = 2 * ax <= dy + r; break;
            case OIT_CHART_TRIANGLE_DOWN: on = 2 * ax <= r - dy; break;
            case OIT_CHART_DIAMOND: on = ax + ay <= r; break;
            case OIT_CHART_CROSS: on = abs(ax - ay) <= 1; break;
            case OIT_CHART_PLUS: on = ax <= 1 || ay <= 1; break;
            default: break;
            }
            if (on)
                oit_image_put_rgb(img, cx + dx, cy + dy, rgb);
        }
}

/* ---- series styles ---- */

void oit_chart_series_colour(int i, float rgb[3])
{
    /* Tableau 10: distinct for most colour vision, dark enough on white */
    static const unsigned char pal[10][3] = {
        {31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {100, 100, 100}, {188, 189, 34}, {23, 190, 207}};
    int k = ((i % 10) + 10) % 10;
    for (int c = 0; c < 3; c++)
        rgb[c] = pal[k][c] / 255.0f;
}

oit_chart_marker oit_chart_series_marker(int i)
{
    int kinds = OIT_CHART_MARKER_KINDS - 1;
    int k = i < 0 ? 0 : (i + i / 10) % kinds;
    return (oit_chart_marker)(OIT_CHART_CIRCLE + k);
}

/* ---- layout and frame ---- */

static int y_label_width(const oit_chart_axis *a)
{
    double t[64];
    int n = oit_chart_ticks(a, t, 64), w = 0;
    for (int i = 0; i < n; i++) {
        char b[32];
        oit_chart_tick_label(a, t[i], b, sizeof b);
        int tw = oit_text_width(b, TEXT_SCALE);
        w = tw > w ? tw : w;
    }
    return w;
}

static int header_height(const oit_chart_desc *d)
{
    int th = oit_text_height(TEXT_SCALE);
    return PAD + (d->title ? th + 8 : 0) + (d->subtitle ? th + 8 : 0) + 8;
}

static oit_status layout(oit_chart *c, const oit_chart_desc *d, oit_error *err)
{
    int th = oit_text_height(TEXT_SCALE);
    int legend = d->legend_width > 0 ? d->legend_width : 260;
    c->plot.x0 = PAD + th + GAP + y_label_width(&d->y) + GAP + TICK;
    c->plot.x1 = d->width - PAD - legend;
    c->plot.y0 = header_height(d);
    c->plot.y1 = d->height - PAD - d->note_lines * LINE_H - (th + GAP) * 2 - TICK;
    if (c->plot.x1 - c->plot.x0 < MIN_PLOT || c->plot.y1 - c->plot.y0 < MIN_PLOT)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "chart %dx%d: no room for a plot area of "
                             "%dx%d pixels beside a %d-pixel legend and %d note lines",
                             d->width, d->height, MIN_PLOT, MIN_PLOT, legend, d->note_lines);
    c->legend_x = c->plot.x1 + 2 * GAP;
    c->legend_y = c->plot.y0;
    c->note_y = d->height - PAD - d->note_lines * LINE_H + (LINE_H - th) / 2;
    c->notes_free = d->note_lines;
    return OIT_OK;
}

/* Rounded the same way as place() below, so lines meet markers. */
static int axis_pixel_x(const oit_chart *c, double v)
{
    return (int)lround(c->plot.x0 + axis_fraction(&c->x, v) * (c->plot.x1 - c->plot.x0));
}

static int axis_pixel_y(const oit_chart *c, double v)
{
    return (int)lround(c->plot.y1 - axis_fraction(&c->y, v) * (c->plot.y1 - c->plot.y0));
}

static void draw_x_ticks(oit_chart *c)
{
    double t[64];
    int n = oit_chart_ticks(&c->x, t, 64), last_right = -1000000;
    for (int i = 0; i < n; i++) {
        int px = axis_pixel_x(c, t[i]);
        fill_rect(&c->img, px, c->plot.y0, px, c->plot.y1, grid_grey);
        fill_rect(&c->img, px, c->plot.y1, px, c->plot.y1 + TICK, ink);
        char b[32];
        oit_chart_tick_label(&c->x, t[i], b, sizeof b);
        int w = oit_text_width(b, TEXT_SCALE);
        /* crowded labels: keep every one that clears the previous */
        if (px - w / 2 > last_right + GAP) {
            oit_text_draw(&c->img, px - w / 2, c->plot.y1 + TICK + GAP / 2, b, ink, TEXT_SCALE);
            last_right = px + w / 2;
        }
    }
}

static void draw_y_ticks(oit_chart *c)
{
    double t[64];
    int n = oit_chart_ticks(&c->y, t, 64), th = oit_text_height(TEXT_SCALE);
    int last_top = 1000000;
    for (int i = 0; i < n; i++) {
        int py = axis_pixel_y(c, t[i]);
        fill_rect(&c->img, c->plot.x0, py, c->plot.x1, py, grid_grey);
        fill_rect(&c->img, c->plot.x0 - TICK, py, c->plot.x0, py, ink);
        char b[32];
        oit_chart_tick_label(&c->y, t[i], b, sizeof b);
        if (py + th / 2 < last_top - 4) {
            int w = oit_text_width(b, TEXT_SCALE);
            oit_text_draw(&c->img, c->plot.x0 - TICK - GAP / 2 - w, py - th / 2, b, ink,
                          TEXT_SCALE);
            last_top = py - th / 2;
        }
    }
}

static void draw_frame(oit_chart *c)
{
    const oit_chart_rect *p = &c->plot;
    fill_rect(&c->img, p->x0, p->y0, p->x1, p->y0, ink);
    fill_rect(&c->img, p->x0, p->y1, p->x1, p->y1, ink);
    fill_rect(&c->img, p->x0, p->y0, p->x0, p->y1, ink);
    fill_rect(&c->img, p->x1, p->y0, p->x1, p->y1, ink);
}

static void fit_text(const char *text, int width, char *buf, size_t cap);

static void draw_labels(oit_chart *c, const oit_chart_desc *d)
{
    int th = oit_text_height(TEXT_SCALE), y = PAD;
    char b[512];
    if (d->title) {
        fit_text(d->title, d->width - 2 * PAD, b, sizeof b);
        oit_text_draw(&c->img, PAD, y, b, ink, TEXT_SCALE);
        y += th + 8;
    }
    if (d->subtitle) {
        fit_text(d->subtitle, d->width - 2 * PAD, b, sizeof b);
        oit_text_draw(&c->img, PAD, y, b, ink, TEXT_SCALE);
    }
    if (d->x.label) {
        int w = oit_text_width(d->x.label, TEXT_SCALE);
        oit_text_draw(&c->img, (c->plot.x0 + c->plot.x1 - w) / 2,
                      c->plot.y1 + TICK + GAP / 2 + th + GAP, d->x.label, ink, TEXT_SCALE);
    }
    if (d->y.label) {
        int w = oit_text_width(d->y.label, TEXT_SCALE);
        oit_text_draw_up(&c->img, PAD, (c->plot.y0 + c->plot.y1 + w) / 2, d->y.label, ink,
                         TEXT_SCALE);
    }
}

static int axis_valid(const oit_chart_axis *a)
{
    return isfinite(a->lo) && isfinite(a->hi) && a->lo < a->hi &&
           (a->scale != OIT_CHART_LOG10 || a->lo > 0.0);
}

oit_status oit_chart_create(oit_chart *c, const oit_chart_desc *d, oit_error *err)
{
    memset(c, 0, sizeof *c);
    if (d->width < 320 || d->height < 240)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "chart %dx%d: smaller than 320x240",
                             d->width, d->height);
    if (!axis_valid(&d->x) || !axis_valid(&d->y))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "chart '%s': invalid axis range",
                             d->title ? d->title : "");
    c->x = d->x;
    c->y = d->y;
    oit_status s = layout(c, d, err);
    if (s == OIT_OK)
        s = oit_image_alloc(&c->img, d->width, d->height, err);
    if (s != OIT_OK)
        return s;
    static const float white[3] = {1.0f, 1.0f, 1.0f};
    fill_rect(&c->img, 0, 0, d->width - 1, d->height - 1, white);
    draw_x_ticks(c);
    draw_y_ticks(c);
    draw_frame(c);
    draw_labels(c, d);
    return OIT_OK;
}

void oit_chart_free(oit_chart *c)
{
    oit_image_free(&c->img);
}

/* ---- data ---- */

/* Pixel position, unrounded and unchecked against the range (lines run to
 * points outside it and are clipped); 0 when it cannot be placed at all. */
static int place(const oit_chart *c, double x, double y, double *px, double *py)
{
    double fx = axis_fraction(&c->x, x), fy = axis_fraction(&c->y, y);
    if (!isfinite(fx) || !isfinite(fy))
        return 0;
    *px = c->plot.x0 + fx * (c->plot.x1 - c->plot.x0);
    *py = c->plot.y1 - fy * (c->plot.y1 - c->plot.y0);
    return 1;
}

int oit_chart_map(const oit_chart *c, double x, double y, int *px, int *py)
{
    double fx = axis_fraction(&c->x, x), fy = axis_fraction(&c->y, y);
    const double tol = 1e-9;
    if (!(fx >= -tol && fx <= 1 + tol && fy >= -tol && fy <= 1 + tol))
        return 0;
    *px = axis_pixel_x(c, x);
    *py = axis_pixel_y(c, y);
    return 1;
}

static void remember(oit_chart *c, oit_chart_rect r)
{
    if (c->placed_count < OIT_CHART_MAX_PLACED)
        c->placed[c->placed_count++] = r;
}

void oit_chart_point(oit_chart *c, double x, double y, oit_chart_marker shape,
                     const float rgb[3])
{
    int px, py;
    if (shape == OIT_CHART_NO_MARKER || !oit_chart_map(c, x, y, &px, &py))
        return;
    marker_at(&c->img, px, py, shape, rgb);
    remember(c, (oit_chart_rect){px - MARKER_R, py - MARKER_R, px + MARKER_R, py + MARKER_R});
}

void oit_chart_polyline(oit_chart *c, const double *x, const double *y, int n,
                        const float rgb[3], int dashed)
{
    int phase = 0;
    for (int i = 0; i + 1 < n; i++) {
        double ax, ay, bx, by;
        if (!place(c, x[i], y[i], &ax, &ay) || !place(c, x[i + 1], y[i + 1], &bx, &by))
            continue;
        /* far-off ends would make Bresenham walk millions of pixels */
        const double lim = 1e5;
        if (fabs(ax) > lim || fabs(ay) > lim || fabs(bx) > lim || fabs(by) > lim)
            continue;
        segment(&c->img, &c->plot, (int)lround(ax), (int)lround(ay), (int)lround(bx),
                (int)lround(by), rgb, dashed, &phase);
    }
}

static int overlaps(const oit_chart_rect *a, const oit_chart_rect *b)
{
    return a->x0 <= b->x1 && b->x0 <= a->x1 && a->y0 <= b->y1 && b->y0 <= a->y1;
}

static int free_spot(const oit_chart *c, const oit_chart_rect *r)
{
    if (r->x0 < c->plot.x0 + 2 || r->x1 > c->plot.x1 - 2 || r->y0 < c->plot.y0 + 2 ||
        r->y1 > c->plot.y1 - 2)
        return 0;
    for (int i = 0; i < c->placed_count; i++)
        if (overlaps(r, &c->placed[i]))
            return 0;
    return 1;
}

/* Where a label may go: beside, above and below the point, then stacked
 * further up and down beside it (with a leader line), nearest first. */
static int label_spots(int px, int py, int w, int h, int spot[16][2])
{
    int off = MARKER_R + 4, n = 0;
    const int near[4][2] = {{px + off, py - h / 2}, {px - off - w, py - h / 2},
                            {px - w / 2, py - off - h}, {px - w / 2, py + off}};
    for (int i = 0; i < 4; i++, n++) {
        spot[n][0] = near[i][0];
        spot[n][1] = near[i][1];
    }
    for (int k = 1; k <= 3; k++)
        for (int side = 0; side < 4; side++, n++) {
            spot[n][0] = side & 1 ? px - off - w : px + off;
            spot[n][1] = py - h / 2 + (side & 2 ? k : -k) * (h + 4);
        }
    return n;
}

int oit_chart_point_label(oit_chart *c, double x, double y, const char *text,
                          const float rgb[3])
{
    int px, py, spot[16][2];
    if (!oit_chart_map(c, x, y, &px, &py))
        return 0;
    int w = oit_text_width(text, TEXT_SCALE), h = oit_text_height(TEXT_SCALE);
    int n = label_spots(px, py, w, h, spot);
    for (int i = 0; i < n; i++) {
        oit_chart_rect r = {spot[i][0], spot[i][1], spot[i][0] + w - 1, spot[i][1] + h - 1};
        if (!free_spot(c, &r))
            continue;
        if (i >= 4) {
            static const float leader[3] = {0.6f, 0.6f, 0.6f};
            int phase = 0, lx = r.x0 > px ? r.x0 - 2 : r.x1 + 2;
            segment(&c->img, &c->plot, px, py, lx, (r.y0 + r.y1) / 2, leader, 0, &phase);
        }
        /* a white box keeps the text readable over grid and data lines */
        static const float white[3] = {1.0f, 1.0f, 1.0f};
        fill_rect(&c->img, r.x0 - 1, r.y0 - 1, r.x1 + 1, r.y1 + 1, white);
        oit_text_draw(&c->img, r.x0, r.y0, text, rgb, TEXT_SCALE);
        remember(c, r);
        return 1;
    }
    return 0;
}

/* text cut to at most width pixels, ending in "..." when cut */
static void fit_text(const char *text, int width, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s", text);
    if (oit_text_width(buf, TEXT_SCALE) <= width)
        return;
    size_t n = strlen(buf);
    while (n > 0 && oit_text_width(buf, TEXT_SCALE) > width) {
        buf[--n] = 0;
        if (n >= 3)
            memcpy(buf + n - 3, "...", 3);
    }
}

int oit_chart_legend(oit_chart *c, const char *text, oit_chart_marker shape,
                     const float rgb[3], int line)
{
    int th = oit_text_height(TEXT_SCALE), bottom = c->img.height - PAD;
    if (c->legend_full)
        return 0;
    if (c->legend_y + 2 * LINE_H > bottom) {
        /* the last line that fits says that entries are missing */
        oit_text_draw(&c->img, c->legend_x, c->legend_y + (LINE_H - th) / 2, "(more not shown)",
                      ink, TEXT_SCALE);
        c->legend_full = 1;
        return 0;
    }
    int cy = c->legend_y + LINE_H / 2, x = c->legend_x;
    if (line) {
        int phase = 0;
        segment(&c->img, NULL, x, cy, x + 30, cy, rgb, line == 2, &phase);
    }
    marker_at(&c->img, x + 15, cy, shape, rgb);
    char b[256];
    fit_text(text, c->img.width - PAD - (x + 40), b, sizeof b);
    oit_text_draw(&c->img, x + 40, cy - th / 2, b, ink, TEXT_SCALE);
    c->legend_y += LINE_H;
    return 1;
}

int oit_chart_note(oit_chart *c, const char *text, const float rgb[3])
{
    if (c->notes_free <= 0)
        return 0;
    char b[512];
    fit_text(text, c->img.width - 2 * PAD, b, sizeof b);
    oit_text_draw(&c->img, PAD, c->note_y, b, rgb, TEXT_SCALE);
    c->note_y += LINE_H;
    c->notes_free--;
    return 1;
}

oit_status oit_chart_write_png(const oit_chart *c, const char *path, oit_error *err)
{
    return oit_image_write_png(&c->img, path, err);
}
