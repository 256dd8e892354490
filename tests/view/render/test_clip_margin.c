/* The section planes' box culling (clip.h, oit_clip_box_outside, which
 * the streamer uses to skip whole parts) as a property over random planes
 * and boxes placed at, just inside and just outside every margin, against
 * the per-pixel test itself (oit_clip_keeps on oit_clip_eye's float planes,
 * what the reference and the fragment stage run) and the exact signed
 * distance in long double:
 *  - sound: a culled box has no corner the per-pixel test keeps, and none
 *    within 1e-6 of the sum's scale of the plane (the rounding of a hit
 *    point o + dir t and of the float plane: a few ulps of the scale);
 *  - useful: a box wholly beyond 1e-3 of that scale on the removed side of
 *    one plane is culled (no real gap is smaller).
 * Boxes sit at offsets 0, +-1e-9 .. +-1e-4 and +-1e-2 of the scale from
 * the plane, their face parallel or a corner first, with 1..6 planes of
 * which the others keep everything. Seeded, no GL. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "view/render/image/clip.h"
#include "tests/lib/test_check.h"

static uint32_t rnd(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static double uni(uint32_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (rnd(s) / 4294967296.0);
}

/* Exact enough: the float plane and corner, summed in long double. */
static long double dist(const float p[4], const float c[3])
{
    return (long double)p[0] * c[0] + (long double)p[1] * c[1] + (long double)p[2] * c[2] +
           (long double)p[3];
}

static double scale_of(const float p[4], const float lo[3], const float hi[3])
{
    double s = fabs((double)p[3]);
    for (int k = 0; k < 3; k++)
        s += fabs((double)p[k]) * fmax(fabs((double)lo[k]), fabs((double)hi[k]));
    return s;
}

static const double offsets[] = {0.0,   1e-9,  -1e-9, 1e-8,  -1e-8,  1e-7, -1e-7,
                                 3e-7,  -3e-7, 1e-6,  -1e-6, -2e-6,  -5e-6, -1e-5,
                                 -2e-5, -5e-5, -1e-4, -1e-3, -2e-3,  -1e-2, 1e-2};
#define N_OFFSETS (int)(sizeof offsets / sizeof offsets[0])

int main(void)
{
    uint32_t seed = 0x6c1b9e45u;
    int culled = 0, kept = 0, bad_sound = 0, bad_useful = 0;
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const double mm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int c = 0; c < 20000; c++) {
        float lo[3], hi[3];
        double centre_mag = rnd(&seed) % 2 ? 1.0 : 1000.0;
        for (int k = 0; k < 3; k++) {
            double m = uni(&seed, -centre_mag, centre_mag), h = uni(&seed, 0.001, 5.0);
            lo[k] = (float)(m - h);
            hi[k] = (float)(m + h);
        }
        /* the plane: a random normal, an axis now and then (a face parallel) */
        oit_clip clip = {.count = 1 + (int)(rnd(&seed) % OIT_CLIP_MAX)};
        int target = (int)(rnd(&seed) % (uint32_t)clip.count);
        for (int i = 0; i < clip.count; i++) {
            float *p = clip.plane[i];
            double n[3] = {0, 0, 0};
            if (rnd(&seed) % 3 == 0)
                n[rnd(&seed) % 3] = rnd(&seed) % 2 ? 1.0 : -1.0;
            else
                for (int k = 0; k < 3; k++)
                    n[k] = uni(&seed, -1, 1);
            if (n[0] == 0 && n[1] == 0 && n[2] == 0)
                n[2] = 1;
            for (int k = 0; k < 3; k++)
                p[k] = (float)n[k];
            /* the corner farthest on the kept side at d = 0 */
            long double best = 0;
            for (int k = 0; k < 3; k++)
                best += fmaxl((long double)p[k] * lo[k], (long double)p[k] * hi[k]);
            double off = i == target ? offsets[c % N_OFFSETS] : 1.0;
            /* d so that best + d = off * scale; scale depends on d: twice */
            p[3] = 0.0f;
            for (int it = 0; it < 3; it++)
                p[3] = (float)(off * scale_of(p, lo, hi) - best);
        }
        double planes[OIT_CLIP_MAX][4];
        float eye[OIT_CLIP_MAX][4];
        oit_clip_model(&clip, mm, planes);
        oit_clip_eye(&clip, identity, eye);
        int out = oit_clip_box_outside(clip.count, (const double(*)[4])planes, lo, hi);
        /* the oracle over the eight corners */
        int float_keeps = 0, near_kept = 0, far_out = 0;
        for (int i = 0; i < clip.count; i++) {
            double sc = scale_of(clip.plane[i], lo, hi);
            long double most = -INFINITY;
            for (int b = 0; b < 8; b++) {
                float corner[3] = {b & 1 ? hi[0] : lo[0], b & 2 ? hi[1] : lo[1],
                                   b & 4 ? hi[2] : lo[2]};
                long double s = dist(clip.plane[i], corner);
                most = s > most ? s : most;
            }
            if (most < -1e-3L * sc)
                far_out = 1;
        }
        for (int b = 0; b < 8; b++) {
            float corner[3] = {b & 1 ? hi[0] : lo[0], b & 2 ? hi[1] : lo[1],
                               b & 4 ? hi[2] : lo[2]};
            const float zero[3] = {0, 0, 0};
            float_keeps |= oit_clip_keeps(clip.count, (const float(*)[4])eye, corner, zero, 0.0f);
            int all_near = 1;
            for (int i = 0; i < clip.count; i++)
                all_near &= dist(clip.plane[i], corner) >=
                            -1e-6L * scale_of(clip.plane[i], lo, hi);
            near_kept |= all_near;
        }
        if (out)
            culled++;
        else
            kept++;
        if (out && (float_keeps || near_kept) && bad_sound++ < 5)
            CHECK(0, "case %d: box [%g %g %g]..[%g %g %g] culled, but plane %d at offset %g of "
                  "its scale keeps a corner (%s)", c, (double)lo[0], (double)lo[1],
                  (double)lo[2], (double)hi[0], (double)hi[1], (double)hi[2], target,
                  offsets[c % N_OFFSETS], float_keeps ? "the per-pixel test" : "within 1e-6");
        if (!out && far_out && bad_useful++ < 5)
            CHECK(0, "case %d: box [%g %g %g]..[%g %g %g] kept, but wholly beyond 1e-3 of the "
                  "scale on the removed side (offset %g)", c, (double)lo[0], (double)lo[1],
                  (double)lo[2], (double)hi[0], (double)hi[1], (double)hi[2],
                  offsets[c % N_OFFSETS]);
    }
    printf("boxes: %d culled, %d kept; %d culled with a kept corner, %d far out kept\n", culled,
           kept, bad_sound, bad_useful);
    CHECK(culled > 3000 && kept > 3000, "the cases do not reach both verdicts");
    CHECK(bad_sound == 0 && bad_useful == 0, "box culling against the per-pixel test");
    return test_verdict();
}
