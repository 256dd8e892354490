// Exact orientation through CGAL (predicates.h). CGAL's Epick kernel filters
// with interval arithmetic and falls back to exact multiprecision, so these
// signs are exact for any double input.
#include "prepare/partition/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;

extern "C" int oit_orient3d_exact(const double a[3], const double b[3], const double c[3],
                                  const double d[3])
{
    Kernel::Point_3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]), pc(c[0], c[1], c[2]),
        pd(d[0], d[1], d[2]);
    switch (CGAL::orientation(pa, pb, pc, pd)) {
    case CGAL::POSITIVE: return 1;
    case CGAL::NEGATIVE: return -1;
    default: return 0;
    }
}

extern "C" int oit_orient2d_exact(const double a[2], const double b[2], const double c[2])
{
    Kernel::Point_2 pa(a[0], a[1]), pb(b[0], b[1]), pc(c[0], c[1]);
    switch (CGAL::orientation(pa, pb, pc)) {
    case CGAL::POSITIVE: return 1;
    case CGAL::NEGATIVE: return -1;
    default: return 0;
    }
}
