/* The top grid's phase of fewest crossed triangles (grid_phase.h). */
#include "prepare/convert/grid_phase.h"

#include <math.h>
#include <string.h>

#include "base/minmax.h"

void oit_grid_phase_init(oit_grid_phase *p, const oit_bin_grid *g)
{
    memset(p, 0, sizeof *p);
    p->cell = g->cell;
    for (int k = 0; k < 3; k++)
        p->base[k] = floor(g->origin[k] / p->cell) * p->cell;
}

/* Phases b with lo < base + (b / N + i) cell < hi for some integer i: the
 * open interval (u, w) in phase units, wrapped onto [0, N). */
static void add_interval(oit_grid_phase *p, int k, double lo, double hi)
{
    const double n = OIT_GRID_PHASES;
    double u = (lo - p->base[k]) / p->cell * n, w = (hi - p->base[k]) / p->cell * n;
    if (w - u >= n)
        return; /* crosses a face at every phase: it weighs on no choice */
    double b0 = floor(u) + 1, b1 = ceil(w) - 1;
    if (b0 > b1)
        return; /* no phase strictly inside: nothing crosses it */
    double shift = floor(b0 / n) * n;
    long s = (long)(b0 - shift), e = (long)(b1 - shift); /* s in [0, N), e < s + N */
    if (e < OIT_GRID_PHASES) {
        p->diff[k][s]++;
        p->diff[k][e + 1]--;
    } else {
        p->diff[k][s]++;
        p->diff[k][OIT_GRID_PHASES]--;
        p->diff[k][0]++;
        p->diff[k][e - OIT_GRID_PHASES + 1]--;
    }
}

void oit_grid_phase_add(oit_grid_phase *p, const oit_triangle *t, size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const float *a = t[i].v[0].pos, *b = t[i].v[1].pos, *c = t[i].v[2].pos;
            float lo = oit_min_f(oit_min_f(a[k], b[k]), c[k]);
            float hi = oit_max_f(oit_max_f(a[k], b[k]), c[k]);
            if (lo < hi)
                add_interval(p, k, lo, hi);
        }
}

/* The grid along axis k at phase b: the last face at or below mn, and the
 * cells from there to past mx. */
static void axis_at(const oit_grid_phase *p, int k, int b, float mn, float mx, float *origin,
                    uint32_t *dims)
{
    double o = p->base[k] + b * (p->cell / OIT_GRID_PHASES);
    o -= ceil((o - mn) / p->cell) * p->cell; /* the face at or below mn */
    *origin = (float)o;
    *dims = (uint32_t)floor((mx - o) / p->cell) + 1;
}

void oit_grid_phase_apply(const oit_grid_phase *p, const float mn[3], const float mx[3],
                          oit_bin_grid *g)
{
    for (int k = 0; k < 3; k++) {
        int64_t run = 0, best = -1;
        int best_b = 0;
        uint32_t best_dims = 0;
        for (int b = 0; b < OIT_GRID_PHASES; b++) {
            run += p->diff[k][b];
            float o;
            uint32_t d;
            axis_at(p, k, b, mn[k], mx[k], &o, &d);
            /* A single cell crosses nothing inside the model: faces outside
             * [mn, mx] are counted by the periodic sum, so score it as 0. */
            int64_t score = d == 1 ? 0 : run;
            if (best < 0 || score < best || (score == best && d < best_dims)) {
                best = score;
                best_b = b;
                best_dims = d;
            }
        }
        axis_at(p, k, best_b, mn[k], mx[k], &g->origin[k], &g->dims[k]);
    }
}
