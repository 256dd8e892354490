/* Rays cast through the parts (verify_internal.h): one Embree scene per
 * chunk of parts, every hit recorded by an intersect filter that lets the
 * traversal go on. Apart as the one file that builds and casts Embree
 * scenes; what the hits mean is verify_hits.c's. */
#include "prepare/convert/verify_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void record_hit(const struct RTCFilterFunctionNArguments *args)
{
    vray_ctx *rc = (vray_ctx *)args->context;
    for (unsigned i = 0; i < args->N; i++) {
        if (args->valid[i] != -1)
            continue;
        args->valid[i] = 0; /* reject: traversal continues to every hit */
        if (rc->n == rc->cap) {
            size_t cap = rc->cap ? 2 * rc->cap : 1024;
            rhit *p = realloc(rc->hits, cap * sizeof *p);
            if (!p) {
                rc->oom = 1;
                continue;
            }
            rc->hits = p;
            rc->cap = cap;
        }
        /* SOA layout of RTCRayN / RTCHitN: tfar is float array 8, primID uint array 5. */
        float t = ((const float *)args->ray)[8 * args->N + i];
        uint32_t prim = ((const uint32_t *)args->hit)[5 * args->N + i];
        rc->hits[rc->n++] = (rhit){rc->ray, {t, rc->part_of_prim[prim]}};
    }
}

/* One Embree scene of parts [p0, p1). Chunks are built, cast and released
 * one at a time, so the BVH and buffers held at once are one chunk's, not
 * the file's (a 40M-triangle file held 4.1 GB in one scene). */
static oit_status build_chunk(verifier *v, uint32_t p0, uint32_t p1, RTCScene *scene,
                              oit_error *err)
{
    uint64_t tris = 0, verts = 0;
    for (uint32_t p = p0; p < p1; p++) {
        tris += oit_partfile_parts(v->pf)[p].index_count / 3;
        verts += oit_partfile_parts(v->pf)[p].vertex_count;
    }
    free(v->part_of_prim);
    v->part_of_prim = malloc((tris ? tris : 1) * sizeof *v->part_of_prim);
    RTCGeometry geom = rtcNewGeometry(v->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        12, verts ? verts : 1);
    uint32_t *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12,
                                           tris ? tris : 1);
    if (!v->part_of_prim || !vb || !ib) {
        rtcReleaseGeometry(geom);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: Embree scene of %llu triangles: out of "
                             "memory", oit_partfile_name(v->pf), (unsigned long long)tris);
    }
    uint64_t vo = 0, to = 0, copied = 0;
    uint32_t drop_from = p0;
    for (uint32_t p = p0; p < p1; p++) {
        oit_partfile_part_view pv;
        oit_status s = oit_partfile_part_data(v->pf, p, &v->decoded, &pv, err);
        if (s) {
            rtcReleaseGeometry(geom);
            return s;
        }
        uint32_t nv = oit_partfile_parts(v->pf)[p].vertex_count;
        for (uint32_t i = 0; i < nv; i++)
            memcpy(vb + 3 * (vo + i), (const char *)pv.positions + (size_t)i * pv.stride, 12);
        for (uint64_t i = 0; i < pv.index_count; i++)
            ib[3 * to + i] = (uint32_t)vo + oit_partfile_index(&pv, i);
        for (uint64_t i = 0; i < pv.index_count / 3; i++)
            v->part_of_prim[to + i] = p;
        vo += nv;
        to += pv.index_count / 3;
        /* Copied: a large file's mapped pages need not stay resident too
         * (dropped 64 MiB at a time: a page two parts share is read once). */
        copied += oit_partfile_parts(v->pf)[p].data_bytes;
        if (copied >= ((uint64_t)64 << 20) || p + 1 == p1) {
            oit_partfile_drop_part_data(v->pf, drop_from, p + 1 - drop_from);
            drop_from = p + 1;
            copied = 0;
        }
    }
    rtcSetGeometryIntersectFilterFunction(geom, record_hit);
    rtcCommitGeometry(geom);
    *scene = rtcNewScene(v->dev);
    /* Compact: the BVH refers to our index buffer instead of copying every
     * triangle into its leaves (6.9 GB against 4.3 GB of peak RSS on a
     * 40M-triangle file in one scene). */
    rtcSetSceneFlags(*scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT);
    rtcAttachGeometry(*scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(*scene);
    v->ray.part_of_prim = v->part_of_prim;
    return OIT_OK;
}

/* Casts every ray through one chunk's scene, adding its hits to the list. */
static oit_status cast_chunk(verifier *v, RTCScene scene, oit_error *err)
{
    for (uint32_t r = 0; r < v->nrays; r++) {
        const vray *ry = &v->rays[r];
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        rh.ray.org_x = ry->org[0];
        rh.ray.org_y = ry->org[1];
        rh.ray.org_z = ry->org[2];
        rh.ray.dir_x = ry->dir[0];
        rh.ray.dir_y = ry->dir[1];
        rh.ray.dir_z = ry->dir[2];
        rh.ray.tnear = 0;
        rh.ray.tfar = INFINITY;
        rh.ray.mask = UINT32_MAX;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        v->ray.ray = r;
        rtcIntersect1(scene, &v->ray.rtc, &rh);
        if (v->ray.oom)
            return oit_error_set(err, OIT_ERR_NOMEM, "%s: ray hits: out of memory",
                                 oit_partfile_name(v->pf));
    }
    return OIT_OK;
}

/* Every ray through every chunk of at most chunk_triangles triangles (a
 * part is never divided). */
oit_status oit_verify_cast_all(verifier *v, uint64_t chunk_triangles, oit_error *err)
{
    oit_status s = OIT_OK;
    for (uint32_t p0 = 0; p0 < v->nparts && !s;) {
        uint64_t tris = oit_partfile_parts(v->pf)[p0].index_count / 3;
        uint32_t p1 = p0 + 1;
        while (p1 < v->nparts &&
               tris + oit_partfile_parts(v->pf)[p1].index_count / 3 <= chunk_triangles)
            tris += oit_partfile_parts(v->pf)[p1++].index_count / 3;
        RTCScene scene = NULL;
        s = build_chunk(v, p0, p1, &scene, err);
        if (!s)
            s = cast_chunk(v, scene, err);
        if (scene)
            rtcReleaseScene(scene);
        v->rep->chunks++;
        p0 = p1;
    }
    return s;
}

