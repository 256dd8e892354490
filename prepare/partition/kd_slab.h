/* Separating slabs for kd nodes (Wang & Xie section 4.2, kd.h).
 *
 * A node of at most 2K layers whose pieces no axis plane separates without
 * cutting one (pipes and beams running diagonally past each other, two
 * interlocking parts) may still have its pieces fall into two groups of at
 * most K layers each that a plane of some other direction separates: two
 * disjoint convex bodies always have one. Such a node becomes a slab cell:
 * one part below the slab's planes, one above, nothing clipped, no triangle
 * added.
 *
 * The planes n.x = d0 <= d1 hold with a gap in exact arithmetic for the
 * float normal as stored: every vertex of the lower group has n.x <= d0 and
 * every vertex of the upper group n.x >= d1, the bounds computed in double
 * and rounded outward, so the stream's order (partfile/order.c) and the
 * verifier see the groups on their sides however they evaluate n.x. Groups
 * that only touch (a gap below rounding) do not qualify: a pixel where two
 * parts coincide would be ordered by pack, not by primitive id.
 *
 * Pieces that share a vertex cannot be parted by a gap, so they form one
 * group (union-find over exact positions); a node of one group, or with a
 * group over K, has no slab.
 *
 * Directions tried: the 13 axis, face-diagonal and body-diagonal directions,
 * the line between every two groups' box centres, and the normals of up to
 * OIT_KD_SLAB_PLANES_PER_PIECE triangles of each piece (for convex polyhedra
 * a face normal separates whenever anything does). A direction is skipped
 * unseen when the spans of each group's 26 corners extreme along the fixed
 * directions (inside its true span) cannot beat the best gap so far. The
 * widest gap, relative to the node's size, wins. */
#ifndef OIT_PARTITION_KD_SLAB_H
#define OIT_PARTITION_KD_SLAB_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"

#define OIT_KD_SLAB_PLANES_PER_PIECE 8

typedef struct oit_kd_slab {
    float normal[3]; /* unit within float rounding */
    float d0, d1;    /* d0 <= d1 */
} oit_kd_slab;

/* The node's triangles tris[0..n) belong to pieces slot[i] < npieces whose
 * layers in the node are weight[slot]. On success (1) side[slot] is 0 for
 * the group below the slab and 1 above, and both groups weigh at most
 * max_layers. Returns 0 when no direction separates such groups, -1 when
 * memory runs out. O(n log n) to group, then per direction O(npieces) to
 * rule it out, O(n) to measure it. */
int oit_kd_find_slab(const oit_triangle *tris, size_t n, const uint32_t *slot,
                     const uint32_t *weight, uint32_t npieces, uint32_t max_layers,
                     oit_kd_slab *slab, uint8_t *side);

#endif
