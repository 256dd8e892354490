/* The Embree reference (reference.h): the frame. One ray per pixel centre
 * (reference_trace.c traces them); rows are shared among pthreads through
 * an atomic row counter. Embree's device and scene live for one frame. */
#include "view/render/reference/reference.h"
#include "base/clock.h"
#include "view/render/reference/reference_job.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Embree errors arrive through a callback on any thread; the first one is
 * kept for the caller. */
typedef struct embree_errors {
    pthread_mutex_t lock;
    int failed;
    char message[256];
} embree_errors;

static void on_embree_error(void *user, enum RTCError code, const char *str)
{
    embree_errors *e = user;
    pthread_mutex_lock(&e->lock);
    if (!e->failed) {
        e->failed = 1;
        snprintf(e->message, sizeof e->message, "Embree error %d: %s", (int)code,
                 str ? str : "(no message)");
    }
    pthread_mutex_unlock(&e->lock);
}

/* The mesh's own vertices are the vertex buffer (pos is the first 12 bytes
 * of each 16-byte oit_vertex), so only the trivial index buffer is built. */
static oit_status build_scene(RTCDevice dev, const oit_mesh *mesh, RTCScene *out,
                              oit_error *err)
{
    if (mesh->count > UINT32_MAX / 3)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "reference: %zu triangles exceed Embree's 32-bit indices", mesh->count);
    RTCScene scene = rtcNewScene(dev);
    if (!scene)
        return oit_error_set(err, OIT_ERR_NOMEM, "reference: cannot create an Embree scene");
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    if (mesh->count > 0) {
        RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   (void *)mesh->tris, 0, sizeof(oit_vertex), mesh->count * 3);
        uint32_t *idx = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                mesh->count);
        if (!idx) {
            rtcReleaseGeometry(geom);
            rtcReleaseScene(scene);
            return oit_error_set(err, OIT_ERR_NOMEM,
                                 "reference: cannot allocate indices for %zu triangles",
                                 mesh->count);
        }
        for (uint32_t i = 0; i < 3 * (uint32_t)mesh->count; i++)
            idx[i] = i;
        rtcSetGeometryIntersectFilterFunction(geom, oit_reference_record_hit);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene);
    *out = scene;
    return OIT_OK;
}

static int thread_count(const oit_reference_desc *desc, int rows)
{
    long n = desc && desc->threads > 0 ? desc->threads : sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1) n = 1;
    if (n > 256) n = 256;
    if (n > rows) n = rows;
    return (int)n;
}


/* Runs the row workers; returns 0 when a hit list could not grow. */
static int run_workers(ref_job *job, int nthreads, oit_frame_stats *stats)
{
    ref_worker *wk = calloc((size_t)nthreads, sizeof *wk);
    if (!wk)
        return 0;
    int started = 0;
    for (int i = 0; i < nthreads; i++) {
        wk[i].job = job;
        if (i > 0 && pthread_create(&wk[i].thread, NULL, oit_reference_render_rows, &wk[i]) != 0)
            break; /* fewer threads still finish the frame */
        started = i + 1;
    }
    oit_reference_render_rows(&wk[0]);
    for (int i = 1; i < started; i++)
        pthread_join(wk[i].thread, NULL);
    for (int i = 0; i < started; i++) {
        stats->fragments += wk[i].fragments;
        stats->fragments_saturated += wk[i].saturated;
        if (wk[i].max_layers > stats->max_layers)
            stats->max_layers = wk[i].max_layers;
    }
    for (int i = 0; i < nthreads; i++) {
        free(wk[i].ray.hits);
        free(wk[i].prims);
    }
    free(wk);
    return !atomic_load(&job->oom);
}

/* Creates the device and scene, traces the frame and releases both. Embree
 * reports errors through the device callback, so they are checked after
 * every step that can raise one. */
oit_status oit_reference_with_scene(const oit_mesh *mesh, int threads, oit_reference_work work,
                                    void *ctx, oit_error *err)
{
    embree_errors eerr;
    memset(&eerr, 0, sizeof eerr);
    pthread_mutex_init(&eerr.lock, NULL);
    char config[32];
    snprintf(config, sizeof config, "threads=%d", threads);
    oit_status s = OIT_OK;
    RTCDevice dev = rtcNewDevice(config);
    if (!dev) {
        s = oit_error_set(err, OIT_ERR_UNSUPPORTED, "reference: cannot create an Embree device (%s)",
                          config);
    } else {
        rtcSetDeviceErrorFunction(dev, on_embree_error, &eerr);
        RTCScene scene = NULL;
        s = build_scene(dev, mesh, &scene, err);
        if (s == OIT_OK && !eerr.failed)
            s = work(scene, ctx, err);
        if (scene)
            rtcReleaseScene(scene);
        if (s == OIT_OK && eerr.failed)
            s = oit_error_set(err, OIT_ERR_UNSUPPORTED, "reference: %s", eerr.message);
        rtcReleaseDevice(dev);
    }
    pthread_mutex_destroy(&eerr.lock);
    return s;
}

/* The frame's rows on the scene (oit_reference_work). */
typedef struct frame_work {
    ref_job *job;
    int threads;
    oit_frame_stats *stats;
} frame_work;

static oit_status trace_rows(RTCScene scene, void *ctx, oit_error *err)
{
    frame_work *fw = ctx;
    fw->job->scene = scene;
    if (!run_workers(fw->job, fw->threads, fw->stats))
        return oit_error_set(err, OIT_ERR_NOMEM, "reference: cannot grow a per-pixel hit list");
    return OIT_OK;
}

oit_status oit_reference_render(const oit_mesh *mesh, const oit_view *view,
                                const oit_reference_desc *desc, oit_image *out,
                                uint32_t *counts, oit_frame_stats *stats,
                                oit_error *err)
{
    double t0 = oit_time_ms();
    out->width = out->height = 0;
    out->rgba = NULL;
    ref_job job;
    memset(&job, 0, sizeof job);
    job.mesh = mesh;
    job.cam = &view->camera;
    job.shading = view->shading;
    job.counts = counts;
    job.ambiguous = desc ? desc->ambiguous : NULL;
    job.ties = desc ? desc->ties : NULL;
    job.saturation_epsilon = desc && desc->saturation_epsilon > 0.0f ? desc->saturation_epsilon : 0.0;
    oit_ray_keying_init(view, &job.keying);
    job.ambiguity_px = desc && desc->ambiguity_px > 0.0f ? desc->ambiguity_px : 1.0 / 64.0;
    atomic_init(&job.next_row, 0);
    atomic_init(&job.oom, 0);
    oit_shading_resolve_defaults(&job.shading);
    if (job.shading.mode == OIT_SHADING_TRANSLUCENT && !(job.shading.scene_scale > 0.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "reference: translucent shading needs scene_scale > 0");
    double model[16];
    if (oit_view_model(view, model))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "reference: a model matrix (pre-transform the mesh instead)");
    oit_status s = oit_ray_basis_make(view, "reference", &job.basis, err);
    if (s == OIT_OK)
        s = oit_image_alloc(out, view->width, view->height, err);
    if (s != OIT_OK)
        return s;
    job.out = out;
    oit_frame_stats fs;
    memset(&fs, 0, sizeof fs);
    frame_work fw = {&job, thread_count(desc, view->height), &fs};
    s = oit_reference_with_scene(mesh, fw.threads, trace_rows, &fw, err);
    if (s != OIT_OK) {
        oit_image_free(out);
        return s;
    }
    fs.ms = oit_time_ms() - t0;
    if (stats)
        *stats = fs;
    return OIT_OK;
}
