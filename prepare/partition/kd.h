/* Subdivision of one grid cell into parts (DESIGN.md "Layer bound",
 * "Visibility order").
 *
 * The cell's triangles arrive clustered into convex pieces. A node's layer
 * bound is the sum over its pieces of 1 (everything of the piece in the node
 * lies in one plane: a line crosses a plane once) or 2 (convex: a line meets
 * it at most twice). A node whose bound is at most K becomes one part;
 * otherwise it is split at the midplane of the axis that minimises the larger
 * child's bound, the triangles are clipped to the two closed halves (a
 * clipped convex piece stays convex; a piece with nothing left vanishes) and
 * both halves recurse. Every split is a 2x1x1 (1x2x1, 1x1x2) subgrid of its
 * node, so the result is a kd-tree of regular subgrids with at most one part
 * per leaf, each part inside its leaf's closed box: the contract of
 * partfile/order.h.
 *
 * Where more than K layers meet at one vertex (a saddle of high valence, a
 * fan of many non-convex sheets) no box separates them: halving only clips
 * the same star again. A node whose pieces all have a corner at one point
 * (or that reaches max_depth) therefore becomes a wide part: its bound
 * exceeds K, up to OIT_KD_MAX_WIDE_LAYERS, and the renderer captures it with
 * more slots per pixel over a smaller screen tile (view/stream/pack.h). Only a
 * node above that limit is refused.
 *
 * A node of at most 2K layers that no axis plane splits cleanly (without
 * cutting a piece, into halves of at most K) tries a separating slab first
 * (kd_slab.h): when one exists the node becomes a leaf with two parts on
 * either side of it, again the contract of partfile/order.h. Failing that, a
 * cutting plane of another direction (kd_cut.h) that leaves both halves
 * within K replaces the axis split when it crosses fewer triangles, or when
 * the axis split's halves would need splitting again: the leaf is then a
 * slab whose two planes coincide, its clipped vertices exactly on them
 * (plane_exact.h).
 */
#ifndef OIT_PARTITION_KD_H
#define OIT_PARTITION_KD_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "oit/partfile.h"
#include "oit/status.h"
#include "prepare/partition/kd_slab.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which slabs a node may become instead of being split on an axis. */
typedef enum oit_kd_slabs {
    OIT_KD_SLABS_ALL = 0,    /* separating (kd_slab.h), else cutting (kd_cut.h) */
    OIT_KD_SLABS_SEPARATING, /* only separating: nothing clipped off-axis */
    OIT_KD_SLABS_NONE        /* axis splits only */
} oit_kd_slabs;

typedef struct oit_kd_params {
    uint32_t max_layers; /* K */
    uint32_t max_depth;  /* splits below the cell; 0: 48 (16 halvings an axis) */
    /* Triangles the parts may hold in all (0: no limit): clipping dense,
     * mutually crossing geometry into K-layer boxes can multiply it many
     * times, and a clear refusal beats exhausting memory. */
    uint64_t max_triangles;
    oit_kd_slabs slabs; /* which slab kinds may end a node (0: both) */
} oit_kd_params;

/* The most layers a wide part may have (the renderer's widest capture). */
#define OIT_KD_MAX_WIDE_LAYERS OIT_PARTFILE_MAX_LAYERS

typedef struct oit_kd_node {
    float lo[3], hi[3];
    int32_t axis;   /* -1: leaf; else split on this axis at split */
    float split;
    uint32_t child; /* split: nodes child (below) and child + 1 (above) */
    int32_t part;   /* leaf: index into parts, or -1 when empty; with a slab,
                     * the part below it */
    int32_t slab;   /* leaf: index into slabs, or -1 */
    uint32_t depth; /* root 0 */
} oit_kd_node;

typedef struct oit_kd_piece {
    uint64_t triangle_count; /* consecutive triangles of the part */
    uint32_t plane_count;
} oit_kd_piece;

typedef struct oit_kd_part {
    size_t tri_first, tri_count;   /* into tris */
    uint32_t piece_first, piece_count;
    uint32_t layer_bound; /* sum over pieces: 1 when planar, else 2 */
} oit_kd_part;

/* A leaf holding two parts on either side of a slab. */
typedef struct oit_kd_slab_leaf {
    oit_kd_slab planes;
    uint32_t part_below, part_above; /* into parts */
} oit_kd_slab_leaf;

typedef struct oit_kd_result {
    oit_kd_node *nodes; /* nodes[0] is the cell; children follow parents */
    size_t node_count, node_cap;
    oit_kd_part *parts; /* in leaf order */
    size_t part_count, part_cap;
    oit_kd_piece *pieces;
    size_t piece_count, piece_cap;
    oit_triangle *tris; /* parts' triangles, piece by piece */
    size_t tri_count, tri_cap;
    /* Parallel to tris: each triangle's source index, that of the input
     * triangle it was clipped from (the build's src). Within a piece (the
     * fast scheme: a part) triangles keep their input order, so these
     * ascend there when the input's did. */
    uint32_t *src;
    size_t src_cap;
    oit_kd_slab_leaf *slabs;
    size_t slab_count, slab_cap;
    uint64_t split_added;  /* triangles added by the midplane clips */
    uint32_t depth;        /* deepest node */
    uint32_t wide_parts;   /* parts whose layer bound exceeds K */
    uint32_t cuts;         /* slabs that are cutting planes (kd_cut.h) */
    /* The fast scheme (kd_fast.h) only: parts whose measured layer count
     * exceeded OIT_PARTFILE_MAX_LAYERS after every extra split allowed,
     * recorded at that limit, and the largest count measured before the
     * clamp. 0 in this scheme. */
    uint32_t clamped_parts;
    uint32_t max_measured;
} oit_kd_result;

/* Subdivides the box [lo, hi] holding tris[0..n) with src[i] (its source
 * index, carried to every piece of it in out->src; NULL: i), piece[i]
 * (< piece_count) and plane[i] (the triangle's plane id within its piece,
 * < n) per triangle. The arrays are only read. Fails with OIT_ERR_UNSUPPORTED (message names the
 * box and the piece count) when a node of more than OIT_KD_MAX_WIDE_LAYERS
 * layers remains or when the parts would exceed max_triangles (the message
 * says which), or OIT_ERR_NOMEM. */
oit_status oit_kd_build(const float lo[3], const float hi[3], const oit_triangle *tris,
                        const uint32_t *src, size_t n, const uint32_t *piece,
                        const uint32_t *plane, uint32_t piece_count,
                        const oit_kd_params *params, oit_kd_result *out, oit_error *err);
/* src for a build whose triangles are their own sources: 0..n-1, malloc'd
 * (NULL for n = 0 or no memory). */
uint32_t *oit_kd_iota(size_t n);
void oit_kd_result_free(oit_kd_result *r);

/* Splits leaf `node` of r at pos[axis] = m into two empty leaves, below at
 * *child and above at *child + 1, one level deeper (r->depth follows); the
 * node becomes their parent. Shared by every scheme that builds r's tree
 * (kd.c, kd_fast.c). Fails only with OIT_ERR_NOMEM, r unchanged. */
oit_status oit_kd_add_children(oit_kd_result *r, size_t node, int axis, float m, size_t *child);

#ifdef __cplusplus
}
#endif
#endif
