/* Cell subdivision into parts (kd.h). */
#include "partition/kd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "partition/clip.h"
#include "partition/convex.h"
#include "partition/grow.h"
#include "partition/kd_cut.h"
#include "partition/kd_split.h"
#include "base/minmax.h"


typedef struct node_set {
    oit_triangle *tris;
    uint32_t *src, *piece, *plane;
    size_t n, cap;
} node_set;

typedef struct kd_ctx {
    const oit_kd_params *p;
    uint32_t *piece_stamp; /* per piece id: last stamp that counted it */
    uint32_t *above_stamp; /* the same for the upper half of a trial split */
    uint32_t *piece_slot;  /* per piece id: leaf-local slot */
    uint32_t *plane_stamp; /* per plane id: last stamp that counted it */
    uint32_t *first_plane[2]; /* per piece id and side: plane first seen */
    uint8_t *two_planes[2];   /* per piece id and side: a second plane seen */
    uint32_t stamp;
    oit_kd_result *out;
    oit_error *err;
} kd_ctx;

#define GROW(arr, count, cap, need)                                                   \
    do {                                                                              \
        if (oit_grow((void **)&(arr), sizeof *(arr), (count), &(cap), (need)))        \
            return OIT_ERR_NOMEM;                                                     \
    } while (0)

/* Appends a triangle (or a clipped piece of one) with what it inherits
 * from s's triangle i. */
static oit_status set_push(node_set *s, const oit_triangle *t, const node_set *from, size_t i)
{
    uint32_t src = from->src[i], piece = from->piece[i], plane = from->plane[i];
    if (s->n == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 64;
        oit_triangle *a = realloc(s->tris, nc * sizeof *a);
        if (a) s->tris = a;
        uint32_t *b = realloc(s->piece, nc * sizeof *b);
        if (b) s->piece = b;
        uint32_t *c = realloc(s->plane, nc * sizeof *c);
        if (c) s->plane = c;
        uint32_t *d = realloc(s->src, nc * sizeof *d);
        if (d) s->src = d;
        if (!a || !b || !c || !d)
            return OIT_ERR_NOMEM;
        s->cap = nc;
    }
    s->tris[s->n] = *t;
    s->src[s->n] = src;
    s->piece[s->n] = piece;
    s->plane[s->n++] = plane;
    return OIT_OK;
}

static void set_free(node_set *s)
{
    free(s->tris);
    free(s->src);
    free(s->piece);
    free(s->plane);
}

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
static uint32_t node_layers(kd_ctx *c, const node_set *s, uint32_t *npieces)
{
    uint32_t k = ++c->stamp, layers = 0, count = 0;
    for (size_t i = 0; i < s->n; i++) {
        count += c->piece_stamp[s->piece[i]] != k;
        layers_add(c, c->piece_stamp, 0, k, s->piece[i], s->plane[i], &layers);
    }
    *npieces = count;
    return layers;
}

static void tri_range(const oit_triangle *t, int axis, float *mn, float *mx)
{
    *mn = oit_min_f(oit_min_f(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
    *mx = oit_max_f(oit_max_f(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
}

/* Layer bounds of the two halves of a split (upper bounds: clipped slivers
 * that round to nothing are not foreseen), per clip.h's rules. */
static void split_layers(kd_ctx *c, const node_set *s, int axis, float m, uint32_t *below,
                         uint32_t *above)
{
    uint32_t k = ++c->stamp;
    *below = *above = 0;
    for (size_t i = 0; i < s->n; i++) {
        float mn, mx;
        tri_range(&s->tris[i], axis, &mn, &mx);
        if (mn < m || mx <= m)
            layers_add(c, c->piece_stamp, 0, k, s->piece[i], s->plane[i], below);
        if (mx > m)
            layers_add(c, c->above_stamp, 1, k, s->piece[i], s->plane[i], above);
    }
}

/* The node's pieces as boxes with their weights, for kd_split.h. */
static oit_status piece_boxes(kd_ctx *c, const node_set *s, uint32_t npieces,
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
            tri_range(&s->tris[i], a, &mn, &mx);
            pb->lo[a] = oit_min_f(pb->lo[a], mn);
            pb->hi[a] = oit_max_f(pb->hi[a], mx);
        }
    }
    for (size_t i = 0; i < s->n; i++) {
        oit_kd_piece_box *pb = &b[c->piece_slot[s->piece[i]]];
        for (int a = 0; a < 3; a++) {
            float mn, mx;
            tri_range(&s->tris[i], a, &mn, &mx);
            pb->face_lo |= (uint8_t)((mn == mx && mn == pb->lo[a]) << a);
            pb->face_hi |= (uint8_t)((mn == mx && mx == pb->hi[a]) << a);
        }
    }
    *out = b;
    return OIT_OK;
}

/* Fallback: the midplane of the axis that most lowers the larger half. */
static int choose_axis(kd_ctx *c, const node_set *s, const float lo[3], const float hi[3],
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
        split_layers(c, s, a, m, &b, &t);
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

/* Appends the node's triangles as one part, grouped by piece (pieces in the
 * order they first appear, triangles in node order within a piece). */
static oit_status emit_part(kd_ctx *c, const node_set *s, uint32_t npieces, int32_t *part_index)
{
    oit_kd_result *r = c->out;
    if (c->p->max_triangles && r->tri_count + s->n > c->p->max_triangles)
        return oit_error_set(c->err, OIT_ERR_UNSUPPORTED, "cell subdivision: clipping into "
                             "parts of at most K = %u layers needs more than %llu triangles; "
                             "the geometry crosses itself too densely for boxes of K layers",
                             c->p->max_layers, (unsigned long long)c->p->max_triangles);
    GROW(r->parts, r->part_count, r->part_cap, 1);
    GROW(r->pieces, r->piece_count, r->piece_cap, npieces);
    GROW(r->tris, r->tri_count, r->tri_cap, s->n);
    GROW(r->src, r->tri_count, r->src_cap, s->n);
    oit_kd_part *part = &r->parts[r->part_count];
    part->tri_first = r->tri_count;
    part->tri_count = s->n;
    part->piece_first = (uint32_t)r->piece_count;
    part->piece_count = npieces;
    uint32_t k = ++c->stamp, slot = 0;
    for (size_t i = 0; i < s->n; i++)
        if (c->piece_stamp[s->piece[i]] != k) {
            c->piece_stamp[s->piece[i]] = k;
            c->piece_slot[s->piece[i]] = slot;
            r->pieces[part->piece_first + slot++] = (oit_kd_piece){0, 0};
        }
    oit_kd_piece *pc = &r->pieces[part->piece_first];
    for (size_t i = 0; i < s->n; i++)
        pc[c->piece_slot[s->piece[i]]].triangle_count++;
    /* Counting sort into place; plane_count counts distinct plane ids. */
    size_t *start = malloc(npieces * sizeof *start);
    if (!start)
        return OIT_ERR_NOMEM;
    size_t at = part->tri_first;
    for (uint32_t p = 0; p < npieces; p++) {
        start[p] = at;
        at += pc[p].triangle_count;
    }
    for (size_t i = 0; i < s->n; i++) {
        size_t at_i = start[c->piece_slot[s->piece[i]]]++;
        r->tris[at_i] = s->tris[i];
        r->src[at_i] = s->src[i];
    }
    free(start);
    for (uint32_t p = 0; p < npieces; p++) {
        uint32_t kp = ++c->stamp;
        for (size_t i = 0; i < s->n; i++)
            if (c->piece_slot[s->piece[i]] == p && c->piece_stamp[s->piece[i]] == k &&
                c->plane_stamp[s->plane[i]] != kp) {
                c->plane_stamp[s->plane[i]] = kp;
                pc[p].plane_count++;
            }
    }
    part->layer_bound = 0;
    for (uint32_t p = 0; p < npieces; p++)
        part->layer_bound += pc[p].plane_count > 1 ? 2 : 1;
    r->tri_count += s->n;
    r->piece_count += npieces;
    *part_index = (int32_t)r->part_count++;
    return OIT_OK;
}

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
            if (set_push(out, &h[side][k], s, i))
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
        set_free(&half);
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

/* The node as a slab leaf: the two halves emitted as parts (count[h]
 * pieces each), below then above, and the slab recorded. */
static oit_status emit_slab_leaf(kd_ctx *c, size_t node, const node_set half[2],
                                 const uint32_t count[2], const oit_kd_slab *planes)
{
    int32_t part[2];
    for (int h = 0; h < 2; h++) {
        oit_status st = emit_part(c, &half[h], count[h], &part[h]);
        if (st)
            return st;
    }
    oit_kd_result *r = c->out;
    GROW(r->slabs, r->slab_count, r->slab_cap, 1);
    r->slabs[r->slab_count] = (oit_kd_slab_leaf){*planes, (uint32_t)part[0], (uint32_t)part[1]};
    r->nodes[node].part = part[0];
    r->nodes[node].slab = (int32_t)r->slab_count++;
    return OIT_OK;
}

/* The node's pieces as the slab and cut searches take them: each
 * triangle's piece slot (piece_boxes' numbering) and each slot's weight. */
typedef struct slab_input {
    uint32_t *slot, *weight;
} slab_input;

static oit_status slab_input_make(const kd_ctx *c, const node_set *s, const oit_kd_piece_box *b,
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

static void slab_input_free(slab_input *in)
{
    free(in->slot);
    free(in->weight);
}

/* The node as two parts on either side of a slab (kd_slab.h), when one
 * separates its pieces; *done tells whether it did. */
static oit_status try_slab(kd_ctx *c, size_t node, const node_set *s, const slab_input *in,
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
        st = set_push(&half[side[slot[i]]], &s->tris[i], s, i);
    if (found > 0 && !st)
        st = emit_slab_leaf(c, node, half, count, &planes);
    *done = found > 0 && !st;
    set_free(&half[0]);
    set_free(&half[1]);
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
        tri_range(&s->tris[i], axis, &mn, &mx);
        crossed += mn < m && mx > m;
    }
    split_layers(c, s, axis, m, &below, &above);
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
                st = set_push(&half[side], &h[side][k], s, i);
        added += (uint64_t)(n[0] + n[1]) - 1;
    }
    uint32_t count[2], layers[2];
    for (int h = 0; h < 2 && found > 0 && !st; h++) {
        layers[h] = node_layers(c, &half[h], &count[h]);
        found = count[h] && layers[h] <= c->p->max_layers;
    }
    if (found > 0 && !st) {
        oit_kd_slab planes = {{(float)cut.plane.n[0], (float)cut.plane.n[1],
                               (float)cut.plane.n[2]},
                              (float)cut.plane.d, (float)cut.plane.d};
        st = emit_slab_leaf(c, node, half, count, &planes);
        c->out->split_added += added;
        c->out->cuts++;
        *done = !st;
    }
    set_free(&half[0]);
    set_free(&half[1]);
    return st;
}

/* A cut replaces the axis split (found: kd_split's; else the midplane
 * fallback's) when it crosses fewer triangles, or when the axis split's
 * halves would need splitting again. */
static oit_status try_cut_instead(kd_ctx *c, size_t node, const node_set *s,
                                  const slab_input *in, uint32_t npieces, int found, int axis,
                                  float m, int *done)
{
    const oit_kd_node *nd = &c->out->nodes[node];
    uint32_t larger, max_cut = UINT32_MAX;
    if (!found) {
        axis = choose_axis(c, s, nd->lo, nd->hi, &larger);
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

static oit_status build_node(kd_ctx *c, size_t node, const node_set *s)
{
    uint32_t npieces, layers = node_layers(c, s, &npieces);
    oit_kd_node *nd = &c->out->nodes[node];
    if (npieces == 0)
        return OIT_OK;
    uint32_t max_depth = c->p->max_depth ? c->p->max_depth : 48;
    int axis = -1;
    float m = 0;
    if (layers > c->p->max_layers && nd->depth < max_depth) {
        oit_kd_piece_box *boxes;
        if (piece_boxes(c, s, npieces, &boxes))
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
                st = slab_input_make(c, s, boxes, npieces, &in);
                if (!st)
                    st = try_slab(c, node, s, &in, npieces, &slab);
                if (!st && !slab && c->p->slabs == OIT_KD_SLABS_ALL)
                    st = try_cut_instead(c, node, s, &in, npieces, found, axis, m, &slab);
                slab_input_free(&in);
            }
        }
        free(boxes);
        if (st || slab)
            return st;
        if (!found) {
            /* A star may still hold triangles away from its vertex (a piece's
             * second plane): halve while that lowers the bound. */
            uint32_t larger = 0;
            axis = choose_axis(c, s, nd->lo, nd->hi, &larger);
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
    return emit_part(c, s, npieces, &c->out->nodes[node].part);
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
