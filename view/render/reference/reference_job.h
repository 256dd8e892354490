/* What the reference's frame (reference.c) hands its row workers
 * (reference_trace.c): the job, one worker's scratch, and the two entry
 * points Embree and pthreads call. Internal to view/render/reference/. */
#ifndef OIT_RENDER_REFERENCE_JOB_H
#define OIT_RENDER_REFERENCE_JOB_H

#include "view/render/image/image.h"
#include "view/render/image/ray.h"
#include "view/render/image/shade.h"
#include "view/render/reference/reference.h"

#include <embree3/rtcore.h>
#include <pthread.h>
#include <stdatomic.h>

typedef struct hit_rec {
    float t, u, v; /* Embree's hit; t decides the view-depth clip, as in GL */
    uint32_t prim;
    float key;     /* the tie rule's sort key (shade.h) */
    int clipped;   /* removed by a section plane (clip.h) */
} hit_rec;

/* Embree hands the filter the context pointer we pass to rtcIntersect1, so
 * the per-ray hit list rides behind the RTCIntersectContext it starts with. */
typedef struct ray_ctx {
    struct RTCIntersectContext rtc;
    hit_rec *hits;
    size_t n, cap;
    int oom;
} ray_ctx;


typedef struct ref_job {
    const oit_mesh *mesh;
    const oit_camera *cam;
    oit_shading shading;
    oit_ray_basis basis;
    RTCScene scene;
    oit_image *out;
    uint32_t *counts;
    uint8_t *ambiguous;
    double ambiguity_px;
    uint32_t *ties;
    double saturation_epsilon;
    oit_ray_keying keying; /* the hits' keys and section planes (ray.h) */
    atomic_int next_row;
    atomic_int oom;
} ref_job;

typedef struct ref_worker {
    ref_job *job;
    ray_ctx ray;
    uint32_t *prims; /* the centre ray's kept prims, for the ambiguity test */
    size_t prims_cap;
    uint64_t fragments, saturated;
    uint32_t max_layers;
    pthread_t thread;
} ref_worker;

/* Builds an Embree scene of mesh's triangles (each hit recorded by
 * oit_reference_record_hit) on a device of `threads` threads, runs
 * work(scene, ctx) on it and releases both; an Embree error on the way is
 * the call's, the message opening "reference:". The frame's rows and the
 * pick's one ray both run here. */
typedef oit_status (*oit_reference_work)(RTCScene scene, void *ctx, oit_error *err);
oit_status oit_reference_with_scene(const oit_mesh *mesh, int threads, oit_reference_work work,
                                    void *ctx, oit_error *err);
/* Traces one ray from org along the unit dir through scene; leaves its
 * hits in rc, de-duplicated and sorted by prim, and returns their count. */
size_t oit_reference_trace(RTCScene scene, ray_ctx *rc, const double org[3], const double dir[3]);

/* Embree's intersect filter: records every hit of the ray and rejects it,
 * so that traversal visits the whole ray. */
void oit_reference_record_hit(const struct RTCFilterFunctionNArguments *args);
/* A worker (a ref_worker *): takes rows from the job's counter and traces
 * each pixel until none is left or a hit list could not grow. */
void *oit_reference_render_rows(void *arg);

#endif
