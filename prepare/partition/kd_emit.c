/* A node's triangles held and emitted (kd_internal.h): the node sets a
 * split builds, and a node written into the result as a part or as a slab
 * leaf's two parts. Apart as the one place that fills oit_kd_result's
 * parts, pieces and triangles. */
#include "prepare/partition/kd_internal.h"

#include <stdlib.h>

/* Appends a triangle (or a clipped piece of one) with what it inherits
 * from s's triangle i. */
oit_status oit_kd_set_push(node_set *s, const oit_triangle *t, const node_set *from, size_t i)
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

void oit_kd_set_free(node_set *s)
{
    free(s->tris);
    free(s->src);
    free(s->piece);
    free(s->plane);
}

/* Appends the node's triangles as one part, grouped by piece (pieces in the
 * order they first appear, triangles in node order within a piece). */
oit_status oit_kd_emit_part(kd_ctx *c, const node_set *s, uint32_t npieces, int32_t *part_index)
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

/* The node as a slab leaf: the two halves emitted as parts (count[h]
 * pieces each), below then above, and the slab recorded. */
oit_status oit_kd_emit_slab_leaf(kd_ctx *c, size_t node, const node_set half[2],
                                 const uint32_t count[2], const oit_kd_slab *planes)
{
    int32_t part[2];
    for (int h = 0; h < 2; h++) {
        oit_status st = oit_kd_emit_part(c, &half[h], count[h], &part[h]);
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
