/* Separating slabs for kd nodes (kd_slab.h). */
#include "prepare/partition/kd_slab.h"
#include "base/minmax.h"
#include "base/sort.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>


/* Directions times vertices per node: a dense node tries fewer directions
 * (fixed ones first) rather than stall the cell. */
#define WORK_BUDGET (1u << 24)

typedef struct span {
    double lo, hi;
    uint32_t slot;
} span;

/* The axis, face-diagonal and body-diagonal directions. */
static const int8_t fixed[13][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 0},  {1, -1, 0},
                                    {1, 0, 1},  {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                    {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};

typedef struct dir_set {
    float (*d)[3];
    uint32_t count, cap;
} dir_set;

static void add_dir(dir_set *s, double x, double y, double z)
{
    double len = sqrt(x * x + y * y + z * z);
    if (!(len > 0) || s->count == s->cap)
        return;
    float *d = s->d[s->count++];
    d[0] = (float)(x / len);
    d[1] = (float)(y / len);
    d[2] = (float)(z / len);
}

static double dotd(const float n[3], const float p[3])
{
    return (double)n[0] * p[0] + (double)n[1] * p[1] + (double)n[2] * p[2];
}

#define SPAN_LESS(x, y) ((x)->lo < (y)->lo)
OIT_SORT_DEFINE(sort_spans, span, SPAN_LESS)

static float round_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

static float round_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

/* The fixed directions, then the line between every two groups' box
 * centres (box[group]), then the normals of a piece's first
 * OIT_KD_SLAB_PLANES_PER_PIECE non-degenerate triangles (not deduplicated:
 * a box's repeat, which only costs a direction tried twice). */
static void candidate_dirs(dir_set *ds, const oit_triangle *tris, size_t n, const uint32_t *slot,
                           uint32_t np, uint32_t ng, const float (*box)[2][3], uint32_t *taken)
{
    for (int i = 0; i < 13; i++)
        add_dir(ds, fixed[i][0], fixed[i][1], fixed[i][2]);
    for (uint32_t a = 0; a < ng; a++)
        for (uint32_t b = a + 1; b < ng; b++) {
            double c[3];
            for (int k = 0; k < 3; k++)
                c[k] = 0.5 * ((double)box[b][0][k] + box[b][1][k] - box[a][0][k] - box[a][1][k]);
            add_dir(ds, c[0], c[1], c[2]);
        }
    memset(taken, 0, np * sizeof *taken);
    for (size_t i = 0; i < n; i++) {
        uint32_t p = slot[i];
        if (taken[p] >= OIT_KD_SLAB_PLANES_PER_PIECE)
            continue;
        const float *a = tris[i].v[0].pos, *b = tris[i].v[1].pos, *c = tris[i].v[2].pos;
        double u[3], v[3];
        for (int k = 0; k < 3; k++) {
            u[k] = (double)b[k] - a[k];
            v[k] = (double)c[k] - a[k];
        }
        uint32_t before = ds->count;
        add_dir(ds, u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0]);
        taken[p] += ds->count > before;
    }
}

typedef struct best_slab {
    double score;
    uint32_t split; /* spans below: the first split of the sorted order */
} best_slab;

/* The widest valid gap along one direction; fills *out and the sorted spans
 * when it beats best->score. */
static int sweep(span *sp, uint32_t np, const uint32_t *weight, uint32_t total, uint32_t K,
                 double margin, double extent, best_slab *best, oit_kd_slab *out)
{
    sort_spans(sp, np);
    double maxhi = -INFINITY;
    uint32_t below = 0;
    int improved = 0;
    for (uint32_t k = 1; k < np; k++) {
        maxhi = oit_max_d(maxhi, sp[k - 1].hi);
        below += weight[sp[k - 1].slot];
        if (below > K || total - below > K)
            continue;
        float d0 = round_up(maxhi + margin), d1 = round_down(sp[k].lo - margin);
        double score = (sp[k].lo - maxhi) / extent;
        if (d0 <= d1 && score > best->score) {
            best->score = score;
            best->split = k;
            out->d0 = d0;
            out->d1 = d1;
            improved = 1;
        }
    }
    return improved;
}

typedef struct corner {
    float p[3];
    uint32_t slot;
} corner;

static int corner_cmp(const void *a, const void *b)
{
    const corner *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->p[k] != y->p[k])
            return x->p[k] < y->p[k] ? -1 : 1;
    return 0;
}

#define CORNER_LESS(x, y) (corner_cmp((x), (y)) < 0)
OIT_SORT_DEFINE(sort_corners, corner, CORNER_LESS)

static uint32_t find_root(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

/* Pieces that share a vertex cannot be separated by a gap, so they travel
 * together: groups are the connected components of "shares a vertex". The
 * corners are sorted and deduplicated (a closed mesh repeats each vertex
 * about six times), each tagged with its group in .slot; comp[slot] is the
 * piece's group. Returns the group count. */
static uint32_t group_pieces(corner *c, size_t *nc, uint32_t np, uint32_t *comp)
{
    sort_corners(c, *nc);
    for (uint32_t p = 0; p < np; p++)
        comp[p] = p;
    for (size_t i = 1; i < *nc; i++)
        if (!corner_cmp(&c[i - 1], &c[i])) {
            uint32_t a = find_root(comp, c[i - 1].slot), b = find_root(comp, c[i].slot);
            comp[a > b ? a : b] = a < b ? a : b;
        }
    for (uint32_t p = 0; p < np; p++)
        comp[p] = find_root(comp, p);
    /* A root is its group's smallest slot, so it is renumbered before the
     * rest of its group reads it. */
    uint32_t groups = 0;
    for (uint32_t p = 0; p < np; p++)
        comp[p] = comp[p] == p ? groups++ : comp[comp[p]];
    size_t m = 0;
    for (size_t i = 0; i < *nc; i++)
        if (!m || corner_cmp(&c[m - 1], &c[i])) {
            c[m] = c[i];
            c[m++].slot = comp[c[i].slot];
        }
    *nc = m;
    return groups;
}

typedef struct slab_work {
    corner *c;
    uint32_t *sup; /* per group, the corners extreme along +-fixed[i] */
    double *ext;   /* their projections */
    uint32_t *comp, *weight, *taken;
    float (*box)[2][3];
    span *sp, *keep;
    dir_set ds;
} slab_work;

static void work_free(slab_work *w)
{
    free(w->c), free(w->sup), free(w->ext), free(w->comp), free(w->weight);
    free(w->taken), free(w->box), free(w->sp), free(w->keep), free(w->ds.d);
}

static int work_alloc(slab_work *w, size_t n, uint32_t np)
{
    uint32_t cap = 13 + np * (np - 1) / 2 + np * OIT_KD_SLAB_PLANES_PER_PIECE;
    w->c = malloc(3 * n * sizeof *w->c);
    w->sup = malloc((size_t)np * 26 * sizeof *w->sup);
    w->ext = malloc((size_t)np * 26 * sizeof *w->ext);
    w->comp = malloc(np * sizeof *w->comp);
    w->weight = calloc(np, sizeof *w->weight);
    w->taken = malloc(np * sizeof *w->taken);
    w->box = malloc(np * sizeof *w->box);
    w->sp = malloc(np * sizeof *w->sp);
    w->keep = malloc(np * sizeof *w->keep);
    w->ds = (dir_set){malloc(cap * sizeof *w->ds.d), 0, cap};
    return w->c && w->sup && w->ext && w->comp && w->weight && w->taken && w->box && w->sp &&
           w->keep && w->ds.d;
}

/* Group boxes, the largest |x|+|y|+|z| (for the rounding margin) and the
 * node's largest extent. */
static void group_boxes(slab_work *w, size_t nc, uint32_t ng, double *scale, double *extent)
{
    for (uint32_t g = 0; g < ng; g++)
        for (int k = 0; k < 3; k++) {
            w->box[g][0][k] = INFINITY;
            w->box[g][1][k] = -INFINITY;
        }
    *scale = 0;
    for (size_t i = 0; i < nc; i++) {
        const float *q = w->c[i].p;
        *scale = oit_max_d(*scale, fabs(q[0]) + fabs(q[1]) + fabs(q[2]));
        for (int k = 0; k < 3; k++) {
            w->box[w->c[i].slot][0][k] = oit_min_f(w->box[w->c[i].slot][0][k], q[k]);
            w->box[w->c[i].slot][1][k] = oit_max_f(w->box[w->c[i].slot][1][k], q[k]);
        }
    }
    *extent = 0;
    for (int k = 0; k < 3; k++) {
        float lo = INFINITY, hi = -INFINITY;
        for (uint32_t g = 0; g < ng; g++) {
            lo = oit_min_f(lo, w->box[g][0][k]);
            hi = oit_max_f(hi, w->box[g][1][k]);
        }
        *extent = oit_max_d(*extent, (double)hi - lo);
    }
}

/* Each group's corners extreme along the fixed directions: their spans lie
 * inside the group's true span along any direction, so a direction whose
 * spans from these alone cannot beat the best gap so far is skipped
 * without touching every corner. */
static void find_support(slab_work *w, size_t nc, uint32_t ng)
{
    double *ext = w->ext;
    for (size_t j = 0; j < (size_t)ng * 26; j++)
        ext[j] = -INFINITY;
    for (size_t i = 0; i < nc; i++) {
        const float *q = w->c[i].p;
        size_t g = w->c[i].slot;
        for (int d = 0; d < 13; d++) {
            double x = fixed[d][0] * (double)q[0] + fixed[d][1] * (double)q[1] +
                       fixed[d][2] * (double)q[2];
            for (int sgn = 0; sgn < 2; sgn++, x = -x)
                if (x > ext[g * 26 + 2 * d + sgn]) {
                    ext[g * 26 + 2 * d + sgn] = x;
                    w->sup[g * 26 + 2 * d + sgn] = (uint32_t)i;
                }
        }
    }
}

static void spans_of(const slab_work *w, const float n[3], const uint32_t *idx, size_t count,
                     uint32_t ng, span *sp)
{
    for (uint32_t g = 0; g < ng; g++)
        sp[g] = (span){INFINITY, -INFINITY, g};
    for (size_t j = 0; j < count; j++) {
        const corner *c = &w->c[idx ? idx[j] : j];
        double x = dotd(n, c->p);
        span *s = &sp[c->slot];
        s->lo = oit_min_d(s->lo, x);
        s->hi = oit_max_d(s->hi, x);
    }
}

int oit_kd_find_slab(const oit_triangle *tris, size_t n, const uint32_t *slot,
                     const uint32_t *weight, uint32_t np, uint32_t max_layers,
                     oit_kd_slab *slab, uint8_t *side)
{
    uint32_t total = 0;
    for (uint32_t p = 0; p < np; p++)
        total += weight[p];
    if (np < 2 || total > 2 * max_layers)
        return 0;
    slab_work w = {0};
    if (!work_alloc(&w, n, np)) {
        work_free(&w);
        return -1;
    }
    size_t nc = 0;
    for (size_t i = 0; i < n; i++)
        for (int v = 0; v < 3; v++) {
            memcpy(w.c[nc].p, tris[i].v[v].pos, sizeof w.c[nc].p);
            w.c[nc++].slot = slot[i];
        }
    uint32_t ng = group_pieces(w.c, &nc, np, w.comp), heaviest = 0;
    for (uint32_t p = 0; p < np; p++)
        w.weight[w.comp[p]] += weight[p];
    for (uint32_t g = 0; g < ng; g++)
        heaviest = w.weight[g] > heaviest ? w.weight[g] : heaviest;
    best_slab best = {0, 0};
    if (ng >= 2 && heaviest <= max_layers) {
        double scale, extent;
        group_boxes(&w, nc, ng, &scale, &extent);
        candidate_dirs(&w.ds, tris, n, slot, np, ng, (const float(*)[2][3])w.box, w.taken);
        /* Rounding room for n.x in float anywhere in the node, so that an eye
         * that order.c places on the wrong side of a plane by rounding still
         * sees no geometry between itself and that plane. */
        double margin = 4.0 * FLT_EPSILON * scale;
        uint32_t budget = WORK_BUDGET / (uint32_t)(nc < WORK_BUDGET ? nc : WORK_BUDGET);
        find_support(&w, nc, ng);
        for (uint32_t d = 0; d < w.ds.count && d < budget && extent > 0; d++) {
            const float *nd = w.ds.d[d];
            best_slab trial = best;
            oit_kd_slab unused;
            spans_of(&w, nd, w.sup, (size_t)ng * 26, ng, w.sp);
            if (!sweep(w.sp, ng, w.weight, total, max_layers, margin, extent, &trial, &unused))
                continue;
            spans_of(&w, nd, NULL, nc, ng, w.sp);
            if (sweep(w.sp, ng, w.weight, total, max_layers, margin, extent, &best, slab)) {
                memcpy(slab->normal, nd, sizeof slab->normal);
                memcpy(w.keep, w.sp, ng * sizeof *w.keep);
            }
        }
    }
    if (best.split) {
        for (uint32_t k = 0; k < ng; k++)
            w.taken[w.keep[k].slot] = k >= best.split; /* per group now */
        for (uint32_t p = 0; p < np; p++)
            side[p] = (uint8_t)w.taken[w.comp[p]];
    }
    work_free(&w);
    return best.split != 0;
}
