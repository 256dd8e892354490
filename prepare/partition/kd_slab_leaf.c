/* A node made two parts across a plane of another direction
 * (kd_internal.h): a separating slab (kd_slab.h), else a cutting plane
 * (kd_cut.h) when it crosses fewer triangles than the axis split would.
 * Apart from kd.c's recursion as the alternatives to an axis split. */
#include "prepare/partition/kd_internal.h"

#include <stdlib.h>

#include "prepare/partition/kd_cut.h"
#include "prepare/partition/plane_exact.h"

oit_status oit_kd_slab_input_make(const kd_ctx *c, const node_set *s, const oit_kd_piece_box *b,
                                  uint32_t npieces, slab_input *in)
{
    in->slot = malloc(s->n * sizeof *in->slot);
    in->weight = malloc(npieces * sizeof *in->weight);
    if (!in->slot || !in->weight)
        return OIT_ERR_NOMEM;
    for (size_t i = 0; i < s->n; i++)
        in->slot[i] = c->piece_slot[s->piece[i]];
    for (uint32_t p = 0; p < npieces; p++)
        in->weight[p] = b[p].weight;
    return OIT_OK;
}

void oit_kd_slab_input_free(slab_input *in)
{
    free(in->slot);
    free(in->weight);
}

/* The node as two parts on either side of a slab (kd_slab.h), when one
 * separates its pieces; *done tells whether it did. */
oit_status oit_kd_try_slab(kd_ctx *c, size_t node, const node_set *s, const slab_input *in,
                           uint32_t npieces, int *done)
{
    const uint32_t *slot = in->slot;
    uint8_t *side = malloc(npieces);
    node_set half[2] = {{0}, {0}};
    oit_kd_slab planes;
    oit_status st = side ? OIT_OK : OIT_ERR_NOMEM;
    int found = 0;
    if (!st) {
        found = oit_kd_find_slab(s->tris, s->n, slot, in->weight, npieces, c->p->max_layers,
                                 &planes, side);
        st = found < 0 ? OIT_ERR_NOMEM : OIT_OK;
    }
    uint32_t count[2] = {0, 0};
    for (uint32_t p = 0; found > 0 && p < npieces; p++)
        count[side[p]]++;
    for (size_t i = 0; found > 0 && !st && i < s->n; i++)
        st = oit_kd_set_push(&half[side[slot[i]]], &s->tris[i], s, i);
    if (found > 0 && !st)
        st = oit_kd_emit_slab_leaf(c, node, half, count, &planes);
    *done = found > 0 && !st;
    oit_kd_set_free(&half[0]);
    oit_kd_set_free(&half[1]);
    free(side);
    return st;
}

/* Triangles the axis plane crosses, and whether its halves stay within K
 * (then it already makes two parts, which a cut must beat on crossings). */
static uint32_t axis_crossings(kd_ctx *c, const node_set *s, int axis, float m, int *two_parts)
{
    uint32_t crossed = 0, below, above;
    for (size_t i = 0; i < s->n; i++) {
        float mn, mx;
        oit_kd_tri_range(&s->tris[i], axis, &mn, &mx);
        crossed += mn < m && mx > m;
    }
    oit_kd_split_layers(c, s, axis, m, &below, &above);
    *two_parts = below <= c->p->max_layers && above <= c->p->max_layers;
    return crossed;
}

/* The node cut by a plane of another direction into two parts (kd_cut.h),
 * when one crosses at most max_cut triangles; *done tells whether it did. */
static oit_status try_cut(kd_ctx *c, size_t node, const node_set *s, const slab_input *in,
                          uint32_t npieces, uint32_t max_cut, int *done)
{
    oit_kd_node *nd = &c->out->nodes[node];
    node_set half[2] = {{0}, {0}};
    oit_kd_cut cut;
    oit_status st = OIT_OK;
    *done = 0;
    int found = oit_kd_find_cut(s->tris, s->n, in->slot, in->weight, npieces, c->p->max_layers,
                                nd->lo, nd->hi, max_cut, &cut);
    if (found < 0)
        st = OIT_ERR_NOMEM;
    uint64_t added = 0;
    for (size_t i = 0; found > 0 && !st && i < s->n; i++) {
        oit_triangle h[2][2];
        int n[2];
        if (!oit_plane_exact_split(&cut.plane, &s->tris[i], nd->lo, nd->hi, h[0], &n[0], h[1],
                                   &n[1])) {
            found = 0; /* a seam would leave the box: let the axis split go on */
            break;
        }
        for (int side = 0; side < 2 && !st; side++)
            for (int k = 0; k < n[side] && !st; k++)
                st = oit_kd_set_push(&half[side], &h[side][k], s, i);
        added += (uint64_t)(n[0] + n[1]) - 1;
    }
    uint32_t count[2], layers[2];
    for (int h = 0; h < 2 && found > 0 && !st; h++) {
        layers[h] = oit_kd_node_layers(c, &half[h], &count[h]);
        found = count[h] && layers[h] <= c->p->max_layers;
    }
    if (found > 0 && !st) {
        oit_kd_slab planes = {{(float)cut.plane.n[0], (float)cut.plane.n[1],
                               (float)cut.plane.n[2]},
                              (float)cut.plane.d, (float)cut.plane.d};
        st = oit_kd_emit_slab_leaf(c, node, half, count, &planes);
        c->out->split_added += added;
        c->out->cuts++;
        *done = !st;
    }
    oit_kd_set_free(&half[0]);
    oit_kd_set_free(&half[1]);
    return st;
}

/* A cut replaces the axis split (found: kd_split's; else the midplane
 * fallback's) when it crosses fewer triangles, or when the axis split's
 * halves would need splitting again. */
oit_status oit_kd_try_cut_instead(kd_ctx *c, size_t node, const node_set *s,
                                  const slab_input *in, uint32_t npieces, int found, int axis,
                                  float m, int *done)
{
    const oit_kd_node *nd = &c->out->nodes[node];
    uint32_t larger, max_cut = UINT32_MAX;
    if (!found) {
        axis = oit_kd_choose_axis(c, s, nd->lo, nd->hi, &larger);
        m = axis >= 0 ? 0.5f * (nd->lo[axis] + nd->hi[axis]) : 0;
    }
    if (axis >= 0) {
        int two_parts;
        uint32_t crossed = axis_crossings(c, s, axis, m, &two_parts);
        if (two_parts)
            max_cut = crossed ? crossed - 1 : 0;
    }
    *done = 0;
    return max_cut || axis < 0 ? try_cut(c, node, s, in, npieces, max_cut, done) : OIT_OK;
}
