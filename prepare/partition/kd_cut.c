/* Cutting planes for kd nodes (kd_cut.h). */
#include "prepare/partition/kd_cut.h"
#include "base/sort.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Primitive integer vectors with components in [-2, 2], first non-zero
 * component positive: each plane direction once. */
static int cut_dirs(int (*dirs)[3])
{
    int count = 0;
    for (int a = -2; a <= 2; a++)
        for (int b = -2; b <= 2; b++)
            for (int c = -2; c <= 2; c++) {
                int first = a ? a : b ? b : c;
                int even = a % 2 == 0 && b % 2 == 0 && c % 2 == 0;
                if (first <= 0 || even)
                    continue;
                dirs[count][0] = a;
                dirs[count][1] = b;
                dirs[count][2] = c;
                count++;
            }
    return count;
}

typedef struct weighted {
    double at;
    uint32_t weight;
} weighted;

#define DOUBLE_LESS(x, y) (*(x) < *(y))
#define WEIGHTED_LESS(x, y) ((x)->at < (y)->at)
OIT_SORT_DEFINE(sort_doubles, double, DOUBLE_LESS)
OIT_SORT_DEFINE(sort_weighted, weighted, WEIGHTED_LESS)

typedef struct cut_work {
    float (*inner)[6][3]; /* per piece: its vertices extreme on each axis */
    double *tl, *th;   /* per triangle, in node order */
    double *tlo, *thi; /* of the triangles that may be crossed, sorted */
    double *events;
    weighted *plo, *phi;
} cut_work;

static double project(const int n[3], const float p[3])
{
    return n[0] * (double)p[0] + n[1] * (double)p[1] + n[2] * (double)p[2];
}

/* The span of n.x over which a plane leaves both halves within K: it
 * changes only at the pieces' ends. Returns 0 when there is none. */
static int feasible_span(const cut_work *w, uint32_t npieces, uint32_t total, uint32_t K,
                         double *from, double *to)
{
    uint32_t c = 0, e = 0, below = 0, ended = 0;
    *from = INFINITY;
    *to = -INFINITY;
    while (c < npieces || e < npieces) {
        int lower = e == npieces || (c < npieces && w->plo[c].at <= w->phi[e].at);
        double at = lower ? w->plo[c].at : w->phi[e].at;
        while (c < npieces && w->plo[c].at <= at)
            below += w->plo[c++].weight;
        while (e < npieces && w->phi[e].at <= at)
            ended += w->phi[e++].weight;
        double next = c < npieces ? w->plo[c].at : INFINITY;
        next = e < npieces && w->phi[e].at < next ? w->phi[e].at : next;
        uint32_t above = total - ended;
        if (below <= K && above <= K && below && above && next < INFINITY) {
            *from = at < *from ? at : *from;
            *to = next;
        }
    }
    return *from < *to;
}

/* Whether a placement may be feasible along n, judged from each piece's
 * six axis-extreme vertices: their span lies inside the piece's, so fewer
 * pieces reach either side and a direction infeasible here is infeasible.
 * (Where the narrower spans leave a side empty, the true ones put every
 * piece on the other side, more than K since total > K.) */
static int may_be_feasible(cut_work *w, const int n[3], const uint32_t *weight,
                           uint32_t npieces, uint32_t total, uint32_t K)
{
    for (uint32_t p = 0; p < npieces; p++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int v = 0; v < 6; v++) {
            double x = project(n, w->inner[p][v]);
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        w->plo[p] = (weighted){lo, weight[p]};
        w->phi[p] = (weighted){hi, weight[p]};
    }
    sort_weighted(w->plo, npieces);
    sort_weighted(w->phi, npieces);
    double from, to;
    return feasible_span(w, npieces, total, K, &from, &to);
}

/* Returns 0 (no prefilter) when memory runs out. */
static int inner_points(cut_work *w, const oit_triangle *tris, size_t count,
                        const uint32_t *slot, uint32_t npieces)
{
    uint8_t *seen = calloc(npieces, 1);
    if (!seen)
        return 0;
    for (size_t i = 0; i < count; i++)
        for (int v = 0; v < 3; v++) {
            const float *q = tris[i].v[v].pos;
            float (*in)[3] = w->inner[slot[i]];
            for (int a = 0; a < 3; a++) {
                if (!seen[slot[i]] || q[a] < in[2 * a][a])
                    memcpy(in[2 * a], q, sizeof in[0]);
                if (!seen[slot[i]] || q[a] > in[2 * a + 1][a])
                    memcpy(in[2 * a + 1], q, sizeof in[0]);
            }
            seen[slot[i]] = 1;
        }
    free(seen);
    return 1;
}

/* Projects the node along n and keeps, sorted, the ends of the triangles
 * that reach into the feasible span (no other can be crossed by a plane
 * there) together with the pieces' ends: the sweep's events. Returns the
 * number of distinct events, 0 when no placement is feasible. */
static size_t project_all(cut_work *w, const int n[3], const oit_triangle *tris, size_t count,
                          const uint32_t *slot, const uint32_t *weight, uint32_t npieces,
                          uint32_t total, uint32_t K, size_t *kept)
{
    for (uint32_t p = 0; p < npieces; p++) {
        w->plo[p] = (weighted){INFINITY, weight[p]};
        w->phi[p] = (weighted){-INFINITY, weight[p]};
    }
    for (size_t i = 0; i < count; i++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int v = 0; v < 3; v++) {
            double x = project(n, tris[i].v[v].pos);
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        w->tl[i] = lo;
        w->th[i] = hi;
        weighted *pl = &w->plo[slot[i]], *ph = &w->phi[slot[i]];
        pl->at = lo < pl->at ? lo : pl->at;
        ph->at = hi > ph->at ? hi : ph->at;
    }
    sort_weighted(w->plo, npieces);
    sort_weighted(w->phi, npieces);
    double from, to;
    if (!feasible_span(w, npieces, total, K, &from, &to))
        return 0;
    size_t m = 0;
    for (size_t i = 0; i < count; i++)
        if (w->tl[i] < to && w->th[i] > from) {
            w->tlo[m] = w->tl[i];
            w->thi[m++] = w->th[i];
        }
    *kept = m;
    for (uint32_t p = 0; p < npieces; p++) {
        w->tlo[m + p] = w->plo[p].at;
        w->thi[m + p] = w->phi[p].at;
    }
    /* Events: the kept ends and the pieces' ends, sorted and distinct. */
    size_t ne = 2 * (m + npieces);
    memcpy(w->events, w->tlo, (m + npieces) * sizeof *w->events);
    memcpy(w->events + m + npieces, w->thi, (m + npieces) * sizeof *w->events);
    sort_doubles(w->events, ne);
    sort_doubles(w->tlo, m);
    sort_doubles(w->thi, m);
    size_t d = 0;
    for (size_t i = 0; i < ne; i++)
        if (d == 0 || w->events[i] != w->events[d - 1])
            w->events[d++] = w->events[i];
    return d;
}

/* The best placement along one direction: between consecutive event values
 * e[i] < e[i+1], a plane crosses the triangles with tlo <= e[i] < thi, the
 * lower half holds the pieces with plo <= e[i], the upper one those with
 * phi > e[i]. */
static void sweep(const cut_work *w, size_t count, uint32_t npieces, size_t events,
                  uint32_t total, uint32_t K, oit_plane_exact *pl, oit_kd_cut *best,
                  int *found, uint32_t *best_spread)
{
    size_t a = 0, b = 0, c = 0, e = 0;
    uint32_t below = 0, ended = 0;
    for (size_t i = 0; i + 1 < events; i++) {
        double at = w->events[i];
        while (a < count && w->tlo[a] <= at)
            a++;
        while (b < count && w->thi[b] <= at)
            b++;
        while (c < npieces && w->plo[c].at <= at)
            below += w->plo[c++].weight;
        while (e < npieces && w->phi[e].at <= at)
            ended += w->phi[e++].weight;
        uint32_t above = total - ended, cut = (uint32_t)(a - b);
        if (below > K || above > K || below == 0 || above == 0)
            continue;
        uint32_t spread = below > above ? below - above : above - below;
        /* best->cut starts at the caller's max_cut. */
        if (cut > best->cut || (*found && cut == best->cut && spread >= *best_spread))
            continue;
        /* A grain multiple strictly inside the gap, nearest its middle. */
        double next = w->events[i + 1], g = pl->grain;
        double d = floor(0.5 * (at + next) / g) * g;
        if (d <= at)
            d += g;
        if (!(d < next))
            continue;
        pl->d = d;
        best->plane = *pl;
        best->cut = cut;
        *best_spread = spread;
        *found = 1;
    }
}

int oit_kd_find_cut(const oit_triangle *tris, size_t n, const uint32_t *slot,
                    const uint32_t *weight, uint32_t npieces, uint32_t max_layers,
                    const float lo[3], const float hi[3], uint32_t max_cut, oit_kd_cut *cut)
{
    int dirs[OIT_KD_CUT_DIRS][3];
    int ndirs = cut_dirs(dirs);
    uint32_t total = 0, spread = 0;
    for (uint32_t p = 0; p < npieces; p++)
        total += weight[p];
    if (total <= max_layers)
        return 0; /* one part already: nothing to cut */
    size_t room = n + npieces;
    cut_work w = {malloc(npieces * sizeof *w.inner), malloc(n * sizeof *w.tl),
                  malloc(n * sizeof *w.th),          malloc(room * sizeof *w.tlo),
                  malloc(room * sizeof *w.thi),      malloc(2 * room * sizeof *w.events),
                  malloc(npieces * sizeof *w.plo),   malloc(npieces * sizeof *w.phi)};
    int found = -1;
    if (w.inner && w.tl && w.th && w.tlo && w.thi && w.events && w.plo && w.phi) {
        found = 0;
        cut->cut = max_cut;
        int prefilter = inner_points(&w, tris, n, slot, npieces);
        for (int k = 0; k < ndirs; k++) {
            oit_plane_exact pl;
            oit_plane_exact_init(&pl, dirs[k], lo, hi);
            if (prefilter && !may_be_feasible(&w, dirs[k], weight, npieces, total, max_layers))
                continue;
            size_t kept = 0;
            size_t events = project_all(&w, dirs[k], tris, n, slot, weight, npieces, total,
                                        max_layers, &kept);
            sweep(&w, kept, npieces, events, total, max_layers, &pl, cut, &found, &spread);
        }
    }
    free(w.inner);
    free(w.tl);
    free(w.th);
    free(w.tlo);
    free(w.thi);
    free(w.events);
    free(w.plo);
    free(w.phi);
    return found;
}
