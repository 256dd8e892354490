/* Per-cell partition (cell.h). */
#include "prepare/convert/cell.h"

#include <stdlib.h>

#include "base/grow.h"
#include "prepare/partition/clip.h"
#include "prepare/partition/convex.h"
#include "prepare/partition/kd_fast.h"

static int flat_on_shared_face(const oit_cell_params *p, const oit_triangle *t)
{
    for (int k = 0; k < 3; k++)
        if (p->lo_shared[k] && t->v[0].pos[k] == p->lo[k] && t->v[1].pos[k] == p->lo[k] &&
            t->v[2].pos[k] == p->lo[k])
            return 1;
    return 0;
}

/* The pieces of tris inside the cell, each with its triangle's source
 * index. */
static oit_status clip_to_cell(const oit_cell_params *p, const oit_triangle *tris,
                               const uint32_t *src, size_t n, oit_triangle **out,
                               uint32_t **out_src, size_t *count, oit_error *err)
{
    size_t cap = n + n / 4 + 16, m = 0;
    oit_triangle *o = malloc(cap * sizeof *o);
    uint32_t *os = malloc(cap * sizeof *os);
    for (size_t i = 0; i < n && o && os; i++) {
        if (m + OIT_CLIP_MAX_TRIS > cap) {
            cap *= 2;
            int ok = 1;
            o = oit_grow(o, cap, sizeof *o, &ok);
            os = oit_grow(os, cap, sizeof *os, &ok);
            if (!ok) {
                free(o);
                o = NULL;
                break;
            }
        }
        int k = oit_clip_triangle_box(&tris[i], p->lo, p->hi, o + m);
        size_t w = m;
        for (int j = 0; j < k; j++)
            if (!flat_on_shared_face(p, &o[m + j])) {
                os[w] = src[i];
                o[w++] = o[m + j];
            }
        m = w;
    }
    if (!o || !os) {
        free(o);
        free(os);
        return oit_error_set(err, OIT_ERR_NOMEM, "cell clip of %zu triangles: out of memory", n);
    }
    *out = o;
    *out_src = os;
    *count = m;
    return OIT_OK;
}

oit_status oit_cell_partition(const oit_cell_params *p, const oit_triangle *tris,
                              const uint32_t *src, size_t n, oit_kd_result *out,
                              oit_cell_counts *counts, oit_error *err)
{
    oit_triangle *clipped = NULL;
    uint32_t *clipped_src = NULL;
    size_t m = 0;
    oit_status s = clip_to_cell(p, tris, src, n, &clipped, &clipped_src, &m, err);
    if (s)
        return s;
    if (p->fast_part_triangles) {
        oit_kd_fast_params fp = {p->fast_part_triangles, p->K, p->max_depth,
                                 (uint64_t)OIT_CELL_MAX_GROWTH * m + (1u << 20)};
        s = oit_kd_build_fast(p->lo, p->hi, clipped, clipped_src, m, &fp, out, err);
        counts->clipped = m;
        counts->pieces_cell = 0;
        free(clipped);
        free(clipped_src);
        return s;
    }
    oit_convex_params cp = {p->max_piece_triangles};
    oit_convex_result cr = {0};
    s = oit_convex_cluster(clipped, m, &cp, &cr, err);
    if (!s) {
        oit_kd_params kp = {p->K, p->max_depth, (uint64_t)OIT_CELL_MAX_GROWTH * m + (1u << 20),
                            p->slabs};
        s = oit_kd_build(p->lo, p->hi, clipped, clipped_src, m, cr.piece_of, cr.plane_of,
                         cr.piece_count, &kp, out, err);
        counts->clipped = m;
        counts->pieces_cell = cr.piece_count;
    }
    oit_convex_result_free(&cr);
    free(clipped);
    free(clipped_src);
    return s;
}
