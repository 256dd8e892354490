/* What a node weighs (kd_internal.h): its layer bound and its trial
 * splits', counted with per-piece stamps, its pieces' boxes, and the
 * midplane fallback. Apart as the counting every decision of the build
 * (kd.c, kd_slab_leaf.c) reads, none of which it makes. */
#include "prepare/partition/kd_internal.h"

#include <math.h>
#include <stdlib.h>

/* A piece contributes one layer while everything of it in the node lies in
 * one plane (a line crosses a plane once; shared edges rasterize once) and
 * two once it has two planes (convexity). side selects the stamp set. */
static void layers_add(kd_ctx *c, uint32_t *stamp, int side, uint32_t k, uint32_t piece,
                       uint32_t plane, uint32_t *layers)
{
    if (stamp[piece] != k) {
        stamp[piece] = k;
        c->first_plane[side][piece] = plane;
        c->two_planes[side][piece] = 0;
        (*layers)++;
    } else if (!c->two_planes[side][piece] && c->first_plane[side][piece] != plane) {
        c->two_planes[side][piece] = 1;
        (*layers)++;
    }
}

/* The node's layer bound: the sum over its pieces of 1 or 2 (above). */
uint32_t oit_kd_node_layers(kd_ctx *c, const node_set *s, uint32_t *npieces)
{
    uint32_t k = ++c->stamp, layers = 0, count = 0;
    for (size_t i = 0; i < s->n; i++) {
        count += c->piece_stamp[s->piece[i]] != k;
        layers_add(c, c->piece_stamp, 0, k, s->piece[i], s->plane[i], &layers);
    }
    *npieces = count;
    return layers;
}

/* Layer bounds of the two halves of a split (upper bounds: clipped slivers
 * that round to nothing are not foreseen), per clip.h's rules. */
void oit_kd_split_layers(kd_ctx *c, const node_set *s, int axis, float m, uint32_t *below,
                         uint32_t *above)
{
    uint32_t k = ++c->stamp;
    *below = *above = 0;
    for (size_t i = 0; i < s->n; i++) {
        float mn, mx;
        oit_kd_tri_range(&s->tris[i], axis, &mn, &mx);
        if (mn < m || mx <= m)
            layers_add(c, c->piece_stamp, 0, k, s->piece[i], s->plane[i], below);
        if (mx > m)
            layers_add(c, c->above_stamp, 1, k, s->piece[i], s->plane[i], above);
    }
}

/* The node's pieces as boxes with their weights, for kd_split.h. */
oit_status oit_kd_piece_boxes(kd_ctx *c, const node_set *s, uint32_t npieces,
                              oit_kd_piece_box **out)
{
    oit_kd_piece_box *b = malloc(npieces * sizeof *b);
    if (!b)
        return OIT_ERR_NOMEM;
    uint32_t k = ++c->stamp, count = 0, unused = 0;
    for (size_t i = 0; i < s->n; i++) {
        uint32_t p = s->piece[i];
        if (c->piece_stamp[p] != k) {
            c->piece_slot[p] = count;
            b[count] = (oit_kd_piece_box){{INFINITY, INFINITY, INFINITY},
                                          {-INFINITY, -INFINITY, -INFINITY}, 0, 0, 0};
            count++;
        }
        layers_add(c, c->piece_stamp, 0, k, p, s->plane[i], &unused);
        oit_kd_piece_box *pb = &b[c->piece_slot[p]];
        pb->weight = c->two_planes[0][p] ? 2 : 1;
        for (int a = 0; a < 3; a++) {
            float mn, mx;
            oit_kd_tri_range(&s->tris[i], a, &mn, &mx);
            pb->lo[a] = oit_min_f(pb->lo[a], mn);
            pb->hi[a] = oit_max_f(pb->hi[a], mx);
        }
    }
    for (size_t i = 0; i < s->n; i++) {
        oit_kd_piece_box *pb = &b[c->piece_slot[s->piece[i]]];
        for (int a = 0; a < 3; a++) {
            float mn, mx;
            oit_kd_tri_range(&s->tris[i], a, &mn, &mx);
            pb->face_lo |= (uint8_t)((mn == mx && mn == pb->lo[a]) << a);
            pb->face_hi |= (uint8_t)((mn == mx && mx == pb->hi[a]) << a);
        }
    }
    *out = b;
    return OIT_OK;
}

/* Fallback: the midplane of the axis that most lowers the larger half. */
int oit_kd_choose_axis(kd_ctx *c, const node_set *s, const float lo[3], const float hi[3],
                       uint32_t *larger)
{
    int best = -1;
    uint32_t best_max = 0;
    float best_ext = 0;
    for (int a = 0; a < 3; a++) {
        float m = 0.5f * (lo[a] + hi[a]), origin[3], cell[3];
        if (!(m > lo[a] && m < hi[a]) || !oit_kd_split_cells(lo, hi, a, m, origin, cell))
            continue; /* the box is too thin to halve in float */
        uint32_t b, t;
        oit_kd_split_layers(c, s, a, m, &b, &t);
        uint32_t mx = b > t ? b : t;
        float ext = hi[a] - lo[a];
        if (best < 0 || mx < best_max || (mx == best_max && ext > best_ext)) {
            best = a;
            best_max = mx;
            best_ext = ext;
        }
    }
    *larger = best_max;
    return best;
}

