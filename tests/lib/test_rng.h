/* A small deterministic generator for the property tests (random files,
 * views, packs): the same seed gives the same cases on every machine, so a
 * failure names a case that can be run again. */
#ifndef OIT_TESTS_TEST_RNG_H
#define OIT_TESTS_TEST_RNG_H

#include <stdint.h>

typedef struct rng {
    uint64_t s;
} rng;

/* Uniform-enough in [0, n), n > 0 (PCG's LCG step, high bits). */
static inline uint32_t rnd(rng *r, uint32_t n)
{
    r->s = r->s * 6364136223846793005u + 1442695040888963407u;
    return (uint32_t)((r->s >> 33) % n);
}

#endif
