/* 3-vectors as plain arrays, in float and in double, header-only.
 *
 * Each function is the expression written out in one fixed order, and the
 * build turns contraction off (-ffp-contract=off), so a file that swaps its
 * own copy for one of these computes the same bits: images and part files
 * do not move. A copy whose arithmetic differs (a float product summed in
 * double, a normalize without the zero guard, an exact predicate of
 * prepare/partition/) is not one of these and stays where it is.
 *
 * For S = d (double, sqrt) and S = f (float, sqrtf), with T its type:
 *
 *   T    oit_dot3S(a, b)         a.b summed left to right: (a0 b0 + a1 b1) + a2 b2
 *   void oit_sub3S(a, b, out)    out = a - b; out may alias a or b
 *   void oit_cross3S(a, b, out)  out = a x b (right-handed); out may not alias
 *   T    oit_normalize3S(v)      returns |v| = sqrt(v.v) and divides v by it
 *                                when it is > 0; a zero or NaN length leaves v
 *                                as it was (callers test the result > 0), an
 *                                infinite one divides (v becomes 0 or NaN)
 *
 * and, for float corners measured in double:
 *
 *   void   oit_sub3fd(a, b, out) out = a - b of float a, b in double: exact
 *   double oit_area3fd(a, b, c)  the area of triangle abc, |(b-a) x (c-a)| / 2,
 *                                the edges exact and the products in double
 *
 * One template for both types, as base/sort.h does, so the two cannot drift. */
#ifndef OIT_BASE_VEC_H
#define OIT_BASE_VEC_H

#include <math.h>

#define OIT_VEC3_DEFINE(S, T, SQRT)                                                       \
    static inline T oit_dot3##S(const T a[3], const T b[3])                               \
    {                                                                                     \
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];                                   \
    }                                                                                     \
    static inline void oit_sub3##S(const T a[3], const T b[3], T out[3])                  \
    {                                                                                     \
        for (int k = 0; k < 3; k++)                                                       \
            out[k] = a[k] - b[k];                                                         \
    }                                                                                     \
    static inline void oit_cross3##S(const T a[3], const T b[3], T out[3])                \
    {                                                                                     \
        out[0] = a[1] * b[2] - a[2] * b[1];                                               \
        out[1] = a[2] * b[0] - a[0] * b[2];                                               \
        out[2] = a[0] * b[1] - a[1] * b[0];                                               \
    }                                                                                     \
    static inline T oit_normalize3##S(T v[3])                                             \
    {                                                                                     \
        T len = SQRT(oit_dot3##S(v, v));                                                  \
        if (len > (T)0)                                                                   \
            for (int k = 0; k < 3; k++)                                                   \
                v[k] /= len;                                                              \
        return len;                                                                       \
    }

OIT_VEC3_DEFINE(d, double, sqrt)
OIT_VEC3_DEFINE(f, float, sqrtf)

static inline void oit_sub3fd(const float a[3], const float b[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = (double)a[k] - (double)b[k];
}

static inline double oit_area3fd(const float a[3], const float b[3], const float c[3])
{
    double u[3], v[3], n[3];
    oit_sub3fd(b, a, u);
    oit_sub3fd(c, a, v);
    oit_cross3d(u, v, n);
    return 0.5 * sqrt(oit_dot3d(n, n));
}

#endif
