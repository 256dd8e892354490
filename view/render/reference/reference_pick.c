/* The reference's pick (reference.h, oit_reference_pick): the pick's one
 * ray traced through an Embree scene of the mesh, as the frame traces each
 * pixel's, so that a pick of the reference lists the reference's hits. */
#include "view/render/reference/reference_job.h"

#include "view/render/pick/pick.h"

#include <stdio.h>
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

oit_status oit_reference_pick(const oit_mesh *mesh, const oit_pick_ray *ray, oit_pick_hits *hits,
                              oit_error *err)
{
    embree_errors eerr;
    memset(&eerr, 0, sizeof eerr);
    pthread_mutex_init(&eerr.lock, NULL);
    RTCDevice dev = rtcNewDevice("threads=1");
    oit_status s = OIT_OK;
    if (!dev) {
        s = oit_error_set(err, OIT_ERR_UNSUPPORTED, "reference: cannot create an Embree device");
    } else {
        rtcSetDeviceErrorFunction(dev, oit_reference_on_error, &eerr);
        RTCScene scene = NULL;
        s = oit_reference_build_scene(dev, mesh, &scene, err);
        ray_ctx rc;
        memset(&rc, 0, sizeof rc);
        rtcInitIntersectContext(&rc.rtc);
        size_t n = s == OIT_OK && !eerr.failed ? oit_reference_trace(scene, &rc, ray->org, ray->dir)
                                              : 0;
        if (s == OIT_OK && rc.oom)
            s = oit_error_set(err, OIT_ERR_NOMEM, "reference: cannot grow the pick's hit list");
        if (s == OIT_OK && eerr.failed)
            s = oit_error_set(err, OIT_ERR_UNSUPPORTED, "reference: %s", eerr.message);
        if (s == OIT_OK)
            s = hand_over(mesh, &rc, n, hits, err);
        free(rc.hits);
        if (scene)
            rtcReleaseScene(scene);
        rtcReleaseDevice(dev);
    }
    pthread_mutex_destroy(&eerr.lock);
    return s;
}
