/* oitstream --pick (pick_json.h). */
#include "tools/oitstream/pick_json.h"

#include <stdlib.h>

#include "base/json.h"
#include "tools/common/method_run.h"

static void floats(oit_json *w, const char *key, const float *v, int n)
{
    oit_json_begin_array(w, key, OIT_JSON_INLINE);
    for (int i = 0; i < n; i++)
        oit_json_general(w, NULL, v[i], 7);
    oit_json_end(w);
}

static void name_or_null(oit_json *w, const char *key, const char *s)
{
    if (s)
        oit_json_string(w, key, s);
    else
        oit_json_null(w, key);
}

static void write_layer(oit_json *w, const oit_pick_layer *l, const double *origin)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_general(w, "depth", l->depth, 9);
    oit_json_begin_array(w, "point", OIT_JSON_INLINE);
    for (int k = 0; k < 3; k++)
        oit_json_general(w, NULL, l->point[k] + (origin ? origin[k] : 0.0), 10);
    oit_json_end(w);
    oit_json_general(w, "alpha", l->alpha, 7);
    floats(w, "colour", l->colour, 3);
    floats(w, "transmittance", l->transmittance, 3);
    oit_json_bool(w, "front", l->front);
    if (l->part == OIT_PICK_NO_PART)
        oit_json_null(w, "part");
    else
        oit_json_uint(w, "part", l->part);
    oit_json_uint(w, "source_triangle", l->source_triangle);
    name_or_null(w, "group", l->group);
    name_or_null(w, "material", l->material);
    oit_json_end(w);
}

static oit_status write_json(const oit_pick_request *rq, const oit_pick_layer *layers, size_t n,
                             FILE *out, oit_error *err)
{
    oit_json w;
    oit_json_init(&w, out, "standard output");
    oit_json_begin_object(&w, NULL, OIT_JSON_BLOCK);
    oit_json_string(&w, "model", rq->model);
    oit_json_string(&w, "method", rq->method);
    oit_json_begin_array(&w, "pixel", OIT_JSON_INLINE);
    oit_json_int(&w, NULL, rq->x);
    oit_json_int(&w, NULL, rq->y);
    oit_json_end(&w);
    oit_json_begin_array(&w, "size", OIT_JSON_INLINE);
    oit_json_int(&w, NULL, rq->view->width);
    oit_json_int(&w, NULL, rq->view->height);
    oit_json_end(&w);
    oit_json_uint(&w, "count", n);
    oit_json_begin_array(&w, "layers", OIT_JSON_BLOCK);
    for (size_t i = 0; i < n; i++)
        write_layer(&w, &layers[i], rq->origin);
    oit_json_end(&w);
    oit_json_end(&w);
    return oit_json_close(&w, err);
}

static oit_status pick_all(const oit_pick_request *rq, oit_renderer *r, oit_scene *scene,
                           oit_pick_layer **layers, size_t *n, oit_error *err)
{
    oit_frame_camera cam;
    oit_frame fr;
    oit_run_frame(rq->view, &cam, &fr);
    oit_status s = oit_renderer_pick(r, scene, &fr, rq->x, rq->y, NULL, 0, n, err);
    if (s != OIT_OK || *n == 0)
        return s;
    *layers = calloc(*n, sizeof **layers);
    if (!*layers)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold %zu layers", rq->model, *n);
    size_t again;
    return oit_renderer_pick(r, scene, &fr, rq->x, rq->y, *layers, *n, &again, err);
}

oit_status oit_pick_get(const oit_pick_request *rq, oit_pick_layer **layers, size_t *n,
                        oit_error *err)
{
    oit_renderer_desc d = {.method = rq->part_file ? NULL : rq->method};
    oit_run_shading(&rq->view->shading, &d);
    oit_scene *scene = NULL;
    oit_renderer *r = NULL;
    *layers = NULL;
    *n = 0;
    oit_status s = rq->part_file
                       ? oit_scene_open(rq->model, &(oit_scene_desc){.defer_validation = 1},
                                        &scene, err)
                       : oit_scene_borrow_mesh(rq->mesh, rq->model, &scene, err);
    if (s == OIT_OK)
        s = oit_renderer_create(&d, &r, err);
    if (s == OIT_OK)
        s = pick_all(rq, r, scene, layers, n, err);
    oit_renderer_destroy(r);
    oit_scene_close(scene);
    if (s != OIT_OK) {
        free(*layers);
        *layers = NULL;
        *n = 0;
    }
    return s;
}

oit_status oit_pick_print(const oit_pick_request *rq, FILE *out, oit_error *err)
{
    oit_pick_layer *layers = NULL;
    size_t n = 0;
    oit_status s = oit_pick_get(rq, &layers, &n, err);
    if (s == OIT_OK)
        s = write_json(rq, layers, n, out, err);
    free(layers);
    return s;
}
