/* Split choice for the kd subdivision (kd_split.h). */
#include "prepare/partition/kd_split.h"

#include <math.h>
#include <stdlib.h>

#include "base/sort.h"

/* One try at a two-cell grid of half-width w whose inner boundary is pos. */
static int cells_with(const float lo[3], const float hi[3], int axis, float pos, float w,
                      float origin[3], float cell_size[3])
{
    for (int k = 0; k < 3; k++) {
        origin[k] = lo[k];
        cell_size[k] = hi[k] - lo[k];
    }
    origin[axis] = pos - w;
    cell_size[axis] = w;
    volatile float plane = origin[axis] + w; /* as partfile/order.c computes it */
    return w > 0 && plane == pos && origin[axis] <= lo[axis] && plane + w >= hi[axis];
}

int oit_kd_split_cells(const float lo[3], const float hi[3], int axis, float pos,
                       float origin[3], float cell_size[3])
{
    float below = pos - lo[axis], above = hi[axis] - pos;
    float w = below > above ? below : above;
    /* pos - w rounds for most positions that are not dyadic fractions of the
     * box; a half-width a few ulps wider usually makes the sum exact again. */
    for (int i = 0; i < 32; i++, w = nextafterf(w, INFINITY))
        if (cells_with(lo, hi, axis, pos, w, origin, cell_size))
            return 1;
    return 0;
}

typedef struct split_score {
    uint32_t parts, cut, imbalance;
} split_score;

static int better(split_score a, split_score b)
{
    if (a.parts != b.parts)
        return a.parts < b.parts;
    if (a.cut != b.cut)
        return a.cut < b.cut;
    return a.imbalance < b.imbalance;
}

typedef struct event {
    float v;
    uint32_t w;
} event;

/* One axis's piece bounds, sorted, with prefix weights: pre[i] is the weight
 * of events [0, i). Flat pieces (lo == hi on the axis) are listed again in
 * flat because a plane through them sends them below; face_hi lists the
 * pieces with a triangle in their upper face (they go below a plane there),
 * face_lo the others with one in their lower face (they go above). */
typedef struct axis_events {
    event *lo, *hi, *flat, *face_hi, *face_lo;
    uint32_t *pre_lo, *pre_hi, *pre_flat;
    uint32_t n, nflat, nface_hi, nface_lo;
} axis_events;

#define EVENT_LESS(x, y) ((x)->v < (y)->v)
OIT_SORT_DEFINE(sort_events_merge_sort, event, EVENT_LESS)

/* The float's bits as an unsigned key in the float's order, -0 as +0 (they
 * compare equal, so equal keys keep their input order as in the merge sort). */
static uint32_t event_key(float v)
{
    union { float f; uint32_t u; } b = {v == 0 ? 0.0f : v};
    return b.u >> 31 ? ~b.u : b.u | 0x80000000u;
}

/* A stable LSD radix sort, 4 passes of 8 bits: the same order as the merge
 * sort (stable, same key), in linear time. The fast scheme sorts every
 * node's triangle bounds on three axes, millions of events at the top of a
 * cell, where the merge sort took a quarter of a conversion. */
static void sort_events(event *a, size_t n)
{
    event *t = n > 256 ? malloc(n * sizeof *t) : NULL;
    if (!t) {
        sort_events_merge_sort(a, n);
        return;
    }
    event *src = a, *dst = t;
    for (int shift = 0; shift < 32; shift += 8) {
        size_t count[257] = {0};
        for (size_t i = 0; i < n; i++)
            count[(event_key(src[i].v) >> shift & 0xffu) + 1]++;
        if (count[(event_key(src[0].v) >> shift & 0xffu) + 1] == n)
            continue; /* every key has this byte: the pass would copy */
        for (int b = 0; b < 256; b++)
            count[b + 1] += count[b];
        for (size_t i = 0; i < n; i++)
            dst[count[event_key(src[i].v) >> shift & 0xffu]++] = src[i];
        event *x = src;
        src = dst;
        dst = x;
    }
    if (src != a)
        for (size_t i = 0; i < n; i++)
            a[i] = src[i];
    free(t);
}

/* Positions in the sorted event arrays for a non-decreasing sequence of
 * planes m: each index only moves forward, so scoring all of a node's
 * candidates costs one pass over its events rather than a binary search
 * per array per candidate. */
typedef struct cursor {
    uint32_t lo_ge, lo_gt, hi_ge, hi_gt, flat_ge, flat_gt, fhi_ge, fhi_gt, flo_ge, flo_gt;
} cursor;

/* Advances *ge to the first event with v >= m and *gt to the first v > m. */
static void advance(const event *e, uint32_t n, float m, uint32_t *ge, uint32_t *gt)
{
    while (*ge < n && e[*ge].v < m)
        (*ge)++;
    if (*gt < *ge)
        *gt = *ge;
    while (*gt < n && e[*gt].v <= m)
        (*gt)++;
}

static void prefix(const event *e, uint32_t n, uint32_t *pre)
{
    pre[0] = 0;
    for (uint32_t i = 0; i < n; i++)
        pre[i + 1] = pre[i] + e[i].w;
}

/* Room for count pieces, shared by the three axes of one choice. */
static int events_alloc(uint32_t count, axis_events *ev)
{
    ev->lo = malloc(5 * (size_t)count * sizeof *ev->lo + 1);
    ev->pre_lo = malloc(3 * ((size_t)count + 1) * sizeof *ev->pre_lo);
    if (!ev->lo || !ev->pre_lo)
        return 0;
    ev->hi = ev->lo + count;
    ev->flat = ev->hi + count;
    ev->face_hi = ev->flat + count;
    ev->face_lo = ev->face_hi + count;
    ev->pre_hi = ev->pre_lo + count + 1;
    ev->pre_flat = ev->pre_hi + count + 1;
    ev->n = count;
    return 1;
}

static void events_fill(const oit_kd_piece_box *pieces, uint32_t count, int axis,
                        axis_events *ev)
{
    ev->nflat = ev->nface_hi = ev->nface_lo = 0;
    for (uint32_t i = 0; i < count; i++) {
        const oit_kd_piece_box *p = &pieces[i];
        ev->lo[i] = (event){p->lo[axis], p->weight};
        ev->hi[i] = (event){p->hi[axis], p->weight};
        if (p->lo[axis] == p->hi[axis])
            ev->flat[ev->nflat++] = ev->lo[i];
        if (p->face_hi >> axis & 1)
            ev->face_hi[ev->nface_hi++] = ev->hi[i];
        if ((p->face_lo >> axis & 1) && p->lo[axis] < p->hi[axis])
            ev->face_lo[ev->nface_lo++] = ev->lo[i];
    }
    sort_events(ev->lo, count);
    sort_events(ev->hi, count);
    sort_events(ev->flat, ev->nflat);
    sort_events(ev->face_hi, ev->nface_hi);
    sort_events(ev->face_lo, ev->nface_lo);
    prefix(ev->lo, count, ev->pre_lo);
    prefix(ev->hi, count, ev->pre_hi);
    prefix(ev->flat, ev->nflat, ev->pre_flat);
}

static void events_free(axis_events *ev)
{
    free(ev->lo);
    free(ev->pre_lo);
}

/* The weights each side of a plane at m, by the rule of kd_split.h: a piece
 * goes below when it starts below m or ends on it, above when it ends above;
 * and whether a piece with a triangle in its upper face and another with one
 * in its lower face meet at m (kd_split.h: their faces may coincide). */
static int sides(const axis_events *ev, cursor *c, float m, uint32_t total, uint32_t *below,
                 uint32_t *above, uint32_t *cut)
{
    advance(ev->lo, ev->n, m, &c->lo_ge, &c->lo_gt);
    advance(ev->hi, ev->n, m, &c->hi_ge, &c->hi_gt);
    advance(ev->flat, ev->nflat, m, &c->flat_ge, &c->flat_gt);
    advance(ev->face_hi, ev->nface_hi, m, &c->fhi_ge, &c->fhi_gt);
    advance(ev->face_lo, ev->nface_lo, m, &c->flo_ge, &c->flo_gt);
    uint32_t starts_below = ev->pre_lo[c->lo_ge], ends_by = ev->pre_hi[c->hi_gt];
    uint32_t flat_on = ev->pre_flat[c->flat_gt] - ev->pre_flat[c->flat_ge];
    *below = starts_below + flat_on;
    *above = total - ends_by;
    *cut = starts_below + flat_on - ends_by;
    return c->fhi_gt > c->fhi_ge && c->flo_gt > c->flo_ge;
}

static int score(const axis_events *ev, cursor *c, float m, uint32_t max_layers, uint32_t total,
                 split_score *out)
{
    uint32_t below, above, cut;
    if (sides(ev, c, m, total, &below, &above, &cut))
        return 0; /* touching faces */
    uint32_t larger = below > above ? below : above;
    if (larger >= total)
        return 0;
    /* Big nodes split near the middle: peeling one part at a time would
     * make the tree (and the sets held along its path) as deep as the node
     * has parts. */
    if (total > 4 * max_layers && larger > total - total / 4)
        return 0;
    out->parts = (below + max_layers - 1) / max_layers + (above + max_layers - 1) / max_layers;
    out->cut = cut;
    out->imbalance = larger - (below + above - larger);
    return 1;
}

typedef struct split_best {
    int found, axis;
    float pos;
    split_score s;
} split_best;

/* c: the cursor of the candidate sequence m belongs to (non-decreasing). */
static void consider(const axis_events *ev, cursor *c, const float lo[3], const float hi[3],
                     int axis, float m, uint32_t max_layers, uint32_t total, split_best *best)
{
    float origin[3], cell[3];
    split_score s;
    if (!(m > lo[axis] && m < hi[axis]) || !score(ev, c, m, max_layers, total, &s) ||
        (best->found && !better(s, best->s)) ||
        !oit_kd_split_cells(lo, hi, axis, m, origin, cell))
        return;
    *best = (split_best){1, axis, m, s};
}

int oit_kd_choose_split(const oit_kd_piece_box *pieces, uint32_t count, const float lo[3],
                        const float hi[3], uint32_t max_layers, int *axis, float *pos)
{
    uint32_t total = 0;
    for (uint32_t i = 0; i < count; i++)
        total += pieces[i].weight;
    split_best best = {0};
    axis_events ev;
    if (!events_alloc(count, &ev)) {
        events_free(&ev);
        return -1;
    }
    for (int a = 0; a < 3; a++) {
        events_fill(pieces, count, a, &ev);
        cursor dyadic = {0}, at_lo = {0}, at_hi = {0};
        for (int j = 1; j < 16; j++) {
            double md = (double)lo[a] + ((double)hi[a] - lo[a]) * j / 16.0;
            if ((double)(float)md == md)
                consider(&ev, &dyadic, lo, hi, a, (float)md, max_layers, total, &best);
        }
        /* Planes through the pieces' own bounds cut nothing that ends or
         * starts there: in CAD models (beams, pipes, boxes on a lattice)
         * they slip between objects where the dyadic planes cut through. */
        for (uint32_t i = 0; i < count; i++) {
            if (i == 0 || ev.lo[i].v != ev.lo[i - 1].v)
                consider(&ev, &at_lo, lo, hi, a, ev.lo[i].v, max_layers, total, &best);
            if (i == 0 || ev.hi[i].v != ev.hi[i - 1].v)
                consider(&ev, &at_hi, lo, hi, a, ev.hi[i].v, max_layers, total, &best);
        }
    }
    events_free(&ev);
    if (best.found) {
        *axis = best.axis;
        *pos = best.pos;
    }
    return best.found;
}
