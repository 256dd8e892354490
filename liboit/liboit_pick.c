/* oit_renderer_pick (liboit.h): the layers at one pixel of a frame, found
 * by the pick's walk (view/render/pick/pick.h) or by the method's own
 * (the Embree reference's), ordered and shaded as the exact image. */
#include "liboit/liboit_internal.h"

#include "view/render/pick/pick.h"

/* The hits of the ray: a part file's parts walked one at a time; in core,
 * the method's own finder (the reference's) or the walk over the mesh. */
static oit_status find_hits(oit_renderer *r, oit_scene *scene, const oit_pick_ray *ray,
                            oit_pick_hits *hits, oit_error *err)
{
    if (scene->pf)
        return oit_pick_partfile(ray, scene->pf, hits, err);
    const oit_lib_method *m;
    const oit_method *table;
    oit_status s = oit_lib_method_for(r, scene, &m, err);
    if (s == OIT_OK)
        s = oit_lib_method_table(r, m, &table, err);
    if (s != OIT_OK)
        return s;
    /* the reference takes no model matrix (its frames refuse one) */
    if (table->pick && !ray->has_model)
        return table->pick(&scene->mesh, ray, hits, err);
    return oit_pick_mesh(ray, &scene->mesh, NULL, hits, err);
}

static oit_status pick_check(const oit_renderer *r, const oit_scene *scene, const oit_frame *frame,
                             const size_t *count, const oit_pick_layer *layers, size_t capacity,
                             oit_error *err)
{
    if (!r || !scene || !frame || !count)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_pick: %s is NULL",
                             !r ? "the renderer" : !scene ? "the scene" : !frame ? "the frame"
                                                                                 : "count");
    if (!layers && capacity)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_renderer_pick: layers is NULL with a capacity of %zu", capacity);
    if (frame->depth_texture)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "oit_renderer_pick: oit_frame.depth_texture (the pick lists the "
                             "transparent scene alone)");
    return OIT_OK;
}

oit_status oit_renderer_pick(oit_renderer *r, oit_scene *scene, const oit_frame *frame, int x,
                             int y, oit_pick_layer *layers, size_t capacity, size_t *count,
                             oit_error *err)
{
    oit_status s = pick_check(r, scene, frame, count, layers, capacity, err);
    if (s != OIT_OK)
        return s;
    *count = 0;
    oit_view v;
    memset(&v, 0, sizeof v);
    oit_pick_ray ray;
    oit_pick_hits hits = {0};
    s = oit_lib_frame_view(r, scene, frame, NULL, &v, err);
    if (s == OIT_OK)
        s = oit_pick_ray_make(&v, x, y, &ray, err);
    if (s == OIT_OK)
        s = find_hits(r, scene, &ray, &hits, err);
    if (s == OIT_OK)
        *count = oit_pick_compose(&ray, &hits, layers, capacity);
    oit_pick_hits_free(&hits);
    return s;
}
