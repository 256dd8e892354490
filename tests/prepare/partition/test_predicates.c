/* prepare/partition/predicates.h: exact orient3d where the double filter cannot
 * decide (near-coplanar points the plain double determinant gets wrong),
 * and exactly collinear triangles. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "prepare/partition/predicates.h"
#include "tests/lib/test_check.h"

static int sign_i64(int64_t v) { return (v > 0) - (v < 0); }

/* For a = e_x, b = e_y, c = e_z, det[b-a; c-a; d-a] = dx + dy + dz - 1. With
 * every coordinate a multiple of 2^-55 below 1, the sum is exact in int64. */
static int plane_sign_exact(const double d[3])
{
    int64_t s = -((int64_t)1 << 55);
    for (int k = 0; k < 3; k++)
        s += (int64_t)ldexp(d[k], 55);
    return sign_i64(s);
}

static int naive_orient3d(const double a[3], const double b[3], const double c[3],
                          const double d[3])
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0]);
    return (det > 0) - (det < 0);
}

static void test_predicates(void)
{
    const double o[3] = {0, 0, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    const double below[3] = {0.25, 0.25, -0.5}, on[3] = {3, -7, 0};
    CHECK(oit_orient3d(o, ex, ey, ez) == 1, "unit tetrahedron must be +1");
    CHECK(oit_orient3d(o, ey, ex, ez) == -1, "swapped tetrahedron must be -1");
    CHECK(oit_orient3d(o, ex, ey, below) == -1, "point below z=0 must be -1");
    CHECK(oit_orient3d(o, ex, ey, on) == 0, "point in z=0 must be 0");

    /* d = (x, y, 1 - x - y rounded, then nudged by -1..+1 ulp): within 1e-16
     * of the plane x+y+z=1, where the double determinant's error bound
     * (~1e-15) exceeds its value. */
    int counts[3] = {0, 0, 0}, naive_wrong = 0, cases = 0;
    for (int i = 0; i < 40; i++)
        for (int j = 0; j < 40; j++)
            for (int nudge = -1; nudge <= 1; nudge++) {
                double d[3];
                d[0] = 0.125 + i * (0.1 / 40.0);
                d[1] = 0.125 + j * (0.1 / 41.0);
                d[2] = 1.0 - d[0] - d[1];
                if (nudge)
                    d[2] = nextafter(d[2], nudge > 0 ? 2.0 : 0.0);
                int want = plane_sign_exact(d);
                int got = oit_orient3d(ex, ey, ez, d);
                CHECK(got == want, "orient3d(e_x,e_y,e_z,(%.17g,%.17g,%.17g)) = %d, exact %d",
                      d[0], d[1], d[2], got, want);
                CHECK(oit_orient3d_exact(ex, ey, ez, d) == want, "exact fallback disagrees");
                counts[want + 1]++;
                naive_wrong += naive_orient3d(ex, ey, ez, d) != want;
                cases++;
            }
    printf("predicates: %d near-coplanar cases: %d negative, %d zero, %d positive; "
           "naive double determinant wrong on %d\n",
           cases, counts[0], counts[1], counts[2], naive_wrong);
    CHECK(counts[0] > 0 && counts[1] > 0 && counts[2] > 0, "cases must cover all three signs");
    CHECK(naive_wrong > 0, "cases must include some the plain double determinant gets wrong");

    const double p[3] = {0.1, 0.2, 0.3}, q[3] = {0.2, 0.4, 0.6}, r[3] = {0.4, 0.8, 1.2};
    const double r2[3] = {0.4, 0.8, nextafter(1.2, 2.0)};
    /* 0.1*2, 0.2*2, ... are exact doublings, so p, q, r are exactly collinear. */
    CHECK(oit_triangle_degenerate(p, q, r) == 1, "exactly collinear points");
    CHECK(oit_triangle_degenerate(p, q, r2) == 0, "collinear up to one ulp is not degenerate");
}

int main(void)
{
    test_predicates();
    return test_verdict();
}
