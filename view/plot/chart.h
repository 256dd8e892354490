/* A small chart drawn into an RGB image with the 5x7 font of text_overlay.h,
 * for tools that must write readable PNG plots without a plotting library:
 * white background, a plot frame with grid, ticks and numeric tick labels on
 * linear or log10 axes, a title and subtitle, axis labels (with units, the
 * caller's text), a legend column right of the plot, note lines under it,
 * and markers, polylines and point labels placed in data coordinates.
 *
 * Layout is fixed when the chart is created (axes, reserved note lines), so
 * the caller fits the axes to its data first (oit_chart_axis_fit). Data
 * outside an axis range, non-finite, or <= 0 on a log axis is not drawn:
 * oit_chart_map says which. The chart owns its image; nothing here keeps
 * state outside the oit_chart the caller passes. */
#ifndef OIT_PLOT_CHART_H
#define OIT_PLOT_CHART_H

#include <stddef.h>

#include "view/render/image/view.h"

typedef enum oit_chart_scale { OIT_CHART_LINEAR = 0, OIT_CHART_LOG10 } oit_chart_scale;

typedef struct oit_chart_axis {
    const char *label;     /* drawn beside the axis; name the unit in it */
    oit_chart_scale scale;
    double lo, hi;         /* the range drawn, lo < hi (> 0 on a log axis) */
} oit_chart_axis;

/* Widens [data_lo, data_hi] by a small margin (3% of a linear range, a
 * twentieth of a decade on a log one; none at a 0 that include_zero asked
 * for) and then to round values (decades on a log axis, multiples of a
 * 1-2-5 step on a linear one), and stores it in a->lo, a->hi. Non-finite
 * bounds (or <= 0 ones on a log axis) are ignored; with nothing left the
 * range is [0, 1] or [1, 10]. include_zero (linear only) stretches the
 * range to take in 0. */
void oit_chart_axis_fit(oit_chart_axis *a, double data_lo, double data_hi, int include_zero);

/* Tick values of an axis in increasing order, at most cap of them: every
 * decade of a log axis (with 2x and 5x when the range spans at most two
 * decades, every n-th decade when it spans more than ten), multiples of a
 * 1-2-5 step of about a fifth of the range on a linear one. Returns the
 * count. */
int oit_chart_ticks(const oit_chart_axis *a, double *ticks, int cap);

/* The label of tick value v: "0.01", "100", "1e-6", "2.5". */
void oit_chart_tick_label(const oit_chart_axis *a, double v, char *buf, size_t cap);

typedef enum oit_chart_marker {
    OIT_CHART_NO_MARKER = 0,
    OIT_CHART_CIRCLE,
    OIT_CHART_SQUARE,
    OIT_CHART_TRIANGLE,
    OIT_CHART_DIAMOND,
    OIT_CHART_TRIANGLE_DOWN,
    OIT_CHART_CROSS,
    OIT_CHART_PLUS,
    OIT_CHART_MARKER_KINDS
} oit_chart_marker;

/* The i-th series' colour (ten that tell apart on white, then repeating)
 * and marker (cycling through the shapes, changing when the colours wrap so
 * that the pair stays distinct for 70 series). */
void oit_chart_series_colour(int i, float rgb[3]);
oit_chart_marker oit_chart_series_marker(int i);

typedef struct oit_chart_desc {
    int width, height;       /* pixels; at least 320 x 240 */
    const char *title;       /* may be NULL; both cut with "..." to the width */
    const char *subtitle;    /* may be NULL */
    oit_chart_axis x, y;     /* label strings must outlive the chart */
    int note_lines;          /* text lines reserved under the plot */
    int legend_width;        /* pixels right of the plot; 0: 260 */
} oit_chart_desc;

typedef struct oit_chart_rect {
    int x0, y0, x1, y1; /* inclusive */
} oit_chart_rect;

#define OIT_CHART_MAX_PLACED 256

typedef struct oit_chart {
    oit_image img;
    oit_chart_axis x, y;
    oit_chart_rect plot;          /* the data area, frame included */
    int legend_x, legend_y;       /* where the next legend entry goes */
    int legend_full;              /* entries were dropped */
    int note_y, notes_free;       /* the next note line, lines left */
    /* what labels must not cover: placed labels and markers */
    oit_chart_rect placed[OIT_CHART_MAX_PLACED];
    int placed_count;
} oit_chart;

/* Allocates the image and draws everything but the data. Fails with
 * OIT_ERR_ARGUMENT when the size is too small for the reserved lines or an
 * axis range is invalid, OIT_ERR_NOMEM when the image cannot be had. */
oit_status oit_chart_create(oit_chart *c, const oit_chart_desc *d, oit_error *err);
void oit_chart_free(oit_chart *c);

/* Pixel of data point (x, y); returns 0 (pixel untouched) when the point is
 * outside the axes' ranges or cannot be placed on them. */
int oit_chart_map(const oit_chart *c, double x, double y, int *px, int *py);

/* A marker of the given shape centred on the data point, when it maps. */
void oit_chart_point(oit_chart *c, double x, double y, oit_chart_marker shape,
                     const float rgb[3]);

/* Straight segments through the n points in order, 2 pixels wide, clipped to
 * the plot area; a segment with an end that cannot be placed (non-finite, or
 * <= 0 on a log axis) is skipped. dashed: 8 pixels on, 6 off. */
void oit_chart_polyline(oit_chart *c, const double *x, const double *y, int n,
                        const float rgb[3], int dashed);

/* Text on a white box next to a data point, on the first place (beside,
 * above, below, then stacked up and down beside it with a leader line)
 * where it covers no earlier label or marker and stays in the plot area.
 * Returns 0 and draws nothing where no place is free (crowded points: the
 * legend still names them) or the point does not map. */
int oit_chart_point_label(oit_chart *c, double x, double y, const char *text,
                          const float rgb[3]);

/* One legend entry: a marker (or none), a line sample when line is 1 (solid)
 * or 2 (dashed), and the text, cut to the legend's width. Entries that do
 * not fit under the previous ones are dropped (returning 0), and the last
 * line that fits says "(more not shown)". */
int oit_chart_legend(oit_chart *c, const char *text, oit_chart_marker shape,
                     const float rgb[3], int line);

/* One line under the plot, cut with "..." to the image width. Returns 0
 * (nothing drawn) when the reserved lines are used up. */
int oit_chart_note(oit_chart *c, const char *text, const float rgb[3]);

oit_status oit_chart_write_png(const oit_chart *c, const char *path, oit_error *err);

#endif
