/* oitbench's charts (bench_plot.h). */
#include "tools/oitbench/bench_plot.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/grow.h"
#include "view/plot/chart.h"

enum {
    WIDTH = 1100,
    HEIGHT = 720,   /* plus a line per note */
    NOTE_H = 22,    /* chart.c's note line */
    MAX_NOTES = 12,
    LEGEND_W = 300
};

static const float grey[3] = {0.45f, 0.45f, 0.45f};
static const float black[3] = {0.0f, 0.0f, 0.0f};
static const float dark_red[3] = {0.6f, 0.1f, 0.1f};

int oit_bench_pareto_front(const double *x, const double *y, int n, unsigned char *on_front)
{
    int count = 0;
    for (int i = 0; i < n; i++) {
        int front = isfinite(x[i]) && isfinite(y[i]);
        for (int j = 0; front && j < n; j++)
            if (j != i && isfinite(x[j]) && isfinite(y[j]) && x[j] <= x[i] && y[j] <= y[i] &&
                (x[j] < x[i] || y[j] < y[i]))
                front = 0;
        on_front[i] = (unsigned char)front;
        count += front;
    }
    return count;
}

static int ran(const oit_bench_row *r)
{
    return r->ok && isfinite(r->ms_median) && isfinite(r->rmse);
}

double oit_bench_rmse_floor(const oit_bench_table *t)
{
    double least = INFINITY;
    for (size_t i = 0; i < t->count; i++) {
        const oit_bench_row *r = &t->rows[i];
        if (r->summary && ran(r) && r->rmse > 0.0)
            least = fmin(least, r->rmse);
    }
    return isfinite(least) ? pow(10.0, floor(log10(least)) - 1.0) : 1e-6;
}

/* "dfb (mesh)", "stream (parts)": an entry's name with what it drew, short
 * enough for a legend; the name alone for a file without geometry. */
static const char *row_label(const oit_bench_row *r, char *buf, size_t cap)
{
    if (r->geometry < 0)
        snprintf(buf, cap, "%s", r->method);
    else
        snprintf(buf, cap, "%s (%s)", r->method,
                 r->geometry == OIT_BENCH_GEOMETRY_PART_FILE ? "parts" : "mesh");
    return buf;
}

/* ---- notes: collected first, because the chart reserves their lines ---- */

typedef struct notes {
    char text[MAX_NOTES][600];
    unsigned char alert[MAX_NOTES]; /* an entry that did not run: red */
    int n, dropped;
} notes;

static void note(notes *ns, int alert, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Adds a line unless the same line is there already (an entry that did not
 * run in several runs is named once). */
static void note(notes *ns, int alert, const char *fmt, ...)
{
    char line[sizeof ns->text[0]];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    for (int i = 0; i < ns->n; i++)
        if (!strcmp(ns->text[i], line))
            return;
    if (ns->n == MAX_NOTES) {
        ns->dropped++;
        return;
    }
    ns->alert[ns->n] = (unsigned char)alert;
    memcpy(ns->text[ns->n++], line, sizeof line);
}

static void draw_notes(oit_chart *c, const notes *ns)
{
    for (int i = 0; i < ns->n; i++)
        oit_chart_note(c, ns->text[i], ns->alert[i] ? dark_red : grey);
}

/* ns->n lines, the last saying how many were left out */
static int note_lines(notes *ns)
{
    if (ns->dropped > 0)
        snprintf(ns->text[ns->n - 1], sizeof ns->text[0],
                 "... and %d more (see report.md and results.csv)", ns->dropped + 1);
    return ns->n;
}

/* Errors name the chart's file (writing errors already do). */
static oit_status open_chart(oit_chart *c, const char *title, const char *subtitle,
                             oit_chart_axis x, oit_chart_axis y, notes *ns, const char *path,
                             oit_error *err)
{
    int lines = note_lines(ns);
    oit_chart_desc d = {WIDTH, HEIGHT + lines * NOTE_H, title, subtitle, x, y, lines, LEGEND_W};
    oit_status s = oit_chart_create(c, &d, err);
    if (s != OIT_OK)
        oit_error_prefix(err, path);
    return s;
}

static oit_status finish(oit_chart *c, const char *path, oit_error *err)
{
    oit_status s = oit_chart_write_png(c, path, err);
    oit_chart_free(c);
    return s;
}

/* ---- series: points of one method ---- */

typedef struct series {
    char name[2 * OIT_BENCH_NAME_MAX];
    double *x, *y;
    int n, cap;
} series;

typedef struct series_set {
    series *s;
    int n, cap;
} series_set;

/* Points in order of x (then y), so a series' line runs left to right. */
static void sort_series(series *s)
{
    for (int i = 1; i < s->n; i++)
        for (int k = i; k > 0 && (s->x[k - 1] > s->x[k] ||
                                  (s->x[k - 1] == s->x[k] && s->y[k - 1] > s->y[k])); k--) {
            double tx = s->x[k], ty = s->y[k];
            s->x[k] = s->x[k - 1];
            s->y[k] = s->y[k - 1];
            s->x[k - 1] = tx;
            s->y[k - 1] = ty;
        }
}

/* ---- speed against error ---- */

typedef struct speed_points {
    const oit_bench_row **row;
    double *ms, *err;
    unsigned char *front;
    int n;
} speed_points;

static oit_status speed_collect(const oit_bench_table *t, double floor_y, speed_points *p,
                                notes *ns, oit_error *err)
{
    size_t cap = t->count ? t->count : 1;
    /* Zeroed: with no row that ran, the Pareto front is still handed the
     * arrays, and GCC (rightly) will not take "n is 0" as "never read". */
    p->row = calloc(cap, sizeof *p->row);
    p->ms = calloc(cap, sizeof *p->ms);
    p->err = calloc(cap, sizeof *p->err);
    p->front = calloc(cap, 1);
    p->n = 0;
    if (!p->row || !p->ms || !p->err || !p->front)
        return oit_error_set(err, OIT_ERR_NOMEM, "speed chart: cannot allocate %zu points", cap);
    for (size_t i = 0; i < t->count; i++) {
        const oit_bench_row *r = &t->rows[i];
        if (!r->summary)
            continue;
        if (!ran(r)) {
            note(ns, 1, "%s %s: %s", r->method, isfinite(r->ms_median) ? "stopped" : "not run",
                 r->reason[0] ? r->reason : "no reason given");
            continue;
        }
        p->row[p->n] = r;
        p->ms[p->n] = r->ms_median;
        p->err[p->n++] = r->rmse > 0.0 ? r->rmse : floor_y;
    }
    oit_bench_pareto_front(p->ms, p->err, p->n, p->front);
    return OIT_OK;
}

static void speed_free(speed_points *p)
{
    free(p->row);
    free(p->ms);
    free(p->err);
    free(p->front);
}

static void range(const double *v, int n, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) {
            *lo = fmin(*lo, v[i]);
            *hi = fmax(*hi, v[i]);
        }
}

/* The front as a line, in order of speed. */
static void draw_front(oit_chart *c, const speed_points *p)
{
    series f = {"front", malloc((size_t)p->n * sizeof(double) + 1),
                malloc((size_t)p->n * sizeof(double) + 1), 0, p->n};
    for (int i = 0; f.x && f.y && i < p->n; i++)
        if (p->front[i]) {
            f.x[f.n] = p->ms[i];
            f.y[f.n++] = p->err[i];
        }
    sort_series(&f);
    oit_chart_polyline(c, f.x, f.y, f.n, black, 1);
    free(f.x);
    free(f.y);
}

static void draw_floor(oit_chart *c, double floor_y)
{
    double x[2] = {c->x.lo, c->x.hi}, y[2] = {floor_y, floor_y};
    oit_chart_polyline(c, x, y, 2, grey, 1);
}

static void speed_draw(oit_chart *c, const speed_points *p, int zeros, double floor_y)
{
    if (zeros)
        draw_floor(c, floor_y);
    draw_front(c, p);
    for (int i = 0; i < p->n; i++) {
        float rgb[3];
        oit_chart_series_colour(i, rgb);
        oit_chart_point(c, p->ms[i], p->err[i], oit_chart_series_marker(i), rgb);
    }
    /* the front's names first: where points crowd, they keep theirs */
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < p->n; i++) {
            float rgb[3];
            oit_chart_series_colour(i, rgb);
            if (p->front[i] == !pass)
                oit_chart_point_label(c, p->ms[i], p->err[i], p->row[i]->method, rgb);
        }
    for (int i = 0; i < p->n; i++) {
        float rgb[3];
        char label[2 * OIT_BENCH_NAME_MAX];
        oit_chart_series_colour(i, rgb);
        oit_chart_legend(c, row_label(p->row[i], label, sizeof label),
                         oit_chart_series_marker(i), rgb, 0);
    }
    oit_chart_legend(c, "Pareto front", OIT_CHART_NO_MARKER, black, 2);
    if (zeros)
        oit_chart_legend(c, "RMSE 0 floor", OIT_CHART_NO_MARKER, grey, 2);
}

/* Log axes around the points, and around the floor line when it is drawn. */
static void speed_axes(const speed_points *p, double floor_y, oit_chart_axis *x,
                       oit_chart_axis *y)
{
    *x = (oit_chart_axis){"median ms per frame (log)", OIT_CHART_LOG10, 0, 0};
    *y = (oit_chart_axis){"mean RMSE vs Embree reference (log)", OIT_CHART_LOG10, 0, 0};
    double lo, hi;
    range(p->ms, p->n, &lo, &hi);
    oit_chart_axis_fit(x, lo, hi, 0);
    range(p->err, p->n, &lo, &hi);
    oit_chart_axis_fit(y, isfinite(floor_y) ? fmin(lo, floor_y) : lo, hi, 0);
}

/* A note per kind of triangles the entries drew ("drew the source mesh,
 * 100448 triangles: dfb, wboit"), as the legend has no room for it; none
 * for a file of the oitbench before geometry. */
static void note_geometry(const oit_bench_table *t, notes *ns)
{
    for (size_t i = 0; i < t->count; i++) {
        const oit_bench_row *r = &t->rows[i];
        int first = r->summary && r->geometry >= 0;
        for (size_t j = 0; first && j < i; j++)
            first = !(t->rows[j].summary && t->rows[j].geometry == r->geometry &&
                      t->rows[j].drawn_triangles == r->drawn_triangles);
        if (!first)
            continue;
        char line[sizeof ns->text[0]];
        size_t used = (size_t)snprintf(line, sizeof line, "drew the %s, %llu triangles:",
                                       r->geometry != OIT_BENCH_GEOMETRY_PART_FILE
                                           ? "source mesh"
                                       : r->drawn_triangles > r->triangles
                                           ? "part file (clipped)" : "part file",
                                       (unsigned long long)r->drawn_triangles);
        for (size_t j = i; j < t->count && used < sizeof line; j++)
            if (t->rows[j].summary && t->rows[j].geometry == r->geometry &&
                t->rows[j].drawn_triangles == r->drawn_triangles)
                used += (size_t)snprintf(line + used, sizeof line - used, "%s %s",
                                         j > i ? "," : "", t->rows[j].method);
        note(ns, 0, "%s", line);
    }
}

oit_status oit_bench_plot_speed_error(const oit_bench_table *t, const char *title,
                                      const char *subtitle, const char *path, oit_error *err)
{
    double floor_y = oit_bench_rmse_floor(t);
    notes ns = {.n = 0};
    note(&ns, 0, "Pareto front (dashed black): no other entry is both faster and more exact.");
    note_geometry(t, &ns);
    speed_points p = {0};
    oit_status s = speed_collect(t, floor_y, &p, &ns, err);
    if (s != OIT_OK)
        oit_error_prefix(err, path);
    int zeros = 0;
    for (int i = 0; s == OIT_OK && i < p.n; i++)
        zeros |= p.row[i]->rmse <= 0.0;
    if (zeros)
        note(&ns, 0, "RMSE 0 (the reference's image to the float) is drawn at %g, on the dashed "
                  "grey line.", floor_y);
    if (s == OIT_OK && p.n == 0)
        note(&ns, 0, "no entry rendered: nothing to plot");
    oit_chart_axis x, y;
    speed_axes(&p, zeros ? floor_y : NAN, &x, &y);
    oit_chart c;
    if (s == OIT_OK && (s = open_chart(&c, title, subtitle, x, y, &ns, path, err)) == OIT_OK) {
        speed_draw(&c, &p, zeros, floor_y);
        draw_notes(&c, &ns);
        s = finish(&c, path, err);
    }
    speed_free(&p);
    return s;
}

static series *find_series(series_set *set, const char *name)
{
    for (int i = 0; i < set->n; i++)
        if (!strcmp(set->s[i].name, name))
            return &set->s[i];
    if (set->n == set->cap) {
        int nc = set->cap ? 2 * set->cap : 8;
        series *ns = realloc(set->s, (size_t)nc * sizeof *ns);
        if (!ns)
            return NULL;
        set->s = ns;
        set->cap = nc;
    }
    series *s = &set->s[set->n++];
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    return s;
}

static int add_point(series_set *set, const char *name, double x, double y)
{
    series *s = find_series(set, name);
    if (!s)
        return 0;
    if (s->n == s->cap) {
        int nc = s->cap ? 2 * s->cap : 8;
        int ok = 1;
        s->x = oit_grow(s->x, (size_t)nc, sizeof *s->x, &ok);
        s->y = oit_grow(s->y, (size_t)nc, sizeof *s->y, &ok);
        if (!ok)
            return 0;
        s->cap = nc;
    }
    s->x[s->n] = x;
    s->y[s->n++] = y;
    return 1;
}

static void series_free(series_set *set)
{
    for (int i = 0; i < set->n; i++) {
        free(set->s[i].x);
        free(set->s[i].y);
    }
    free(set->s);
    memset(set, 0, sizeof *set);
}

static void set_range(const series_set *set, int want_y, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int i = 0; i < set->n; i++) {
        double a, b;
        range(want_y ? set->s[i].y : set->s[i].x, set->s[i].n, &a, &b);
        *lo = fmin(*lo, a);
        *hi = fmax(*hi, b);
    }
}

static void draw_series(oit_chart *c, series_set *set)
{
    for (int i = 0; i < set->n; i++) {
        series *s = &set->s[i];
        float rgb[3];
        oit_chart_series_colour(i, rgb);
        sort_series(s);
        oit_chart_polyline(c, s->x, s->y, s->n, rgb, 0);
        for (int k = 0; k < s->n; k++)
            oit_chart_point(c, s->x[k], s->y[k], oit_chart_series_marker(i), rgb);
        oit_chart_legend(c, s->name, oit_chart_series_marker(i), rgb, 1);
    }
}

/* The summary row of method in t when it never rendered, else NULL. */
static const oit_bench_row *never_ran(const oit_bench_table *t, const char *method)
{
    for (size_t i = 0; i < t->count; i++) {
        const oit_bench_row *row = &t->rows[i];
        if (row->summary && !strcmp(row->method, method))
            return !row->ok && !isfinite(row->ms_median) ? row : NULL;
    }
    return NULL;
}

/* Entries that never rendered: a line per method, in how many runs, and
 * the reason of the first. */
/* Runs written before gpu_mesh_bytes (bench_csv.h): their in-core methods'
 * figures leave the mesh out, so the chart says which runs those are. */
static void note_mesh_left_out(const oit_bench_table *runs, int n, notes *ns)
{
    int old = 0;
    for (int r = 0; r < n; r++)
        old += runs[r].count > 0 && !runs[r].rows[0].mesh_counted;
    if (old == 1 && n == 1)
        note(ns, 1, "this results.csv predates gpu_mesh_bytes: in-core figures leave out the "
                    "mesh");
    else if (old > 0)
        note(ns, 1, "%d of %d runs predate gpu_mesh_bytes: their in-core figures leave out the "
                    "mesh", old, n);
}

static void note_not_run(const oit_bench_table *runs, int n, notes *ns)
{
    for (int r = 0; r < n; r++)
        for (size_t i = 0; i < runs[r].count; i++) {
            const oit_bench_row *row = &runs[r].rows[i];
            int missed = 0, earlier = 0;
            if (!row->summary || never_ran(&runs[r], row->method) != row)
                continue;
            for (int q = 0; q < n; q++) {
                missed += never_ran(&runs[q], row->method) != NULL;
                earlier |= q < r && never_ran(&runs[q], row->method) != NULL;
            }
            if (earlier)
                continue;
            if (n == 1)
                note(ns, 1, "%s not run: %s", row->method, row->reason);
            else
                note(ns, 1, "%s not run in %d of %d runs: %s", row->method, missed, n,
                     row->reason);
        }
}

/* A linear axis from 0 unless the figures span more than two decades
 * (then log10, labelled log_label). */
static void fit_y_auto(oit_chart_axis *y, double lo, double hi, const char *log_label)
{
    y->scale = lo > 0.0 && hi / lo > 100.0 ? OIT_CHART_LOG10 : OIT_CHART_LINEAR;
    oit_chart_axis_fit(y, lo, hi, y->scale == OIT_CHART_LINEAR);
    if (y->scale == OIT_CHART_LOG10)
        y->label = log_label;
}

/* The chart of the set, when s is OIT_OK, with x fitted to its x values
 * (from 0 when x_zero) and y to its y values: fit_y_auto when y_log_label
 * is set, else on y's own scale. Frees the set either way. */
static oit_status series_chart(series_set *set, oit_status s, const char *title,
                               const char *subtitle, oit_chart_axis x, int x_zero,
                               oit_chart_axis y, const char *y_log_label, notes *ns,
                               const char *path, oit_error *err)
{
    double lo, hi;
    set_range(set, 0, &lo, &hi);
    oit_chart_axis_fit(&x, lo, hi, x_zero);
    set_range(set, 1, &lo, &hi);
    if (y_log_label)
        fit_y_auto(&y, lo, hi, y_log_label);
    else
        oit_chart_axis_fit(&y, lo, hi, 0);
    oit_chart c;
    if (s == OIT_OK)
        s = open_chart(&c, title, subtitle, x, y, ns, path, err);
    if (s == OIT_OK) {
        draw_series(&c, set);
        draw_notes(&c, ns);
        s = finish(&c, path, err);
    }
    series_free(set);
    return s;
}

oit_status oit_bench_plot_memory_depth(const oit_bench_table *runs, int n, const char *title,
                                       const char *subtitle, const char *path, oit_error *err)
{
    series_set set = {0};
    notes ns = {.n = 0};
    note(&ns, 0, "x: the most surfaces the Embree reference ray met at one pixel of the view");
    note(&ns, 0, "y: every GPU buffer and texture held at the peak, in-core methods' mesh "
              "included;");
    note(&ns, 0, "the stream's: its upload ring, residency cache, capture and per-pixel state");
    if (n == 1)
        note_geometry(&runs[0], &ns);
    note_mesh_left_out(runs, n, &ns);
    char key[2 * OIT_BENCH_NAME_MAX];
    int ok = 1;
    for (int r = 0; r < n; r++)
        for (size_t i = 0; ok && i < runs[r].count; i++) {
            const oit_bench_row *row = &runs[r].rows[i];
            if (!row->summary && row->ok)
                ok = add_point(&set, row_label(row, key, sizeof key), row->view_max_layers,
                               (double)row->gpu_bytes_peak / 1048576.0);
        }
    note_not_run(runs, n, &ns);
    oit_status s = ok ? OIT_OK : oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold the points",
                                               path);
    if (s == OIT_OK && set.n == 0)
        note(&ns, 0, "no view rendered: nothing to plot");
    oit_chart_axis x = {"depth complexity of the view (max layers)", OIT_CHART_LINEAR, 0, 0};
    oit_chart_axis y = {"GPU memory at peak (MiB)", OIT_CHART_LINEAR, 0, 0};
    return series_chart(&set, s, title, subtitle, x, 1, y, "GPU memory at peak (MiB, log)", &ns,
                        path, err);
}

oit_status oit_bench_plot_time_triangles(const oit_bench_table *runs, int n, const char *title,
                                         const char *subtitle, const char *path,
                                         oit_error *err)
{
    series_set set = {0};
    notes ns = {.n = 0};
    note(&ns, 0, "one point per run and method: the run's median over all its views and timed "
              "frames");
    char key[2 * OIT_BENCH_NAME_MAX];
    int ok = 1, models = 0;
    for (int r = 0; r < n; r++) {
        int distinct = runs[r].count > 0;
        for (int q = 0; distinct && q < r; q++)
            distinct = runs[q].count == 0 || runs[q].rows[0].triangles != runs[r].rows[0].triangles;
        models += distinct;
        for (size_t i = 0; ok && i < runs[r].count; i++) {
            const oit_bench_row *row = &runs[r].rows[i];
            if (row->summary && ran(row))
                ok = add_point(&set, row_label(row, key, sizeof key), (double)row->triangles,
                               row->ms_median);
        }
    }
    if (models < 2)
        note(&ns, 1, "every run has the same triangle count: give runs of models of other sizes");
    note_not_run(runs, n, &ns);
    oit_status s = ok ? OIT_OK : oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold the points",
                                               path);
    oit_chart_axis x = {"triangles of the model (log)", OIT_CHART_LOG10, 0, 0};
    oit_chart_axis y = {"median ms per frame (log)", OIT_CHART_LOG10, 0, 0};
    return series_chart(&set, s, title, subtitle, x, 0, y, NULL, &ns, path, err);
}
