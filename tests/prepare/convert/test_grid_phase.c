/* prepare/convert/grid_phase.h: the chosen phase crosses as few triangles as any
 * of the 256 (counted here by brute force, face by face), wrapped intervals
 * included, and the grid still covers the model. */
#include "prepare/convert/grid_phase.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/lib/test_check.h"

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* Triangles crossed by a face of the grid (origin o, cell c) on axis k. */
static uint64_t crossed(const oit_triangle *t, size_t n, int k, double o, double c)
{
    uint64_t m = 0;
    for (size_t i = 0; i < n; i++) {
        double lo = fmin(fmin(t[i].v[0].pos[k], t[i].v[1].pos[k]), t[i].v[2].pos[k]);
        double hi = fmax(fmax(t[i].v[0].pos[k], t[i].v[1].pos[k]), t[i].v[2].pos[k]);
        double f = o + ceil((lo - o) / c) * c; /* first face at or above lo */
        if (f == lo)
            f += c;
        m += f < hi;
    }
    return m;
}

static void run(uint32_t seed, size_t n, float width)
{
    oit_triangle *t = calloc(n, sizeof *t);
    float mn[3] = {1e9f, 1e9f, 1e9f}, mx[3] = {-1e9f, -1e9f, -1e9f};
    for (size_t i = 0; i < n; i++)
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                /* Clustered: most triangles start near 0.3 or 0.95 of a cell,
                 * so some phases cross many and the wrap at 1 is exercised. */
                float base = (float)(lcg(&seed) % 7) + (lcg(&seed) % 2 ? 0.3f : 0.95f);
                float p = base + width * (float)(lcg(&seed) % 1000) / 1000.0f * (v ? 1.0f : 0.0f);
                t[i].v[v].pos[k] = v == 0 ? base : p;
                mn[k] = fminf(mn[k], t[i].v[v].pos[k]);
                mx[k] = fmaxf(mx[k], t[i].v[v].pos[k]);
            }
    oit_bin_grid g = {{0, 0, 0}, 1.0f, {8, 8, 8}};
    oit_grid_phase ph;
    oit_grid_phase_init(&ph, &g);
    oit_grid_phase_add(&ph, t, n);
    oit_grid_phase_apply(&ph, mn, mx, &g);
    for (int k = 0; k < 3; k++) {
        uint64_t best = UINT64_MAX;
        for (int b = 0; b < OIT_GRID_PHASES; b++) {
            uint64_t c = crossed(t, n, k, b / 256.0, 1.0);
            best = c < best ? c : best;
        }
        uint64_t got = crossed(t, n, k, g.origin[k], 1.0);
        CHECK(got == best, "seed %u axis %d: the phase crosses %llu, the best %llu", seed, k,
              (unsigned long long)got, (unsigned long long)best);
        CHECK(g.origin[k] <= mn[k] && g.origin[k] + g.dims[k] * g.cell > mx[k],
              "seed %u axis %d: grid [%g, +%u cells) misses [%g, %g]", seed, k, g.origin[k],
              g.dims[k], mn[k], mx[k]);
        CHECK(g.origin[k] * 256.0f == floorf(g.origin[k] * 256.0f),
              "axis %d: origin %g is not a multiple of cell / 256", k, g.origin[k]);
    }
    free(t);
}

int main(void)
{
    run(1, 500, 0.2f);   /* narrow: a free phase exists */
    run(2, 500, 0.6f);   /* wide, wrapping past the cell's end */
    run(3, 200, 1.5f);   /* some wider than a cell: cross every phase */
    return test_verdict();
}
