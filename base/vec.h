/* 3-vectors as plain arrays, in float and in double, header-only.
 *
 * Each function is the expression written out in one fixed order, and the
 * build turns contraction off (-ffp-contract=off), so a file that swaps its
 * own copy for one of these computes the same bits: images and part files
 * do not move. A copy whose arithmetic differs (a float product summed in
 * double, a normalize without the zero guard, an exact predicate of
 * partition/) is not one of these and stays where it is. */
#ifndef OIT_BASE_VEC_H
#define OIT_BASE_VEC_H

#include <math.h>

/* a.b, summed left to right: (a0 b0 + a1 b1) + a2 b2. */
static inline double oit_dot3d(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out = a x b (right-handed); out may not alias a or b. */
static inline void oit_cross3d(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Returns |v| = sqrt(v.v) and divides v by it when it is > 0; a zero or NaN
 * length leaves v as it was, so callers test the result (> 0) instead of
 * meeting NaN. An infinite length divides (v becomes 0 or NaN). */
static inline double oit_normalize3d(double v[3])
{
    double len = sqrt(oit_dot3d(v, v));
    if (len > 0.0)
        for (int k = 0; k < 3; k++)
            v[k] /= len;
    return len;
}

/* a.b in float, summed left to right. */
static inline float oit_dot3f(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out = a - b in float; out may alias a or b. */
static inline void oit_sub3f(const float a[3], const float b[3], float out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

/* out = a x b in float; out may not alias a or b. */
static inline void oit_cross3f(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* oit_normalize3d in float (sqrtf): returns |v|, divides only when > 0. */
static inline float oit_normalize3f(float v[3])
{
    float len = sqrtf(oit_dot3f(v, v));
    if (len > 0.0f)
        for (int k = 0; k < 3; k++)
            v[k] /= len;
    return len;
}

#endif
