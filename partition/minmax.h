/* Minimum and maximum of finite values as plain compares.
 *
 * fminf/fmaxf honour NaN and so stay library calls without
 * -ffinite-math-only; in the per-vertex loops of binning, clipping and the
 * kd subdivision they took 18% of oitprep's time. Coordinates there are
 * finite (readers drop non-finite triangles), so a compare is exact. */
#ifndef OIT_PARTITION_MINMAX_H
#define OIT_PARTITION_MINMAX_H

static inline float oit_min_f(float a, float b) { return b < a ? b : a; }
static inline float oit_max_f(float a, float b) { return b > a ? b : a; }
static inline double oit_min_d(double a, double b) { return b < a ? b : a; }
static inline double oit_max_d(double a, double b) { return b > a ? b : a; }

#endif
