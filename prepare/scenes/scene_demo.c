/* demo: the built-in scene (about 100K triangles). A chain of three linked
 * rings, three nested spheres beside it and a twisted band around both, in
 * distinct colours, so that from the default camera (azimuth 30, elevation
 * 20, looking at the bounding box centre) every kind of overlap shows:
 * interlocking, nesting and a surface seen from both sides. Fixed geometry:
 * the seed does not change it. */
#include "prepare/scenes/scene.h"

#include "prepare/scenes/shapes.h"

oit_status oit_scene_demo(oit_emit *e, const oit_scene_args *a, oit_error *err)
{
    const oit_v3 z = {0, 0, 1}, y = {0, 1, 0};
    /* Ring i's circle passes through the hole of ring i+1: centres 1.8
     * apart, major radius 1.2, alternate planes. */
    static const uint8_t rings[3][4] = {{220, 50, 40, 140}, {240, 190, 40, 140}, {40, 90, 220, 140}};
    for (int i = 0; i < 3; i++) {
        oit_emit_color(e, rings[i][0], rings[i][1], rings[i][2], rings[i][3]);
        oit_shape_torus(e, oit_v3_make(-1.8f + 1.8f * i, 0, 0), i == 1 ? y : z, 1.2f, 0.25f, 1.0f,
                        0, 128, 40);
    }
    static const uint8_t shells[3][4] = {{60, 200, 120, 90}, {200, 80, 200, 120}, {250, 250, 250, 200}};
    static const float radii[3] = {1.0f, 0.65f, 0.3f};
    for (int i = 0; i < 3; i++) {
        oit_emit_color(e, shells[i][0], shells[i][1], shells[i][2], shells[i][3]);
        oit_shape_sphere(e, oit_v3_make(0, 0, -2.6f), radii[i], 112);
    }
    oit_emit_color(e, 250, 140, 30, 110);
    oit_shape_torus(e, oit_v3_make(0, 0, -0.9f), y, 3.4f, 0.5f, 0.1f, 2, 512, 32);
    return oit_emit_flush(e);
}
