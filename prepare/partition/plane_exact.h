/* Planes that clipped geometry lies on exactly, not within rounding.
 *
 * A plane n.x = d with a float normal cannot hold a clipped vertex exactly:
 * the point where an edge meets it rounds off it, and the order's and the
 * verifier's evaluation of n.x may then put that vertex on the wrong side.
 * Here the normal is an integer vector whose largest component n[axis] is
 * a power of two, d is a multiple of a power-of-two grain, and a seam
 * vertex takes its other two coordinates as multiples of the grain: then
 * d - sum n[j] x[j] is exact in double and so is its quotient by n[axis],
 * which the grain (chosen from the box by oit_plane_exact_init) keeps
 * representable in float. The seam vertex moves off the true edge point by
 * about a grain, a few float ulps of the box's largest coordinate. Where a
 * corner lies within a grain of the plane, that can fold a sliver a grain
 * wide back over its neighbour, as the axis clip's rounding can: a line
 * through the fold meets the piece again at the same depth (verify counts
 * such hits as one layer, as a rasterizer's fill rule would). Refusing cuts
 * with any such fold tripled head.stl's triangles (453K -> 1.36M): its many
 * slivers have normals no sign test can trust.
 *
 * Sides are decided exactly (error-free sums), whatever the magnitudes. */
#ifndef OIT_PARTITION_PLANE_EXACT_H
#define OIT_PARTITION_PLANE_EXACT_H

#include "oit/mesh.h"

typedef struct oit_plane_exact {
    int n[3];     /* |n[axis]| is the largest component and a power of two */
    int axis;
    double d;     /* a multiple of grain */
    double grain; /* a power of two */
} oit_plane_exact;

/* The grain for normal n over the box [lo, hi]: the smallest power of two
 * at which every multiple inside the box, and every solved coordinate, is
 * a float. Sets n's axis. */
void oit_plane_exact_init(oit_plane_exact *pl, const int n[3], const float lo[3],
                          const float hi[3]);

/* The sign of n.p - d, exactly. */
int oit_plane_exact_side(const oit_plane_exact *pl, const float p[3]);

/* The sign of n.p - d for any float normal, exactly (a product of two
 * floats is exact in double): how the verifier and the tests judge a
 * vertex against a slab's planes as stored. */
int oit_plane_side_exact(const float n[3], double d, const float p[3]);

/* The vertex where edge p-q, its ends strictly on opposite sides, meets the
 * plane: on it exactly, inside the box [lo, hi], the same bits whichever
 * way round the edge is given. Colour is interpolated. Returns 0 when no
 * grain point near the edge point lies inside the box (a box thinner than
 * the grain). */
int oit_plane_exact_seam(const oit_plane_exact *pl, const oit_vertex *p, const oit_vertex *q,
                         const float lo[3], const float hi[3], oit_vertex *out);

/* Splits t into its closed halves below (n.x <= d) and above, at most 2
 * triangles each, with seams from oit_plane_exact_seam. A triangle lying in
 * the plane goes below only. Returns 0 when a seam could not be placed. */
int oit_plane_exact_split(const oit_plane_exact *pl, const oit_triangle *t, const float lo[3],
                          const float hi[3], oit_triangle *below, int *n_below,
                          oit_triangle *above, int *n_above);

#endif
