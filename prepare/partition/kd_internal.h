/* The guaranteed kd build's inside (kd.h: oit_kd_build), shared by its
 * files: kd.c (the recursion: when a node splits, how, and into what),
 * kd_layers.c (a node's layer bound, its trial splits' and its pieces'
 * boxes), kd_emit.c (node sets, and a node emitted as a part or slab leaf)
 * and kd_slab_leaf.c (a node made two parts across a slab or cut instead of
 * an axis split). kd.c uses the other three, kd_slab_leaf.c uses
 * kd_layers.c and kd_emit.c; nothing outside prepare/partition/ includes it. */
#ifndef OIT_PARTITION_KD_INTERNAL_H
#define OIT_PARTITION_KD_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "base/minmax.h"
#include "prepare/partition/grow.h"
#include "prepare/partition/kd.h"
#include "prepare/partition/kd_slab.h"
#include "prepare/partition/kd_split.h"

/* A node's triangles, each with its source index, convex piece and plane
 * id. The root's arrays are the caller's (read only). */
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

/* Grows a kd result array for need more, or returns OIT_ERR_NOMEM from the
 * function it is used in. */
#define GROW(arr, count, cap, need)                                                   \
    do {                                                                              \
        if (oit_grow((void **)&(arr), sizeof *(arr), (count), &(cap), (need)))        \
            return OIT_ERR_NOMEM;                                                     \
    } while (0)

/* The extent of triangle t along axis. Inline: it runs per triangle in
 * every trial split. */
static inline void oit_kd_tri_range(const oit_triangle *t, int axis, float *mn, float *mx)
{
    *mn = oit_min_f(oit_min_f(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
    *mx = oit_max_f(oit_max_f(t->v[0].pos[axis], t->v[1].pos[axis]), t->v[2].pos[axis]);
}

/* The node's pieces as the slab and cut searches take them: each
 * triangle's piece slot (oit_kd_piece_boxes' numbering) and each slot's
 * weight. */
typedef struct slab_input {
    uint32_t *slot, *weight;
} slab_input;

/* ---- kd_layers.c ---- */

/* The node's layer bound: per piece 1 while all of it lies in one plane, 2
 * once it has two (convexity); *npieces the pieces in the node. */
uint32_t oit_kd_node_layers(kd_ctx *c, const node_set *s, uint32_t *npieces);

/* Layer bounds of the two halves of a split at m on axis (upper bounds:
 * clipped slivers that round to nothing are not foreseen), per clip.h's
 * rules. */
void oit_kd_split_layers(kd_ctx *c, const node_set *s, int axis, float m, uint32_t *below,
                         uint32_t *above);

/* The node's pieces as boxes with their weights, for kd_split.h, in the
 * order they first appear (c->piece_slot numbers them); malloc'd into *out,
 * OIT_ERR_NOMEM when it cannot be. */
oit_status oit_kd_piece_boxes(kd_ctx *c, const node_set *s, uint32_t npieces,
                              oit_kd_piece_box **out);

/* Fallback: the midplane of the axis that most lowers the larger half
 * (*larger its bound); -1 when no axis halves the box in float. */
int oit_kd_choose_axis(kd_ctx *c, const node_set *s, const float lo[3], const float hi[3],
                       uint32_t *larger);

/* ---- kd_emit.c ---- */

/* Appends a triangle (or a clipped piece of one) with what it inherits
 * from `from`'s triangle i. */
oit_status oit_kd_set_push(node_set *s, const oit_triangle *t, const node_set *from, size_t i);

/* Frees a set made by set_push (not the root's, which is the caller's). */
void oit_kd_set_free(node_set *s);

/* Appends the node's triangles as one part, grouped by piece (pieces in the
 * order they first appear, triangles in node order within a piece), its
 * layer bound from its pieces' planes; *part_index its index. Fails with
 * OIT_ERR_UNSUPPORTED past max_triangles. */
oit_status oit_kd_emit_part(kd_ctx *c, const node_set *s, uint32_t npieces, int32_t *part_index);

/* The node as a slab leaf: the two halves emitted as parts (count[h]
 * pieces each), below then above, and the slab recorded. */
oit_status oit_kd_emit_slab_leaf(kd_ctx *c, size_t node, const node_set half[2],
                                 const uint32_t count[2], const oit_kd_slab *planes);

/* ---- kd_slab_leaf.c ---- */

/* The node's piece slots and weights (b from piece_boxes) into in;
 * OIT_ERR_NOMEM when they cannot be allocated (free them anyway). */
oit_status oit_kd_slab_input_make(const kd_ctx *c, const node_set *s, const oit_kd_piece_box *b,
                                  uint32_t npieces, slab_input *in);
void oit_kd_slab_input_free(slab_input *in);

/* The node as two parts on either side of a slab (kd_slab.h), when one
 * separates its pieces; *done tells whether it did. */
oit_status oit_kd_try_slab(kd_ctx *c, size_t node, const node_set *s, const slab_input *in,
                           uint32_t npieces, int *done);

/* A cut (kd_cut.h) replaces the axis split (found: kd_split's at m on
 * axis; else the midplane fallback's) when it crosses fewer triangles, or
 * when the axis split's halves would need splitting again; *done tells
 * whether the node became a cut slab leaf. */
oit_status oit_kd_try_cut_instead(kd_ctx *c, size_t node, const node_set *s, const slab_input *in,
                                  uint32_t npieces, int found, int axis, float m, int *done);

#endif
