/* Cell subdivision into parts (kd.h). This file holds the recursion: when
 * a node splits, on which axis, or whether it becomes a part, a star's part
 * or a slab leaf. A node's layer counting is in kd_layers.c, its sets and
 * emission in kd_emit.c, slabs and cuts in kd_slab_leaf.c
 * (kd_internal.h). */
#include "prepare/partition/kd_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prepare/partition/clip.h"

/* One half of a split (side 0 below, 1 above). The halves are built one at
 * a time so that a path down the tree holds one set per level, not two.
 * added counts the triangles the clip adds, on the below pass only. */
static oit_status split_set(const node_set *s, int axis, float m, int side, node_set *out,
                            uint64_t *added)
{
    for (size_t i = 0; i < s->n; i++) {
        oit_triangle h[2][2];
        int n[2];
        oit_clip_triangle_split(&s->tris[i], axis, m, h[0], &n[0], h[1], &n[1]);
        for (int k = 0; k < n[side]; k++)
            if (oit_kd_set_push(out, &h[side][k], s, i))
                return OIT_ERR_NOMEM;
        if (side == 0)
            *added += (uint64_t)(n[0] + n[1]) - 1;
    }
    return OIT_OK;
}

static oit_status build_node(kd_ctx *c, size_t node, const node_set *s);

oit_status oit_kd_add_children(oit_kd_result *r, size_t node, int axis, float m, size_t *child)
{
    GROW(r->nodes, r->node_count, r->node_cap, 2);
    oit_kd_node *nd = &r->nodes[node];
    *child = r->node_count;
    r->node_count += 2;
    nd->axis = axis;
    nd->split = m;
    nd->child = (uint32_t)*child;
    for (int h = 0; h < 2; h++) {
        oit_kd_node *ch = &r->nodes[*child + h];
        *ch = *nd;
        ch->axis = -1;
        ch->part = -1;
        ch->slab = -1;
        ch->depth = nd->depth + 1;
        if (h == 0)
            ch->hi[axis] = m;
        else
            ch->lo[axis] = m;
    }
    if (nd->depth + 1 > r->depth)
        r->depth = nd->depth + 1;
    return OIT_OK;
}

static oit_status split_node(kd_ctx *c, size_t node, const node_set *s, int axis, float m)
{
    oit_kd_result *r = c->out;
    size_t child;
    if (oit_kd_add_children(r, node, axis, m, &child))
        return OIT_ERR_NOMEM;
    oit_status st = OIT_OK;
    for (int side = 0; side < 2 && !st; side++) {
        node_set half = {0};
        st = split_set(s, axis, m, side, &half, &r->split_added);
        if (!st)
            st = build_node(c, child + side, &half);
        oit_kd_set_free(&half);
    }
    return st;
}

static int same_pos(const oit_vertex *a, const float p[3])
{
    return a->pos[0] == p[0] && a->pos[1] == p[1] && a->pos[2] == p[2];
}

/* Whether every piece of the node has a triangle with a corner at p. */
static int all_pieces_touch(kd_ctx *c, const node_set *s, const float p[3], uint32_t npieces)
{
    uint32_t k = ++c->stamp, hit = 0;
    for (size_t i = 0; i < s->n; i++) {
        const oit_triangle *t = &s->tris[i];
        if (c->piece_stamp[s->piece[i]] != k &&
            (same_pos(&t->v[0], p) || same_pos(&t->v[1], p) || same_pos(&t->v[2], p))) {
            c->piece_stamp[s->piece[i]] = k;
            hit++;
        }
    }
    return hit == npieces;
}

/* A star: all pieces of the node meet at one vertex. A box around that
 * vertex holds all of them however small it gets, so halving is futile.
 * Clipping keeps a vertex inside the box as a corner of some sub-triangle,
 * so testing the corners of the first piece's triangles finds it. b and
 * piece_slot are piece_boxes' (left as they are). Returns 1, 0, or -1 when
 * memory runs out. */
static int node_is_star(kd_ctx *c, const node_set *s, const oit_kd_piece_box *b,
                        uint32_t npieces)
{
    if (s->n > 64u * npieces)
        return 0; /* a star's triangles are few: each piece holds a fan */
    /* Candidates: the corners of the piece with the fewest triangles, which
     * in a star is a small fan; a piece of many is not part of one. */
    uint32_t *count = calloc(npieces, sizeof *count), best = 0, best_count = UINT32_MAX;
    if (!count)
        return -1;
    for (size_t i = 0; i < s->n; i++)
        count[c->piece_slot[s->piece[i]]]++;
    for (size_t i = 0; i < s->n; i++)
        if (count[c->piece_slot[s->piece[i]]] < best_count) {
            best_count = count[c->piece_slot[s->piece[i]]];
            best = s->piece[i];
        }
    free(count);
    if (best_count > 16)
        return 0;
    /* The centre lies in every piece's box: that rules out most candidates
     * before all_pieces_touch scans the node for them. */
    float lo[3] = {-INFINITY, -INFINITY, -INFINITY}, hi[3] = {INFINITY, INFINITY, INFINITY};
    for (uint32_t p = 0; p < npieces; p++)
        for (int a = 0; a < 3; a++) {
            lo[a] = oit_max_f(lo[a], b[p].lo[a]);
            hi[a] = oit_min_f(hi[a], b[p].hi[a]);
        }
    for (size_t i = 0; i < s->n; i++)
        for (int v = 0; v < 3 && s->piece[i] == best; v++) {
            const float *p = s->tris[i].v[v].pos;
            if (p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] &&
                p[2] >= lo[2] && p[2] <= hi[2] && all_pieces_touch(c, s, p, npieces))
                return 1;
        }
    return 0;
}

/* Whether the axis split leaves both halves within K without cutting a
 * piece (kd_split.h's rule for which side a piece goes to). */
static int split_is_clean(const oit_kd_piece_box *b, uint32_t npieces, int axis, float m,
                          uint32_t K)
{
    uint32_t below = 0, above = 0;
    for (uint32_t p = 0; p < npieces; p++) {
        if (b[p].lo[axis] < m && b[p].hi[axis] > m)
            return 0;
        if (b[p].hi[axis] > m)
            above += b[p].weight;
        else
            below += b[p].weight;
    }
    return below <= K && above <= K;
}

static oit_status build_node(kd_ctx *c, size_t node, const node_set *s)
{
    uint32_t npieces, layers = oit_kd_node_layers(c, s, &npieces);
    oit_kd_node *nd = &c->out->nodes[node];
    if (npieces == 0)
        return OIT_OK;
    uint32_t max_depth = c->p->max_depth ? c->p->max_depth : 48;
    int axis = -1;
    float m = 0;
    if (layers > c->p->max_layers && nd->depth < max_depth) {
        oit_kd_piece_box *boxes;
        if (oit_kd_piece_boxes(c, s, npieces, &boxes))
            return OIT_ERR_NOMEM;
        int star = node_is_star(c, s, boxes, npieces), found = 0, slab = 0;
        oit_status st = star < 0 ? OIT_ERR_NOMEM : OIT_OK;
        if (!st && !star) {
            found = oit_kd_choose_split(boxes, npieces, nd->lo, nd->hi, c->p->max_layers, &axis,
                                        &m);
            st = found < 0 ? OIT_ERR_NOMEM : OIT_OK;
            if (!st && layers <= 2 * c->p->max_layers &&
                !(found && split_is_clean(boxes, npieces, axis, m, c->p->max_layers)) &&
                c->p->slabs != OIT_KD_SLABS_NONE) {
                slab_input in = {0};
                st = oit_kd_slab_input_make(c, s, boxes, npieces, &in);
                if (!st)
                    st = oit_kd_try_slab(c, node, s, &in, npieces, &slab);
                if (!st && !slab && c->p->slabs == OIT_KD_SLABS_ALL)
                    st = oit_kd_try_cut_instead(c, node, s, &in, npieces, found, axis, m, &slab);
                oit_kd_slab_input_free(&in);
            }
        }
        free(boxes);
        if (st || slab)
            return st;
        if (!found) {
            /* A star may still hold triangles away from its vertex (a piece's
             * second plane): halve while that lowers the bound. */
            uint32_t larger = 0;
            axis = oit_kd_choose_axis(c, s, nd->lo, nd->hi, &larger);
            if (star && larger >= layers)
                axis = -1;
            m = axis >= 0 ? 0.5f * (nd->lo[axis] + nd->hi[axis]) : 0;
        }
    }
    if (axis >= 0)
        return split_node(c, node, s, axis, m);
    if (layers > c->p->max_layers) {
        if (layers > OIT_KD_MAX_WIDE_LAYERS)
            return oit_error_set(c->err, OIT_ERR_UNSUPPORTED,
                                 "%u convex pieces (%u layers) meet in the box "
                                 "(%g %g %g)..(%g %g %g) after %u subdivisions: more than the "
                                 "%u layers a wide part may have",
                                 npieces, layers, nd->lo[0], nd->lo[1], nd->lo[2], nd->hi[0],
                                 nd->hi[1], nd->hi[2], nd->depth, OIT_KD_MAX_WIDE_LAYERS);
        c->out->wide_parts++;
    }
    return oit_kd_emit_part(c, s, npieces, &c->out->nodes[node].part);
}

uint32_t *oit_kd_iota(size_t n)
{
    uint32_t *a = n ? malloc(n * sizeof *a) : NULL;
    for (size_t i = 0; a && i < n; i++)
        a[i] = (uint32_t)i;
    return a;
}

oit_status oit_kd_build(const float lo[3], const float hi[3], const oit_triangle *tris,
                        const uint32_t *src, size_t n, const uint32_t *piece,
                        const uint32_t *plane, uint32_t piece_count,
                        const oit_kd_params *params, oit_kd_result *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    kd_ctx c = {.p = params, .out = out, .err = err};
    oit_status st = OIT_OK;
    uint32_t *own = src || !n ? NULL : oit_kd_iota(n);
    if (!src)
        src = own;
    if (n && !src)
        st = OIT_ERR_NOMEM;
    c.piece_stamp = calloc(piece_count + 1, sizeof *c.piece_stamp);
    c.above_stamp = calloc(piece_count + 1, sizeof *c.above_stamp);
    c.piece_slot = calloc(piece_count + 1, sizeof *c.piece_slot);
    c.plane_stamp = calloc(n + 1, sizeof *c.plane_stamp);
    for (int h = 0; h < 2; h++) {
        c.first_plane[h] = calloc(piece_count + 1, sizeof *c.first_plane[h]);
        c.two_planes[h] = calloc(piece_count + 1, 1);
        if (!c.first_plane[h] || !c.two_planes[h])
            st = OIT_ERR_NOMEM;
    }
    out->nodes = malloc(16 * sizeof *out->nodes);
    if (!c.piece_stamp || !c.above_stamp || !c.piece_slot || !c.plane_stamp || !out->nodes)
        st = OIT_ERR_NOMEM;
    if (!st) {
        out->node_cap = 16;
        out->node_count = 1;
        oit_kd_node *root = &out->nodes[0];
        memcpy(root->lo, lo, sizeof root->lo);
        memcpy(root->hi, hi, sizeof root->hi);
        root->axis = -1;
        root->part = -1;
        root->slab = -1;
        root->depth = 0;
        /* The root reads the caller's arrays; build_node never writes them. */
        node_set s = {(oit_triangle *)tris, (uint32_t *)src, (uint32_t *)piece,
                      (uint32_t *)plane, n, n};
        st = build_node(&c, 0, &s);
    }
    free(own);
    free(c.piece_stamp);
    free(c.above_stamp);
    free(c.piece_slot);
    free(c.plane_stamp);
    for (int h = 0; h < 2; h++) {
        free(c.first_plane[h]);
        free(c.two_planes[h]);
    }
    if (st == OIT_ERR_NOMEM && !(err && err->message[0]))
        oit_error_set(err, st, "cell subdivision of %zu triangles: out of memory", n);
    if (st)
        oit_kd_result_free(out);
    return st;
}

void oit_kd_result_free(oit_kd_result *r)
{
    free(r->nodes);
    free(r->parts);
    free(r->pieces);
    free(r->tris);
    free(r->src);
    free(r->slabs);
    memset(r, 0, sizeof *r);
}
