/* Cell subdivision into parts (kd.h). */
#include "partition/kd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "partition/clip.h"
#include "partition/convex.h"

typedef struct node_set {
    oit_triangle *tris;
    uint32_t *piece, *plane;
    size_t n, cap;
} node_set;

typedef struct kd_ctx {
    const oit_kd_params *p;
    uint32_t *piece_stamp; /* per piece id: last stamp that counted it */
    uint32_t *above_stamp; /* the same for the upper half of a trial split */
    uint32_t *piece_slot;  /* per piece id: leaf-local slot */
    uint32_t *plane_stamp; /* per plane id: last stamp that counted it */
    size_t plane_cap;
    const uint32_t *root_piece;
    uint32_t stamp;
    oit_kd_result *out;
    oit_error *err;
} kd_ctx;

#define GROW(arr, count, cap, need)                                                   \
    do {                                                                              \
        if ((count) + (need) > (cap)) {                                               \
            size_t nc_ = (cap) ? (cap) : 16;                                          \
            while (nc_ < (count) + (need))                                            \
                nc_ *= 2;                                                             \
            void *p_ = realloc((arr), nc_ * sizeof *(arr));                           \
            if (!p_)                                                                  \
                return OIT_ERR_NOMEM;                                                 \
            (arr) = p_;                                                               \
            (cap) = nc_;                                                              \
        }                                                                             \
    } while (0)

static oit_status set_push(node_set *s, const oit_triangle *t, uint32_t piece, uint32_t plane)
{
    if (s->n == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 64;
        oit_triangle *a = realloc(s->tris, nc * sizeof *a);
        if (a) s->tris = a;
        uint32_t *b = realloc(s->piece, nc * sizeof *b);
        if (b) s->piece = b;
        uint32_t *c = realloc(s->plane, nc * sizeof *c);
        if (c) s->plane = c;
        if (!a || !b || !c)
            return OIT_ERR_NOMEM;
        s->cap = nc;
    }
    s->tris[s->n] = *t;
    s->piece[s->n] = piece;
    s->plane[s->n++] = plane;
    return OIT_OK;
}

static void set_free(node_set *s)
{
    free(s->tris);
    free(s->piece);
    free(s->plane);
}

static uint32_t count_pieces(kd_ctx *c, const uint32_t *piece, size_t n)
{
    uint32_t k = ++c->stamp, count = 0;
    for (size_t i = 0; i < n; i++)
        if (c->piece_stamp[piece[i]] != k) {
            c->piece_stamp[piece[i]] = k;
            count++;
        }
    return count;
}

static void tri_range(const oit_triangle *t, int axis, float *mn, float *mx)
{
    *mn = fminf(fminf(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
    *mx = fmaxf(fmaxf(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
}

/* Pieces that would reach each half of a split (an upper bound: clipped
 * slivers that round to nothing are not foreseen), per clip.h's rules. */
static void split_counts(kd_ctx *c, const node_set *s, int axis, float m, uint32_t *below,
                         uint32_t *above)
{
    uint32_t k = ++c->stamp;
    *below = *above = 0;
    for (size_t i = 0; i < s->n; i++) {
        float mn, mx;
        tri_range(&s->tris[i], axis, &mn, &mx);
        uint32_t p = s->piece[i];
        if ((mn < m || mx <= m) && c->piece_stamp[p] != k) {
            c->piece_stamp[p] = k;
            (*below)++;
        }
        if (mx > m && c->above_stamp[p] != k) {
            c->above_stamp[p] = k;
            (*above)++;
        }
    }
}

static int choose_axis(kd_ctx *c, const node_set *s, const float lo[3], const float hi[3])
{
    int best = -1;
    uint32_t best_max = 0;
    float best_ext = 0;
    for (int a = 0; a < 3; a++) {
        float m = 0.5f * (lo[a] + hi[a]);
        if (!(m > lo[a] && m < hi[a]))
            continue; /* the box is too thin to halve in float */
        uint32_t b, t;
        split_counts(c, s, a, m, &b, &t);
        uint32_t mx = b > t ? b : t;
        float ext = hi[a] - lo[a];
        if (best < 0 || mx < best_max || (mx == best_max && ext > best_ext)) {
            best = a;
            best_max = mx;
            best_ext = ext;
        }
    }
    return best;
}

/* Appends the node's triangles as one part, grouped by piece (pieces in the
 * order they first appear, triangles in node order within a piece). */
static oit_status emit_part(kd_ctx *c, const node_set *s, uint32_t npieces, int32_t *part_index)
{
    oit_kd_result *r = c->out;
    GROW(r->parts, r->part_count, r->part_cap, 1);
    GROW(r->pieces, r->piece_count, r->piece_cap, npieces);
    GROW(r->tris, r->tri_count, r->tri_cap, s->n);
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
    for (size_t i = 0; i < s->n; i++)
        r->tris[start[c->piece_slot[s->piece[i]]]++] = s->tris[i];
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
    r->tri_count += s->n;
    r->piece_count += npieces;
    *part_index = (int32_t)r->part_count++;
    return OIT_OK;
}

static oit_status split_set(const node_set *s, int axis, float m, node_set *below,
                            node_set *above, uint64_t *added)
{
    for (size_t i = 0; i < s->n; i++) {
        oit_triangle b[2], a[2];
        int nb, na;
        oit_clip_triangle_split(&s->tris[i], axis, m, b, &nb, a, &na);
        for (int k = 0; k < nb; k++)
            if (set_push(below, &b[k], s->piece[i], s->plane[i]))
                return OIT_ERR_NOMEM;
        for (int k = 0; k < na; k++)
            if (set_push(above, &a[k], s->piece[i], s->plane[i]))
                return OIT_ERR_NOMEM;
        *added += (uint64_t)(nb + na) - 1;
    }
    return OIT_OK;
}

static oit_status build_node(kd_ctx *c, size_t node, const node_set *s);

/* Last resort at the depth cap: float rounding can make a flat or gently
 * curved surface exactly non-convex at the scale of an ulp, so that more
 * than K/2 exact pieces meet at one vertex and no box separates them. In such
 * a (tiny) box the triangles are re-clustered with a flatness tolerance; when
 * that gives few enough pieces they replace the exact ones (counted in
 * tolerant_parts). Returns OIT_ERR_UNSUPPORTED when it does not. The node's
 * arrays are rewritten in place (they are the node's own copies). */
static oit_status recluster_tolerant(kd_ctx *c, const node_set *s, uint32_t *npieces)
{
    if (s->piece == c->root_piece)
        return OIT_ERR_UNSUPPORTED; /* the caller's arrays: never rewritten */
    oit_convex_params cp = {0, 1e-5};
    oit_convex_result r;
    if (oit_convex_cluster(s->tris, s->n, &cp, &r, NULL))
        return OIT_ERR_NOMEM;
    if (r.piece_count > c->p->max_pieces || r.piece_count > *npieces) {
        oit_convex_result_free(&r);
        return OIT_ERR_UNSUPPORTED;
    }
    /* Reuse the node's old piece ids (there are more of them) so the ids stay
     * inside the stamp arrays; plane ids are below s->n. */
    uint32_t ids[512], k = ++c->stamp, m = 0;
    for (size_t i = 0; i < s->n && m < r.piece_count; i++)
        if (c->piece_stamp[s->piece[i]] != k) {
            c->piece_stamp[s->piece[i]] = k;
            ids[m++] = s->piece[i];
        }
    if (s->n + 1 > c->plane_cap) {
        uint32_t *p = realloc(c->plane_stamp, (s->n + 1) * sizeof *p);
        if (!p) {
            oit_convex_result_free(&r);
            return OIT_ERR_NOMEM;
        }
        memset(p + c->plane_cap, 0, (s->n + 1 - c->plane_cap) * sizeof *p);
        c->plane_stamp = p;
        c->plane_cap = s->n + 1;
    }
    for (size_t i = 0; i < s->n; i++) {
        s->piece[i] = ids[r.piece_of[i]];
        s->plane[i] = r.plane_of[i];
    }
    *npieces = r.piece_count;
    c->out->tolerant_parts++;
    oit_convex_result_free(&r);
    return OIT_OK;
}

static oit_status split_node(kd_ctx *c, size_t node, const node_set *s, int axis)
{
    oit_kd_result *r = c->out;
    GROW(r->nodes, r->node_count, r->node_cap, 2);
    oit_kd_node *nd = &r->nodes[node];
    float m = 0.5f * (nd->lo[axis] + nd->hi[axis]);
    size_t child = r->node_count;
    r->node_count += 2;
    nd->axis = axis;
    nd->child = (uint32_t)child;
    for (int h = 0; h < 2; h++) {
        oit_kd_node *ch = &r->nodes[child + h];
        *ch = *nd;
        ch->axis = -1;
        ch->part = -1;
        ch->depth = nd->depth + 1;
        if (h == 0)
            ch->hi[axis] = m;
        else
            ch->lo[axis] = m;
    }
    if (nd->depth + 1 > r->depth)
        r->depth = nd->depth + 1;
    node_set below = {0}, above = {0};
    oit_status st = split_set(s, axis, m, &below, &above, &r->split_added);
    if (!st)
        st = build_node(c, child, &below);
    set_free(&below);
    if (!st)
        st = build_node(c, child + 1, &above);
    set_free(&above);
    return st;
}

static oit_status build_node(kd_ctx *c, size_t node, const node_set *s)
{
    uint32_t npieces = count_pieces(c, s->piece, s->n);
    oit_kd_node *nd = &c->out->nodes[node];
    if (npieces == 0)
        return OIT_OK;
    if (npieces <= c->p->max_pieces)
        return emit_part(c, s, npieces, &c->out->nodes[node].part);
    uint32_t max_depth = c->p->max_depth ? c->p->max_depth : 48;
    int axis = nd->depth < max_depth ? choose_axis(c, s, nd->lo, nd->hi) : -1;
    if (axis < 0) {
        oit_status st = recluster_tolerant(c, s, &npieces);
        if (st != OIT_ERR_UNSUPPORTED)
            return st ? st : emit_part(c, s, npieces, &c->out->nodes[node].part);
        return oit_error_set(c->err, OIT_ERR_UNSUPPORTED,
                             "%u convex pieces still meet in the box (%g %g %g)..(%g %g %g) "
                             "after %u subdivisions: more than K/2 = %u layers there",
                             npieces, nd->lo[0], nd->lo[1], nd->lo[2], nd->hi[0], nd->hi[1],
                             nd->hi[2], nd->depth, c->p->max_pieces);
    }
    return split_node(c, node, s, axis);
}

oit_status oit_kd_build(const float lo[3], const float hi[3], const oit_triangle *tris, size_t n,
                        const uint32_t *piece, const uint32_t *plane, uint32_t piece_count,
                        const oit_kd_params *params, oit_kd_result *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    kd_ctx c = {.p = params, .out = out, .err = err};
    c.piece_stamp = calloc(piece_count + 1, sizeof *c.piece_stamp);
    c.above_stamp = calloc(piece_count + 1, sizeof *c.above_stamp);
    c.piece_slot = calloc(piece_count + 1, sizeof *c.piece_slot);
    c.plane_stamp = calloc(n + 1, sizeof *c.plane_stamp);
    c.plane_cap = n + 1;
    c.root_piece = piece;
    out->nodes = malloc(16 * sizeof *out->nodes);
    oit_status st = OIT_OK;
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
        root->depth = 0;
        /* The root reads the caller's arrays; build_node never writes them. */
        node_set s = {(oit_triangle *)tris, (uint32_t *)piece, (uint32_t *)plane, n, n};
        st = build_node(&c, 0, &s);
    }
    free(c.piece_stamp);
    free(c.above_stamp);
    free(c.piece_slot);
    free(c.plane_stamp);
    if (st == OIT_ERR_NOMEM)
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
    memset(r, 0, sizeof *r);
}
