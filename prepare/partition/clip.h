/* Watertight clipping of triangles and convex polygons against axis-aligned
 * planes.
 *
 * A new vertex is computed from the two endpoints of the edge it splits,
 * taken in canonical (lexicographic) order, in double precision: the same
 * edge seen from the triangle on either side, or from the cell on either side
 * of the plane, yields the same bits. The split coordinate is set to the
 * plane exactly and the others are clamped to the edge's range, so clipped
 * geometry lies inside the closed half-space (and a clipped part inside its
 * closed cell box) in float, without rounding outside. Colours are
 * interpolated the same way.
 */
#ifndef OIT_PARTITION_CLIP_H
#define OIT_PARTITION_CLIP_H

#include <stddef.h>

#include "oit/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A triangle clipped by up to 6 planes has at most 9 vertices. */
#define OIT_CLIP_MAX_VERTS 9
#define OIT_CLIP_MAX_TRIS (OIT_CLIP_MAX_VERTS - 2)

/* Clips the convex polygon in[0..n) to the closed half-space
 * pos[axis] <= c (keep_below != 0) or pos[axis] >= c. Writes at most n + 1
 * vertices to out (which must not alias in) and returns their count (0 when
 * nothing remains, possibly 1 or 2 when only a point or edge touches). */
int oit_clip_polygon(const oit_vertex *in, int n, int axis, float c, int keep_below,
                     oit_vertex *out);

/* Fan-triangulates the convex polygon v[0..n) into out, dropping triangles
 * that are exactly degenerate. Returns the number written (<= n - 2). */
int oit_polygon_triangulate(const oit_vertex *v, int n, oit_triangle *out);

/* Clips t to the closed box [lo, hi] and triangulates what remains into out
 * (room for OIT_CLIP_MAX_TRIS). A triangle that lies inside the box is copied
 * unchanged. Returns the count. */
int oit_clip_triangle_box(const oit_triangle *t, const float lo[3], const float hi[3],
                          oit_triangle *out);

/* Splits t at pos[axis] = c into the closed halves; below and above get at
 * most 2 triangles each. A triangle lying in the plane goes to the lower half
 * only, so no surface is stored twice. */
void oit_clip_triangle_split(const oit_triangle *t, int axis, float c, oit_triangle *below,
                             int *n_below, oit_triangle *above, int *n_above);

/* Lexicographic order on position, then colour: the canonical order in
 * which an edge's new vertex is computed, so both triangles sharing the
 * edge get the same bits. */
int oit_vertex_less(const oit_vertex *a, const oit_vertex *b);

/* 1 when the three positions are collinear (exact). */
int oit_triangle_is_degenerate(const oit_triangle *t);

#ifdef __cplusplus
}
#endif
#endif
