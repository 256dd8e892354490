/* Each ray's hits checked (verify_internal.h): (1) hits per part against
 * the layer bound, (2) the order the part file gives the ray's viewpoint.
 * Apart from the casting (verify_cast.c): these checks see sorted hits
 * only. */
#include "prepare/convert/verify_internal.h"

#include <stdlib.h>

static int cmp_hit_t(const void *a, const void *b)
{
    const vhit *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return (x->part > y->part) - (x->part < y->part);
}

/* Checks (1) hits per part against the layer bound, on hits sorted by t. A
 * ray through an edge or vertex hits every triangle there at one depth, where
 * a rasterizer's fill rule makes one fragment: hits of one part within `tie`
 * of each other count as one layer. */
static int same_layer(const verifier *v, size_t i)
{
    const vhit *h = v->line;
    for (size_t j = i; j-- > 0 && h[j].t >= h[i].t - v->tie;)
        if (h[j].part == h[i].part)
            return 1;
    return 0;
}

static void check_layers(verifier *v, const float org[3])
{
    uint32_t nt = 0;
    for (size_t i = 0; i < v->line_n; i++) {
        uint32_t p = v->line[i].part;
        if (same_layer(v, i))
            continue;
        if (v->count[p]++ == 0)
            v->touched[nt++] = p;
    }
    for (uint32_t i = 0; i < nt; i++) {
        uint32_t p = v->touched[i], c = v->count[p];
        if (c > v->rep->max_hits_per_part) {
            v->rep->max_hits_per_part = c;
            v->rep->worst_part_bound = v->bound[p];
        }
        if (c >= v->bound[p] && !v->reached[p]) {
            v->reached[p] = 1;
            v->rep->parts_at_bound++;
        }
        if (c > v->bound[p] && v->rep->measured_bounds) {
            /* A measured count is an estimate: exceeding it is a figure. */
            v->rep->bound_exceeded++;
            if (c - v->bound[p] > v->rep->most_over_bound)
                v->rep->most_over_bound = c - v->bound[p];
        } else if (c > v->bound[p]) {
            v->rep->layer_violations++;
            oit_verify_note(v, "ray from (%g %g %g): part %u gives %u hits, more than its bound",
                            org[0], org[1], org[2], p, c);
        }
        v->count[p] = 0;
    }
}

/* Checks (2): along the ray (hits sorted by t) no part comes later whose rank
 * is below that of a part met more than `tie` earlier. Hits within `tie` of
 * the eye are skipped: an eye lying on a surface sees it edge-on (no
 * fragment, and the near plane clips it), so its part has no place in the
 * order from there. */
static void check_order(verifier *v, const float org[3])
{
    const vhit *h = v->line;
    size_t n = v->line_n, j = 0;
    if (n < 2)
        return;
    while (n > 0 && h[0].t <= v->tie)
        h++, n--;
    uint32_t max_rank = 0, max_part = 0;
    int have = 0;
    for (size_t i = 0; i < n; i++) {
        for (; j < i && h[j].t < h[i].t - v->tie; j++)
            if (!have || v->rank[h[j].part] > max_rank) {
                max_rank = v->rank[h[j].part];
                max_part = h[j].part;
                have = 1;
            }
        uint32_t r = v->rank[h[i].part];
        if (r == UINT32_MAX || (have && r < max_rank)) {
            v->rep->order_violations++;
            oit_verify_note(v, "ray from (%g %g %g): part %u is met after part %u but ordered "
                               "before it", org[0], org[1], org[2], h[i].part, max_part);
            return;
        }
    }
}

static oit_status order_from(verifier *v, const float eye[3], oit_error *err)
{
    uint32_t n = 0;
    oit_status s = oit_order_compute(v->order, eye, v->ordered, &n, err);
    if (s)
        return s;
    for (uint32_t p = 0; p < v->nparts; p++)
        v->rank[p] = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++)
        v->rank[v->ordered[i]] = i;
    return OIT_OK;
}

/* Sorts the hits into one list per ray, by t, and checks each ray against
 * the order of its viewpoint. */
oit_status oit_verify_check_rays(verifier *v, oit_error *err)
{
    size_t n = v->ray.n;
    size_t *first = calloc((size_t)v->nrays + 1, sizeof *first);
    vhit *sorted = malloc((n ? n : 1) * sizeof *sorted);
    if (!first || !sorted) {
        free(first);
        free(sorted);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %zu ray hits: out of memory",
                             oit_partfile_name(v->pf), n);
    }
    for (size_t i = 0; i < n; i++)
        first[v->ray.hits[i].ray + 1]++;
    for (uint32_t r = 0; r < v->nrays; r++)
        first[r + 1] += first[r];
    for (size_t i = 0; i < n; i++)
        sorted[first[v->ray.hits[i].ray]++] = v->ray.hits[i].h;
    for (uint32_t r = v->nrays; r > 0; r--)
        first[r] = first[r - 1];
    first[0] = 0;
    free(v->ray.hits);
    v->ray.hits = NULL;
    oit_status s = OIT_OK;
    uint32_t view = UINT32_MAX;
    for (uint32_t r = 0; r < v->nrays && !s; r++) {
        if (v->rays[r].view != view) {
            view = v->rays[r].view;
            s = order_from(v, v->eyes[view], err);
            if (s)
                break;
        }
        v->line = sorted + first[r];
        v->line_n = first[r + 1] - first[r];
        if (v->line_n > 1)
            qsort(v->line, v->line_n, sizeof *v->line, cmp_hit_t);
        v->rep->rays++;
        v->rep->hits += v->line_n;
        v->rep->rays_hitting += v->line_n > 0;
        check_layers(v, v->rays[r].org);
        check_order(v, v->rays[r].org);
    }
    v->line = NULL;
    free(first);
    free(sorted);
    return s;
}

