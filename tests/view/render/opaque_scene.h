/* test_opaque's scene, which test_opaque_sizes draws again at other frame
 * sizes: screen-aligned quads (gl_test_scene.h), two of them opaque, and
 * the exact number of fragments the GL methods store for them. */
#ifndef OIT_TESTS_RENDER_OPAQUE_SCENE_H
#define OIT_TESTS_RENDER_OPAQUE_SCENE_H

#include <math.h>
#include <stdint.h>

#include "tests/lib/gl_test_scene.h"

/* Front to back: transparent, opaque (smaller), transparent behind it
 * (same batch), two more behind (a later batch), one in front beside. */
static const quad_spec QUADS[] = {
    {-2.0f, 1.6f, {200, 40, 40, 120}, 1},  {-3.0f, 1.2f, {40, 200, 40, 255}, 1},
    {-3.5f, 3.0f, {40, 40, 200, 100}, 0},  {-4.0f, 3.5f, {200, 200, 40, 90}, 1},
    {-5.0f, 4.5f, {40, 200, 200, 255}, 1}, {-2.5f, 0.5f, {90, 90, 90, 140}, 1},
};
#define NQ (int)(sizeof QUADS / sizeof QUADS[0])

/* Fragments the pixels of v store: per pixel the quads covering it up to
 * and including the nearest opaque one (see_through: all). */
static inline uint64_t expect_stored(const oit_view *v, int see_through)
{
    uint64_t total = 0;
    double tanh = tan(0.5 * v->camera.fovy_deg * 3.14159265358979323846 / 180.0);
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * tanh * v->width / v->height;
            double dy = (1 - (y + 0.5) / v->height * 2) * tanh;
            double nearest = 1e30;
            for (int i = 0; i < NQ; i++)
                if (!see_through && QUADS[i].rgba[3] == 255 && fabs(dx * QUADS[i].z) < QUADS[i].half &&
                    fabs(dy * QUADS[i].z) < QUADS[i].half && -QUADS[i].z < nearest)
                    nearest = -QUADS[i].z;
            for (int i = 0; i < NQ; i++)
                total += fabs(dx * QUADS[i].z) < QUADS[i].half &&
                         fabs(dy * QUADS[i].z) < QUADS[i].half && -QUADS[i].z <= nearest;
        }
    return total;
}

#endif
