/* The checks that read the parts rather than cast rays
 * (verify_internal.h): (3) slab sides, exactly, (4) source triangles.
 * Apart from the ray checks as whole-file passes over part data. */
#include "prepare/convert/verify_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prepare/partition/plane_exact.h"

/* Vertices of part p outside lo <= n.x <= hi (slab i's planes), judged
 * exactly: a cutting plane's seam vertices lie on it to the last bit. */
static oit_status count_outside(verifier *v, uint32_t i, uint32_t p, double lo, double hi,
                                oit_error *err)
{
    const float *n = oit_partfile_slab_at(v->pf, i)->normal;
    oit_partfile_part_view pv;
    oit_status s = oit_partfile_part_data(v->pf, p, &v->decoded, &pv, err);
    uint32_t nv = s ? 0 : oit_partfile_parts(v->pf)[p].vertex_count;
    for (uint32_t k = 0; k < nv; k++) {
        float q[3];
        memcpy(q, (const char *)pv.positions + (size_t)k * pv.stride, sizeof q);
        double x = (double)n[0] * q[0] + (double)n[1] * q[1] + (double)n[2] * q[2];
        if ((lo > -INFINITY && oit_plane_side_exact(n, lo, q) < 0) ||
            (hi < INFINITY && oit_plane_side_exact(n, hi, q) > 0)) {
            oit_verify_note(v, "a vertex at n.x = %.9g, outside %.9g..%.9g (slab %u, part %u)", x,
                            lo, hi, i, p);
            v->rep->slab_violations++;
        }
    }
    return s;
}

/* A part to check against a slab's planes. */
typedef struct slab_side {
    uint32_t part, slab;
    double lo, hi;
} slab_side;

static int side_cmp(const void *a, const void *b)
{
    const slab_side *x = a, *y = b;
    if (x->part != y->part)
        return x->part < y->part ? -1 : 1;
    return (x->slab > y->slab) - (x->slab < y->slab);
}

/* Checked in file order, the pages read dropped every 64 MiB of file: a
 * fault maps its neighbours too, so slab parts spread over a 1.3 GB file
 * held 770 MB when checked slab by slab. */
oit_status oit_verify_check_slabs(verifier *v, oit_error *err)
{
    uint32_t ns = oit_partfile_slab_count(v->pf);
    v->rep->slabs = ns;
    size_t n = 0, cap = 0;
    slab_side *list = NULL;
    for (uint32_t i = 0; i < ns; i++) {
        const oit_partfile_slab *sl = oit_partfile_slab_at(v->pf, i);
        uint32_t m = 0;
        const uint32_t *in = oit_partfile_slab_inside(v->pf, i, &m);
        if (n + m + 2 > cap) {
            cap = 2 * (n + m + 2);
            slab_side *p = realloc(list, cap * sizeof *p);
            if (!p) {
                free(list);
                return oit_error_set(err, OIT_ERR_NOMEM, "%s: slab check: out of memory",
                                     oit_partfile_name(v->pf));
            }
            list = p;
        }
        list[n++] = (slab_side){sl->part_below, i, -INFINITY, sl->d0};
        list[n++] = (slab_side){sl->part_above, i, sl->d1, INFINITY};
        for (uint32_t k = 0; k < m; k++)
            list[n++] = (slab_side){in[k], i, sl->d0, sl->d1};
    }
    if (n > 1)
        qsort(list, n, sizeof *list, side_cmp);
    oit_status s = OIT_OK;
    const oit_partfile_part *parts = oit_partfile_parts(v->pf);
    uint32_t drop_from = 0;
    for (size_t k = 0; k < n && !s; k++) {
        uint32_t p = list[k].part;
        s = count_outside(v, list[k].slab, p, list[k].lo, list[k].hi, err);
        /* By the span of file passed, not the bytes read: fault-around maps
         * the pages between the parts read too. */
        if (parts[p].data_offset - parts[drop_from].data_offset >= ((uint64_t)64 << 20) ||
            k + 1 == n) {
            oit_partfile_drop_part_data(v->pf, drop_from, p + 1 - drop_from);
            drop_from = p + 1 < v->nparts ? p + 1 : p;
        }
    }
    free(list);
    return s;
}

/* Check (4): the distinct source indices of all parts, in a bitmap of
 * triangles_in bits, against the triangles the converter kept. */
oit_status oit_verify_check_sources(verifier *v, oit_error *err)
{
    oit_partfile_summary sum;
    oit_partfile_get_summary(v->pf, &sum);
    uint64_t words = sum.triangles_in / 64 + 1;
    uint64_t *seen = words <= SIZE_MAX / 8 ? calloc((size_t)words, 8) : NULL;
    if (!seen)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: source index map of %llu triangles: out "
                             "of memory", oit_partfile_name(v->pf),
                             (unsigned long long)sum.triangles_in);
    uint64_t found = 0;
    for (uint32_t p = 0; p < v->nparts; p++) {
        oit_partfile_part_view pv;
        oit_status s = oit_partfile_part_data(v->pf, p, &v->decoded, &pv, err);
        if (s) {
            free(seen);
            return s;
        }
        for (uint64_t t = 0; t < pv.index_count / 3; t++) {
            uint32_t i = oit_partfile_source(&pv, t); /* < triangles_in: validated */
            uint64_t bit = 1ull << (i % 64);
            found += !(seen[i / 64] & bit);
            seen[i / 64] |= bit;
        }
        oit_partfile_drop_part_data(v->pf, p, 1);
    }
    free(seen);
    v->rep->sources_kept = sum.triangles_in - sum.triangles_dropped;
    v->rep->sources_found = found;
    v->rep->sources_lost = found < v->rep->sources_kept ? v->rep->sources_kept - found : 0;
    if (v->rep->sources_lost && !v->rep->first_violation[0])
        snprintf(v->rep->first_violation, sizeof v->rep->first_violation,
                 "%llu of the %llu source triangles kept are in no part",
                 (unsigned long long)v->rep->sources_lost,
                 (unsigned long long)v->rep->sources_kept);
    return OIT_OK;
}

