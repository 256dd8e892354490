/* Minimum and maximum of finite values as plain compares.
 *
 * fminf/fmaxf honour NaN and so stay library calls without
 * -ffinite-math-only; in the per-vertex loops of binning, clipping and the
 * kd subdivision they took 18% of oitprep's time. Coordinates there are
 * finite (readers drop non-finite triangles), so a compare is exact.
 *
 * NaN: oit_min_f(a, b) is b < a ? b : a, so a NaN b leaves a as it was, as
 * fminf does; only a NaN a differs (kept). A running bound that starts at
 * +-infinity is never NaN, and there the two agree on every input. */
#ifndef OIT_BASE_MINMAX_H
#define OIT_BASE_MINMAX_H

static inline float oit_min_f(float a, float b) { return b < a ? b : a; }
static inline float oit_max_f(float a, float b) { return b > a ? b : a; }
static inline double oit_min_d(double a, double b) { return b < a ? b : a; }
static inline double oit_max_d(double a, double b) { return b > a ? b : a; }

#endif
