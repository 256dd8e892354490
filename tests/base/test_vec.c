/* base/vec.h by its contracts: the cross product's handedness, the dot
 * product's summation order (the order the copies it replaced used, on
 * which byte-identical images depend: a different order gives 1, not 0,
 * below), normalize's length, zero and NaN guard, in double and float, and
 * the float corners measured in double (exact edges, triangle area). */
#include "base/vec.h"

#include <math.h>
#include <string.h>

#include "tests/lib/test_check.h"

static void test_double(void)
{
    const double x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    double z[3];
    oit_cross3d(x, y, z);
    CHECK(z[0] == 0 && z[1] == 0 && z[2] == 1, "x cross y = (%g, %g, %g), want +z", z[0], z[1],
          z[2]);
    const double a[3] = {2, -3, 5}, b[3] = {-7, 11, 13};
    double c[3];
    oit_cross3d(a, b, c);
    CHECK(c[0] == -94 && c[1] == -61 && c[2] == 1, "a cross b = (%g, %g, %g), want (-94, -61, 1)",
          c[0], c[1], c[2]);
    CHECK(oit_dot3d(a, b) == 2 * -7 + -3 * 11 + 5 * 13, "a.b = %g", oit_dot3d(a, b));
    /* (1 + 1e16) rounds to 1e16 before -1e16 comes in: left to right is 0;
     * summing the last two first would give 1. */
    const double big[3] = {1, 1e16, -1e16}, ones[3] = {1, 1, 1};
    CHECK(oit_dot3d(big, ones) == 0.0, "dot summed out of order: %g, want 0", oit_dot3d(big, ones));

    double v[3] = {3, 0, 4};
    double len = oit_normalize3d(v);
    CHECK(len == 5 && v[0] == 0.6 && v[1] == 0 && v[2] == 0.8, "|(3,0,4)| = %g -> (%g, %g, %g)",
          len, v[0], v[1], v[2]);
    double zero[3] = {0, -0.0, 0};
    CHECK(oit_normalize3d(zero) == 0.0 && zero[0] == 0 && signbit(zero[1]) && zero[2] == 0,
          "a zero vector must come back 0 and unchanged");
    double bad[3] = {NAN, 1, 2};
    double nlen = oit_normalize3d(bad);
    CHECK(!(nlen > 0.0) && isnan(bad[0]) && bad[1] == 1 && bad[2] == 2,
          "a NaN vector must not pass as normalized and stay unchanged (len %g, v1 %g)", nlen,
          bad[1]);
}

static void test_float(void)
{
    const float x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    float z[3];
    oit_cross3f(y, x, z);
    CHECK(z[0] == 0 && z[1] == 0 && z[2] == -1, "y cross x = (%g, %g, %g), want -z", z[0], z[1],
          z[2]);
    /* 1e8f has an ulp of 8: 1 + 1e8 is 1e8, so left to right gives 0. */
    const float big[3] = {1, 1e8f, -1e8f}, ones[3] = {1, 1, 1};
    CHECK(oit_dot3f(big, ones) == 0.0f, "float dot summed out of order: %g",
          oit_dot3f(big, ones));
    float a[3] = {5, 7, 9}, b[3] = {1, 2, 3};
    oit_sub3f(a, b, a); /* aliasing allowed */
    CHECK(a[0] == 4 && a[1] == 5 && a[2] == 6, "a - b = (%g, %g, %g)", a[0], a[1], a[2]);
    float v[3] = {0, 3, 4};
    float len = oit_normalize3f(v);
    CHECK(len == 5.0f && v[0] == 0 && v[1] == 0.6f && v[2] == 0.8f, "|(0,3,4)| = %g -> (%g, %g)",
          len, v[1], v[2]);
    float zero[3] = {0, 0, 0};
    CHECK(oit_normalize3f(zero) == 0.0f && zero[0] == 0 && zero[1] == 0 && zero[2] == 0,
          "a zero float vector must come back 0 and unchanged");
}

/* Float corners measured in double: the edge is exact where float
 * arithmetic would round (1e8 - 1 has no float: its ulp there is 8). */
static void test_float_in_double(void)
{
    const float a[3] = {1e8f, 0, 0}, b[3] = {1, 0, 0};
    double d[3];
    oit_sub3fd(a, b, d);
    CHECK(d[0] == 99999999.0, "1e8 - 1 in double = %.1f, want 99999999 (not rounded in float)",
          d[0]);
    const float p[3] = {1e7f, 0, 5}, q[3] = {1e7f + 4, 0, 5}, r[3] = {1e7f, 3, 5};
    CHECK(oit_area3fd(p, q, r) == 6.0, "area of the 3-4-5 triangle = %g, want 6",
          oit_area3fd(p, q, r));
    CHECK(oit_area3fd(p, p, r) == 0.0, "a degenerate triangle has area %g", oit_area3fd(p, p, r));
}

int main(void)
{
    test_double();
    test_float();
    test_float_in_double();
    return test_verdict();
}
