/* Deterministic PRNG for the scene generators (splitmix64).
 *
 * Scenes must give the same bytes for the same arguments on every run, so
 * every random choice comes from an oit_rng seeded from the caller's seed; the state is
 * a value owned by the caller (no global state). Independent streams (one per
 * block, per instance...) come from oit_rng_make(seed, stream) so that a
 * change in one part of a scene does not shift the numbers of the others. */
#ifndef OIT_SCENES_RNG_H
#define OIT_SCENES_RNG_H

#include <stdint.h>

typedef struct oit_rng {
    uint64_t state;
} oit_rng;

static inline uint64_t oit_rng_next(oit_rng *r)
{
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static inline oit_rng oit_rng_make(uint64_t seed, uint64_t stream)
{
    oit_rng r = {seed ^ (stream * 0xD1B54A32D192ED03ull)};
    oit_rng_next(&r);
    return r;
}

/* Uniform in [0, 1). */
static inline double oit_rng_unit(oit_rng *r)
{
    return (double)(oit_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [lo, hi). */
static inline float oit_rng_range(oit_rng *r, float lo, float hi)
{
    return lo + (hi - lo) * (float)oit_rng_unit(r);
}

/* Uniform integer in [0, n), n > 0. */
static inline uint32_t oit_rng_below(oit_rng *r, uint32_t n)
{
    return (uint32_t)(oit_rng_unit(r) * n);
}

#endif
