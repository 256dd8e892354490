/* quads: the DFB paper's synthetic scene. N screen-aligned squares in the XY
 * plane facing +Z, each covering a fraction C of the [-1,1]^2 square, centred
 * with a small jitter, at N distinct depths in [-1, 1] visited in a scrambled
 * order so that drawing order is not depth order. A camera on +Z looking at
 * the origin sees every quad over the centre pixel (the jitter is bounded so
 * that the centre stays covered). */
#include "prepare/scenes/scene.h"

#include <math.h>

#include "prepare/scenes/rng.h"

uint64_t oit_scene_quads_estimate(const oit_scene_args *a)
{
    return 2 * a->count;
}

static uint64_t gcd_u64(uint64_t a, uint64_t b)
{
    while (b) {
        uint64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* A stride coprime with n: i -> (i * stride) % n is then a permutation, which
 * scrambles depth order in O(1) memory. */
static uint64_t scramble_stride(uint64_t n)
{
    uint64_t s = (uint64_t)(0.618033988749895 * (double)n) | 1;
    while (n > 1 && gcd_u64(s, n) != 1)
        s++;
    return s % (n ? n : 1);
}

oit_status oit_scene_quads(oit_emit *e, const oit_scene_args *a, oit_error *err)
{
    oit_rng rng = oit_rng_make(a->seed, 1);
    uint64_t n = a->count, stride = scramble_stride(n);
    float h = (float)sqrt(a->coverage); /* half side: (2h)^2 / 4 = C */
    /* Below h/2 the centre stays covered; below (1-h)/4 the square stays
     * inside [-1,1]^2. */
    float jitter = fminf(0.5f * h, 0.25f * (1.0f - h));
    for (uint64_t i = 0; i < n && !e->status; i++) {
        uint64_t slot = n > 1 ? (i * stride) % n : 0;
        float z = (float)(-1.0 + 2.0 * ((double)slot + 0.5) / (double)n);
        float cx = oit_rng_range(&rng, -jitter, jitter), cy = oit_rng_range(&rng, -jitter, jitter);
        uint8_t rgb[3];
        oit_scene_hsv((float)oit_rng_unit(&rng), 0.75f, 0.95f, rgb);
        oit_emit_color(e, rgb[0], rgb[1], rgb[2], (uint8_t)oit_rng_range(&rng, 51, 205));
        uint32_t q0 = oit_emit_vertex(e, oit_v3_make(cx - h, cy - h, z));
        uint32_t q1 = oit_emit_vertex(e, oit_v3_make(cx + h, cy - h, z));
        uint32_t q2 = oit_emit_vertex(e, oit_v3_make(cx + h, cy + h, z));
        uint32_t q3 = oit_emit_vertex(e, oit_v3_make(cx - h, cy + h, z));
        oit_emit_quad(e, q0, q1, q2, q3); /* counter-clockwise seen from +Z */
    }
    return e->status;
}

void oit_scene_hsv(float h, float s, float v, uint8_t rgb[3])
{
    float hh = (h - floorf(h)) * 6.0f, f = hh - floorf(hh);
    float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    float r, g, b;
    switch ((int)hh % 6) {
    case 0: r = v, g = t, b = p; break;
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    default: r = v, g = p, b = q; break;
    }
    rgb[0] = (uint8_t)lrintf(r * 255), rgb[1] = (uint8_t)lrintf(g * 255), rgb[2] = (uint8_t)lrintf(b * 255);
}
