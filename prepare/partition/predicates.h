/* Exact geometric predicates on double coordinates (float inputs convert to
 * double exactly). A double-precision evaluation with a proven error bound
 * (Shewchuk's orient3d/orient2d stage A bounds) answers almost every call; the
 * rest go to CGAL's Exact_predicates_inexact_constructions_kernel, which is
 * exact. Results are signs: +1, 0, -1. Thread-safe, no state. */
#ifndef OIT_PARTITION_PREDICATES_H
#define OIT_PARTITION_PREDICATES_H

#ifdef __cplusplus
extern "C" {
#endif

/* Sign of det[b-a; c-a; d-a] (CGAL's convention): +1 when d lies on the
 * side of the plane a, b, c that ((b-a) x (c-a)) points to. */
int oit_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]);

/* Sign of det[b-a; c-a] of a, b, c projected on the coordinate plane that
 * drops axis `drop` (0, 1 or 2), keeping axes (drop+1)%3, (drop+2)%3 in that
 * order: +1 counter-clockwise. Equals the sign of the normal's `drop`
 * component, so coplanar triangles compare facing by it. */
int oit_orient2d(const double a[3], const double b[3], const double c[3], int drop);

/* The exact fallbacks (CGAL), exposed for tests that compare the filter. */
int oit_orient3d_exact(const double a[3], const double b[3], const double c[3], const double d[3]);
int oit_orient2d_exact(const double a[2], const double b[2], const double c[2]);

/* 1 when a, b, c are collinear (or coincide): the triangle has no plane.
 * Exact: all three coordinate projections have orientation 0. */
int oit_triangle_degenerate(const double a[3], const double b[3], const double c[3]);

#ifdef __cplusplus
}
#endif
#endif
