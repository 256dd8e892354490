/* The layers at one pixel (oit_renderer_pick, include/oit/pick.h): every
 * triangle the ray through the pixel's centre meets, keyed, clipped,
 * ordered and shaded by the same rules as the exact image (shade.h, the
 * tie rule), each with the transmittance in front of it.
 *
 * The ray is the reference's (view/render/image/ray.h), so the layers are
 * the reference's hits; a rasterizing method composites the same ones
 * except on the reference's ambiguity mask, where the pixel's centre lies
 * on an edge and coverage and rays may differ by a triangle.
 *
 * Finding the hits is a walk: over an in-core mesh, or over a part file's
 * parts whose bounds the ray crosses, one part decoded at a time (memory:
 * the largest part and the hits, never the model). The Embree reference
 * finds them its own way (reference.h, oit_reference_pick) and hands them
 * to the same ordering. */
#ifndef OIT_RENDER_PICK_H
#define OIT_RENDER_PICK_H

#include <stdlib.h>

#include "oit/partfile.h"
#include "oit/pick.h"
#include "view/render/image/ray.h"

/* One hit of the ray, before keying. The triangle is copied: a part file's
 * parts are decoded into a buffer the walk reuses. */
typedef struct oit_pick_hit {
    oit_triangle tri;
    uint64_t source;
    uint32_t part;
    float t;    /* along the unit ray from its origin */
    float u, v; /* barycentric weights of vertices 1 and 2 */
    float key;  /* the tie rule's (oit_pick_compose sets it) */
} oit_pick_hit;

typedef struct oit_pick_hits {
    oit_pick_hit *h;
    size_t n, cap;
} oit_pick_hits;

/* The ray of pixel (x, y) (y = 0 the top row) of a view. */
typedef struct oit_pick_ray {
    const oit_view *view;
    int x, y;
    oit_ray_basis basis;
    double org[3], dir[3];
    /* The view's model matrix (view.h): the walk meets each triangle as
     * the GL methods draw it, its vertices transformed and rounded to
     * float; has_model 0: the identity. */
    int has_model;
    double model[16];
} oit_pick_ray;

/* A pixel outside the view or a camera no ray can be cast from is
 * refused, naming what is wrong. */
oit_status oit_pick_ray_make(const oit_view *view, int x, int y, oit_pick_ray *out,
                             oit_error *err);

/* Appends to hits every triangle of mesh the ray meets at t > 0 (through
 * the model matrix: the hit's triangle is the transformed one); source:
 * the triangles' source indices, NULL for their positions. */
oit_status oit_pick_mesh(const oit_pick_ray *ray, const oit_mesh *mesh, const uint32_t *source,
                         oit_pick_hits *hits, oit_error *err);
/* The same over a part file's parts, each part whose bounds the ray
 * crosses decoded in turn (validated on its first use). */
oit_status oit_pick_partfile(const oit_pick_ray *ray, oit_partfile *pf, oit_pick_hits *hits,
                             oit_error *err);
/* Appends one hit (growing the array); OIT_ERR_NOMEM when it cannot.
 * Inline, so that the reference's plugin adds its hits without linking
 * the walk (and the part file reader under it). */
static inline oit_status oit_pick_hits_add(oit_pick_hits *hits, const oit_pick_hit *hit,
                                           oit_error *err)
{
    if (hits->n == hits->cap) {
        size_t cap = hits->cap ? hits->cap * 2 : 64;
        oit_pick_hit *p = (oit_pick_hit *)realloc(hits->h, cap * sizeof *p);
        if (!p)
            return oit_error_set(err, OIT_ERR_NOMEM, "pick: cannot hold %zu hits", cap);
        hits->h = p;
        hits->cap = cap;
    }
    hits->h[hits->n++] = *hit;
    return OIT_OK;
}

static inline void oit_pick_hits_free(oit_pick_hits *hits)
{
    free(hits->h);
    hits->h = NULL;
    hits->n = hits->cap = 0;
}

/* The hits as the exact image composites them: keyed, clipped to the
 * view's depth range and section planes, one a source triangle (the
 * nearest: a triangle cut into pieces lies in one plane), sorted by (key,
 * source) and shaded (shade.h). The first `capacity` layers go to layers
 * (NULL with 0: none); returns how many there are in all. hits is
 * reordered. */
size_t oit_pick_compose(const oit_pick_ray *ray, oit_pick_hits *hits, oit_pick_layer *layers,
                        size_t capacity);

#endif
