/* Exact integer-normal planes (plane_exact.h). */
#include "prepare/partition/plane_exact.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prepare/partition/clip.h"

void oit_plane_exact_init(oit_plane_exact *pl, const int n[3], const float lo[3],
                          const float hi[3])
{
    double bound = 0;
    int axis = 0;
    for (int k = 0; k < 3; k++) {
        pl->n[k] = n[k];
        double m = fmax(fabs((double)lo[k]), fabs((double)hi[k]));
        /* A free coordinate with n[k] = 0 is still a grain multiple. */
        bound += (n[k] ? abs(n[k]) : 1) * m;
        if (abs(n[k]) > abs(n[axis]))
            axis = k;
    }
    /* |d - sum n[j] x[j]| <= 2 bound < 2^24 grain: its quotient by n[axis]
     * has at most 24 significant bits. */
    int e;
    frexp(fmax(2 * bound, (double)FLT_MIN), &e);
    pl->axis = axis;
    pl->grain = ldexp(1.0, e - 24);
    pl->d = 0;
}

static void two_sum(double a, double b, double *s, double *err)
{
    *s = a + b;
    double bv = *s - a, av = *s - bv;
    *err = (a - av) + (b - bv);
}

int oit_plane_side_exact(const float n[3], double d, const float p[3])
{
    /* Each product of two floats is exact in double; the sum is kept as a
     * non-overlapping expansion (grow-expansion), whose largest non-zero
     * component has the sum's sign. */
    double t[4] = {(double)n[0] * p[0], (double)n[1] * p[1], (double)n[2] * p[2], -d};
    double e[4];
    int m = 0;
    for (int i = 0; i < 4; i++) {
        double q = t[i];
        for (int j = 0; j < m; j++)
            two_sum(q, e[j], &q, &e[j]);
        e[m++] = q;
    }
    for (int j = m - 1; j >= 0; j--)
        if (e[j] != 0)
            return e[j] > 0 ? 1 : -1;
    return 0;
}

int oit_plane_exact_side(const oit_plane_exact *pl, const float p[3])
{
    const float n[3] = {(float)pl->n[0], (float)pl->n[1], (float)pl->n[2]};
    return oit_plane_side_exact(n, pl->d, p);
}

static double approx_value(const oit_plane_exact *pl, const float p[3])
{
    return pl->n[0] * (double)p[0] + pl->n[1] * (double)p[1] + pl->n[2] * (double)p[2] - pl->d;
}

/* The grain point for one choice of rounding (bit j: up) of the two free
 * coordinates; 0 when it leaves the box or is not a float. */
static int grain_point(const oit_plane_exact *pl, const double x[3], int choice,
                       const float lo[3], const float hi[3], double y[3])
{
    int k = pl->axis, bit = 0;
    double s = pl->d;
    for (int j = 0; j < 3; j++) {
        if (j == k)
            continue;
        double q = x[j] / pl->grain;
        y[j] = ((choice >> bit++) & 1 ? ceil(q) : floor(q)) * pl->grain;
        s -= pl->n[j] * y[j];
    }
    y[k] = s / pl->n[k];
    for (int j = 0; j < 3; j++)
        if ((double)(float)y[j] != y[j] || y[j] < lo[j] || y[j] > hi[j])
            return 0;
    return 1;
}

int oit_plane_exact_seam(const oit_plane_exact *pl, const oit_vertex *p, const oit_vertex *q,
                         const float lo[3], const float hi[3], oit_vertex *out)
{
    const oit_vertex *a = oit_vertex_less(p, q) ? p : q;
    const oit_vertex *b = a == p ? q : p;
    double fa = approx_value(pl, a->pos), fb = approx_value(pl, b->pos);
    double t = fa / (fa - fb), x[3], best[3] = {0, 0, 0}, best_dist = INFINITY;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; k++)
        x[k] = a->pos[k] + t * ((double)b->pos[k] - a->pos[k]);
    for (int choice = 0; choice < 4; choice++) {
        double y[3];
        if (!grain_point(pl, x, choice, lo, hi, y))
            continue;
        double dist = 0;
        for (int k = 0; k < 3; k++)
            dist += (y[k] - x[k]) * (y[k] - x[k]);
        if (dist < best_dist) {
            best_dist = dist;
            memcpy(best, y, sizeof best);
        }
    }
    if (!(best_dist < INFINITY))
        return 0;
    for (int k = 0; k < 3; k++)
        out->pos[k] = (float)best[k];
    for (int k = 0; k < 4; k++)
        out->rgba[k] = (uint8_t)lrint(a->rgba[k] + t * ((double)b->rgba[k] - a->rgba[k]));
    return 1;
}

/* The closed half below (keep = -1) or above (keep = 1) of triangle t whose
 * vertex sides are side[]; returns the polygon's vertex count or -1. */
static int clip_side(const oit_plane_exact *pl, const oit_triangle *t, const int side[3],
                     int keep, const float lo[3], const float hi[3], oit_vertex *out)
{
    int m = 0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        if (side[i] != -keep)
            out[m++] = t->v[i];
        if (side[i] * side[j] < 0 && !oit_plane_exact_seam(pl, &t->v[i], &t->v[j], lo, hi,
                                                           &out[m++]))
            return -1;
    }
    return m;
}

int oit_plane_exact_split(const oit_plane_exact *pl, const oit_triangle *t, const float lo[3],
                          const float hi[3], oit_triangle *below, int *n_below,
                          oit_triangle *above, int *n_above)
{
    int side[3], has_below = 0, has_above = 0;
    for (int i = 0; i < 3; i++) {
        side[i] = oit_plane_exact_side(pl, t->v[i].pos);
        has_below |= side[i] < 0;
        has_above |= side[i] > 0;
    }
    *n_below = *n_above = 0;
    if (!has_above) {
        below[(*n_below)++] = *t;
        return 1;
    }
    if (!has_below) {
        above[(*n_above)++] = *t;
        return 1;
    }
    oit_vertex poly[4];
    int n = clip_side(pl, t, side, -1, lo, hi, poly);
    if (n < 0)
        return 0;
    *n_below = oit_polygon_triangulate(poly, n, below);
    n = clip_side(pl, t, side, 1, lo, hi, poly);
    if (n < 0)
        return 0;
    *n_above = oit_polygon_triangulate(poly, n, above);
    return 1;
}
