/* The reference's pick (reference.h, oit_reference_pick): the pick's one
 * ray traced through an Embree scene of the mesh, as the frame traces each
 * pixel's, so that a pick of the reference lists the reference's hits. */
#include "view/render/reference/reference_job.h"

#include "view/render/pick/pick.h"

#include <stdlib.h>
#include <string.h>

/* The hits (sorted by prim) as the pick's: the triangle copied, its
 * position its source. */
static oit_status hand_over(const oit_mesh *mesh, const ray_ctx *rc, size_t n,
                            oit_pick_hits *hits, oit_error *err)
{
    oit_status s = OIT_OK;
    for (size_t i = 0; s == OIT_OK && i < n; i++) {
        oit_pick_hit h;
        memset(&h, 0, sizeof h);
        h.tri = mesh->tris[rc->hits[i].prim];
        h.source = rc->hits[i].prim;
        h.part = OIT_PICK_NO_PART;
        h.t = rc->hits[i].t;
        h.u = rc->hits[i].u;
        h.v = rc->hits[i].v;
        s = oit_pick_hits_add(hits, &h, err);
    }
    return s;
}

/* The pick's one ray on the scene (oit_reference_work). */
typedef struct pick_work {
    const oit_mesh *mesh;
    const oit_pick_ray *ray;
    oit_pick_hits *hits;
} pick_work;

static oit_status trace_pick(RTCScene scene, void *ctx, oit_error *err)
{
    pick_work *pw = ctx;
    ray_ctx rc;
    memset(&rc, 0, sizeof rc);
    rtcInitIntersectContext(&rc.rtc);
    size_t n = oit_reference_trace(scene, &rc, pw->ray->org, pw->ray->dir);
    oit_status s = rc.oom ? oit_error_set(err, OIT_ERR_NOMEM,
                                          "reference: cannot grow the pick's hit list")
                          : hand_over(pw->mesh, &rc, n, pw->hits, err);
    free(rc.hits);
    return s;
}

oit_status oit_reference_pick(const oit_mesh *mesh, const oit_pick_ray *ray, oit_pick_hits *hits,
                              oit_error *err)
{
    pick_work pw = {mesh, ray, hits};
    return oit_reference_with_scene(mesh, 1, trace_pick, &pw, err);
}
