/* Measured layer count of a part (layers_measured.h). */
#include "prepare/partition/layers_measured.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/minmax.h"
#include "base/vec.h"

/* Centres sit at (i + CENTRE_U, j + CENTRE_V) cells: fractions of sqrt(2)
 * and sqrt(3), which no dyadic CAD coordinate hits. */
#define CENTRE_U 0.41421356237
#define CENTRE_V 0.73205080757

/* The 13 directions, unnormalised: the projection below builds its own
 * orthonormal frame, so only the direction matters. */
static const double DIRS[OIT_LAYERS_DIRECTIONS][3] = {
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1},   {1, 1, 0},  {1, -1, 0}, {1, 0, 1},  {1, 0, -1},
    {0, 1, 1}, {0, 1, -1}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};

typedef struct frame {
    double u[3], v[3];
} frame;

static void normalise(double a[3])
{
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= l;
}

/* u and v orthonormal and perpendicular to d. */
static frame frame_of(const double d_in[3])
{
    double d[3] = {d_in[0], d_in[1], d_in[2]};
    normalise(d);
    double h[3] = {0, 0, 0};
    h[fabs(d[0]) < 0.9 ? 0 : 1] = 1; /* any axis not near d */
    frame f;
    oit_cross3d(d, h, f.u);
    normalise(f.u);
    oit_cross3d(d, f.u, f.v);
    return f;
}

static void project(const frame *f, const float p[3], double *x, double *y)
{
    *x = f->u[0] * p[0] + f->u[1] * p[1] + f->u[2] * p[2];
    *y = f->v[0] * p[0] + f->v[1] * p[1] + f->v[2] * p[2];
}

typedef struct grid {
    double x0, y0, cx, cy; /* origin and cell size of the projected bounds */
    uint32_t *count;       /* OIT_LAYERS_GRID^2 */
} grid;

static void grid_fit(grid *g, const frame *f, const oit_triangle *tris, size_t n)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double x, y;
            project(f, tris[i].v[k].pos, &x, &y);
            lo[0] = oit_min_d(lo[0], x), hi[0] = oit_max_d(hi[0], x);
            lo[1] = oit_min_d(lo[1], y), hi[1] = oit_max_d(hi[1], y);
        }
    g->x0 = lo[0];
    g->y0 = lo[1];
    /* A flat extent still needs a positive cell, or every centre lies past it. */
    g->cx = fmax(hi[0] - lo[0], 1e-30) / OIT_LAYERS_GRID;
    g->cy = fmax(hi[1] - lo[1], 1e-30) / OIT_LAYERS_GRID;
    memset(g->count, 0, sizeof *g->count * OIT_LAYERS_GRID * OIT_LAYERS_GRID);
}

static double edge(const double a[2], const double b[2], double x, double y)
{
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

/* The first cell index whose centre is >= t, clamped to the grid. */
static long first_at(double t, double origin, double cell, double frac)
{
    double i = ceil((t - origin) / cell - frac);
    return i < 0 ? 0 : i > OIT_LAYERS_GRID ? OIT_LAYERS_GRID : (long)i;
}

/* Counts the triangle at every centre its projection contains (edges
 * included: a centre exactly on one is a measure-zero line). */
static void grid_add(grid *g, const frame *f, const oit_triangle *t)
{
    double p[3][2];
    for (int k = 0; k < 3; k++)
        project(f, t->v[k].pos, &p[k][0], &p[k][1]);
    double area = edge(p[0], p[1], p[2][0], p[2][1]);
    if (area == 0)
        return; /* edge-on */
    double s = area > 0 ? 1 : -1;
    double mnx = oit_min_d(oit_min_d(p[0][0], p[1][0]), p[2][0]);
    double mxx = oit_max_d(oit_max_d(p[0][0], p[1][0]), p[2][0]);
    double mny = oit_min_d(oit_min_d(p[0][1], p[1][1]), p[2][1]);
    double mxy = oit_max_d(oit_max_d(p[0][1], p[1][1]), p[2][1]);
    long i0 = first_at(mnx, g->x0, g->cx, CENTRE_U), j0 = first_at(mny, g->y0, g->cy, CENTRE_V);
    for (long j = j0; j < OIT_LAYERS_GRID; j++) {
        double y = g->y0 + (j + CENTRE_V) * g->cy;
        if (y > mxy)
            break;
        for (long i = i0; i < OIT_LAYERS_GRID; i++) {
            double x = g->x0 + (i + CENTRE_U) * g->cx;
            if (x > mxx)
                break;
            if (s * edge(p[0], p[1], x, y) >= 0 && s * edge(p[1], p[2], x, y) >= 0 &&
                s * edge(p[2], p[0], x, y) >= 0)
                g->count[j * OIT_LAYERS_GRID + i]++;
        }
    }
}

static uint32_t grid_max(const grid *g)
{
    uint32_t m = 0;
    for (uint32_t i = 0; i < OIT_LAYERS_GRID * OIT_LAYERS_GRID; i++)
        m = g->count[i] > m ? g->count[i] : m;
    return m;
}

oit_status oit_layers_measure(const oit_triangle *tris, size_t n, uint32_t *layers,
                              oit_error *err)
{
    grid g;
    g.count = malloc(sizeof *g.count * OIT_LAYERS_GRID * OIT_LAYERS_GRID);
    if (!g.count)
        return oit_error_set(err, OIT_ERR_NOMEM, "layer count of a part of %zu triangles: "
                             "out of memory", n);
    uint32_t most = 1;
    for (uint32_t d = 0; d < OIT_LAYERS_DIRECTIONS && n; d++) {
        frame f = frame_of(DIRS[d]);
        grid_fit(&g, &f, tris, n);
        for (size_t i = 0; i < n; i++)
            grid_add(&g, &f, &tris[i]);
        uint32_t m = grid_max(&g);
        most = m > most ? m : most;
    }
    free(g.count);
    *layers = most;
    return OIT_OK;
}
