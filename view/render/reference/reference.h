/* The exact reference, independent of GL: an Embree ray through every pixel
 * centre collects every hit (filter callback, no early exit), hits are sorted
 * by the tie rule's (key, prim) (shade.h) and composited in double precision
 * with shade.h. */
#ifndef OIT_RENDER_REFERENCE_H
#define OIT_RENDER_REFERENCE_H

#include "view/render/method.h"
#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_reference_desc {
    int threads; /* 0: all cores */
    /* Optional, width*height bytes: set to 1 where the pixel is ambiguous
     * between rasterization and ray casting, i.e. the set of triangles hit
     * changes when the ray moves by ambiguity_px pixels in x or y (the
     * centre lies on a triangle edge or a silhouette). Hits that tie in
     * depth are not ambiguous: the tie rule (shade.h) orders them. Costs
     * four more rays per pixel. */
    uint8_t *ambiguous;
    float ambiguity_px; /* default 1/64 pixel */
    /* Optional, width*height counts: kept hits whose key is within 2^-18 of
     * their t (a few steps of the key's grid, shade.h) of the key of the
     * kept hit before them on the pixel's ray: ties, and near ties that a
     * GL method's rounding may turn into ties. A method unable to order
     * ties (dual depth peeling) loses at most these fragments. */
    uint32_t *ties;
    /* > 0: oit_frame_stats.fragments_saturated counts the kept hits that
     * reach their pixel once its transmittance is below this in every
     * channel: what a per-fragment early termination at that threshold
     * drops (the image is still the exact one). */
    float saturation_epsilon;
} oit_reference_desc;

/* out is allocated by the call. counts (optional) receives hits per pixel. */
oit_status oit_reference_render(const oit_mesh *mesh, const oit_view *view,
                                const oit_reference_desc *desc, oit_image *out,
                                uint32_t *counts, oit_frame_stats *stats,
                                oit_error *err);

/* The hits of a pick's ray (view/render/pick/pick.h) in mesh, by Embree as
 * the frame finds them (every hit, de-duplicated), each triangle's position
 * its source; the method's pick operation. */
struct oit_pick_ray;
struct oit_pick_hits;
oit_status oit_reference_pick(const oit_mesh *mesh, const struct oit_pick_ray *ray,
                              struct oit_pick_hits *hits, oit_error *err);

/* The reference as a method (view/render/method.h), named "reference". */
extern const oit_method oit_method_reference;

#ifdef __cplusplus
}
#endif
#endif
