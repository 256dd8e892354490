/* Cutting planes for kd nodes: Wang & Xie's slab (section 4.1) at thickness
 * zero, for nodes that neither an axis plane splits cleanly nor a
 * separating slab (kd_slab.h) parts.
 *
 * A node of at most 2K layers whose pieces interlock (a pipe through a
 * ring, beams crossing diagonally) must be cut somewhere. The kd's axis
 * split cuts along a world axis and then recurses; a plane of another
 * direction may cut far fewer triangles and leave two halves of at most K
 * layers at once: the node becomes one part on each side of the plane,
 * stored as a slab whose planes coincide (d0 = d1), with no inside part.
 *
 * Exactness. The order (partfile/order.c) and the verifier put a part on the
 * plane's side by evaluating n.x, so a clipped vertex must lie on the plane
 * exactly, not within rounding. The normal is therefore an integer vector
 * whose largest component is a power of two (plane_exact.h): a seam vertex
 * takes its other coordinates as multiples of a power-of-two grain and
 * solves the plane for the largest one, which is then exact in float.
 * Directions tried: the OIT_KD_CUT_DIRS primitive integer vectors with
 * components in [-2, 2] (the axes, the face and body diagonals, and 36
 * directions between them, at most 18 degrees from any direction).
 *
 * The plane is placed strictly between two consecutive ends of the
 * triangles' spans along n, so it crosses every triangle it cuts properly
 * (a middle vertex may still lie on it: sides are decided exactly, and such
 * a vertex belongs to both halves). Among the placements that leave both
 * halves at most K
 * layers (a cut piece counts in both, with its weight in the node), the one
 * that cuts fewest triangles wins, then the most even one. */
#ifndef OIT_PARTITION_KD_CUT_H
#define OIT_PARTITION_KD_CUT_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "prepare/partition/plane_exact.h"

#define OIT_KD_CUT_DIRS 49

typedef struct oit_kd_cut {
    oit_plane_exact plane;
    uint32_t cut; /* triangles the plane crosses */
} oit_kd_cut;

/* The node's triangles tris[0..n) belong to pieces slot[i] < npieces of
 * layers weight[slot]; the node's box is [lo, hi]. Returns 1 and the
 * cheapest cut that leaves both halves within max_layers and crosses at
 * most max_cut triangles, 0 when none does, -1 when memory runs out.
 * O(n log n) per direction. */
int oit_kd_find_cut(const oit_triangle *tris, size_t n, const uint32_t *slot,
                    const uint32_t *weight, uint32_t npieces, uint32_t max_layers,
                    const float lo[3], const float hi[3], uint32_t max_cut, oit_kd_cut *cut);

#endif
