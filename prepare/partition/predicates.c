/* Filtered predicates (predicates.h): the determinant in double with
 * Shewchuk's stage-A error bound; only when |det| is within the bound (nearly
 * or exactly degenerate input) is the exact CGAL predicate called. */
#include "prepare/partition/predicates.h"

#include <float.h>
#include <math.h>

/* Shewchuk's epsilon is half an ulp of 1: 2^-53. */
#define PRED_EPS (DBL_EPSILON * 0.5)
#define O3D_BOUND ((7.0 + 56.0 * PRED_EPS) * PRED_EPS)
#define O2D_BOUND ((3.0 + 16.0 * PRED_EPS) * PRED_EPS)

int oit_orient3d(const double a[3], const double b[3], const double c[3], const double d[3])
{
    /* Shewchuk's orient3d(a, b, c, d) = det[a-d; b-d; c-d] = -det[b-a; c-a; d-a]. */
    double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
    double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
    double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    double cdxady = cdx * ady, adxcdy = adx * cdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady;
    double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    double perm = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) +
                  (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                  (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
    double bound = O3D_BOUND * perm;
    if (det > bound)
        return -1;
    if (-det > bound)
        return 1;
    return oit_orient3d_exact(a, b, c, d);
}

int oit_orient2d(const double a[3], const double b[3], const double c[3], int drop)
{
    int u = (drop + 1) % 3, v = (drop + 2) % 3;
    double detl = (b[u] - a[u]) * (c[v] - a[v]);
    double detr = (b[v] - a[v]) * (c[u] - a[u]);
    double det = detl - detr;
    double bound = O2D_BOUND * (fabs(detl) + fabs(detr));
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    double pa[2] = {a[u], a[v]}, pb[2] = {b[u], b[v]}, pc[2] = {c[u], c[v]};
    return oit_orient2d_exact(pa, pb, pc);
}

int oit_triangle_degenerate(const double a[3], const double b[3], const double c[3])
{
    for (int k = 0; k < 3; k++)
        if (oit_orient2d(a, b, c, k) != 0)
            return 0;
    return 1;
}
