/* One layer of a pixel as oit_renderer_pick returns it: a plain struct,
 * included by oit/liboit.h, which documents the call. */
#ifndef OIT_PICK_H
#define OIT_PICK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* oit_pick_layer.part of an in-core scene, which has no parts. */
#define OIT_PICK_NO_PART UINT32_MAX

/* One fragment of the pixel, as the exact image composites it:
 *     C += transmittance * alpha * colour;  T = transmittance * (1 - alpha)
 * (translucent shading: transmittance already carries the absorption of
 * the medium on the way to it). Colours are in the compositing space
 * (oit_render_shading.colour_space: sRGB-encoded values, or linear light). */
typedef struct oit_pick_layer {
    /* The tie rule's key: distance along the pixel centre's ray from its
     * origin (the eye; orthographic: the near plane) to the triangle's
     * plane, its lowest mantissa bits cleared; scene units. */
    double depth;
    /* Where the pixel centre's ray meets the triangle, in the scene's
     * coordinates (relative to oit_scene_info.origin, as its positions). */
    double point[3];
    float colour[3];        /* shaded, as composited */
    float alpha;            /* coverage (translucent: Fresnel's)  */
    float transmittance[3]; /* of the light before this layer: 1 for the front one */
    int front;              /* 1: the face turns towards the viewer */
    uint32_t part;          /* the part file's part, or OIT_PICK_NO_PART */
    /* The triangle's index among those the mesh reader delivered for the
     * source file (a clipped piece: the triangle it was cut from), the
     * tie rule's second key. */
    uint64_t source_triangle;
    /* The group (object, node, shape) and material the triangle came from;
     * NULL: the scene keeps no names (no reader carries them yet). */
    const char *group;
    const char *material;
} oit_pick_layer;

#ifdef __cplusplus
}
#endif
#endif
