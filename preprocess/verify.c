/* Ray-cast verification of a part file (verify.h). */
#include "preprocess/verify.h"
#include "base/vec.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/partfile.h"
#include "partition/plane_exact.h"
#include "partfile/order.h"

typedef struct vhit {
    float t;
    uint32_t part;
} vhit;

/* A hit of ray `ray`, recorded while the chunk holding its part is built. */
typedef struct rhit {
    uint32_t ray;
    vhit h;
} rhit;

/* The filter gets the context pointer we pass to rtcIntersect1; the hit list
 * rides behind the RTCIntersectContext it starts with. */
typedef struct vray_ctx {
    struct RTCIntersectContext rtc;
    const uint32_t *part_of_prim; /* of the chunk's primitives */
    uint32_t ray;                 /* the ray being cast */
    rhit *hits;
    size_t n, cap;
    int oom;
} vray_ctx;

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

/* A ray to cast, and the viewpoint whose order it checks. */
typedef struct vray {
    float org[3], dir[3];
    uint32_t view;
} vray;

typedef struct verifier {
    oit_partfile *pf;
    oit_order *order;
    RTCDevice dev;
    uint32_t *part_of_prim;
    uint32_t *rank, *ordered, *count, *touched, *bound;
    uint8_t *reached;
    uint32_t nparts;
    float lo[3], hi[3], centre[3], radius, tie;
    vray *rays;
    float (*eyes)[3]; /* per view */
    uint32_t nrays, nviews;
    vhit *line; /* one ray's hits, sorted by t */
    size_t line_n;
    vray_ctx ray;
    oit_verify_report *rep;
    oit_partfile_buffer decoded; /* one part at a time, reused */
} verifier;

static uint64_t rng_next(uint64_t *s)
{
    /* splitmix64: fixed seed, so a run is reproducible. */
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double rng_unit(uint64_t *s)
{
    return (rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

static void random_direction(uint64_t *s, float d[3])
{
    double z = 2 * rng_unit(s) - 1, a = 6.283185307179586 * rng_unit(s), r = sqrt(fmax(0, 1 - z * z));
    d[0] = (float)(r * cos(a));
    d[1] = (float)(r * sin(a));
    d[2] = (float)z;
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
static oit_status cast_all(verifier *v, uint64_t chunk_triangles, oit_error *err)
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

static int cmp_hit_t(const void *a, const void *b)
{
    const vhit *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return (x->part > y->part) - (x->part < y->part);
}

static void note(verifier *v, const char *fmt, double a, double b, double c, unsigned p,
                 unsigned q)
{
    if (v->rep->first_violation[0])
        return;
    snprintf(v->rep->first_violation, sizeof v->rep->first_violation, fmt, a, b, c, p, q);
}

/* Checks (1) hits per part against the layer bound, on hits sorted by t. A
 * ray through an edge or vertex hits every triangle there at one depth, where
 * a rasterizer's fill rule makes one fragment: hits of one part within `tie`
 * of each other count as one layer. */
static int same_layer(const verifier *v, size_t i)
{
    const vhit *h = v->line;
    for (size_t j = i; j-- > 0 && h[j].t >= h[i].t - v->tie;)
        if (h[j].part == h[i].part)
            return 1;
    return 0;
}

static void check_layers(verifier *v, const float org[3])
{
    uint32_t nt = 0;
    for (size_t i = 0; i < v->line_n; i++) {
        uint32_t p = v->line[i].part;
        if (same_layer(v, i))
            continue;
        if (v->count[p]++ == 0)
            v->touched[nt++] = p;
    }
    for (uint32_t i = 0; i < nt; i++) {
        uint32_t p = v->touched[i], c = v->count[p];
        if (c > v->rep->max_hits_per_part) {
            v->rep->max_hits_per_part = c;
            v->rep->worst_part_bound = v->bound[p];
        }
        if (c >= v->bound[p] && !v->reached[p]) {
            v->reached[p] = 1;
            v->rep->parts_at_bound++;
        }
        if (c > v->bound[p] && v->rep->measured_bounds) {
            /* A measured count is an estimate: exceeding it is a figure. */
            v->rep->bound_exceeded++;
            if (c - v->bound[p] > v->rep->most_over_bound)
                v->rep->most_over_bound = c - v->bound[p];
        } else if (c > v->bound[p]) {
            v->rep->layer_violations++;
            note(v, "ray from (%g %g %g): part %u gives %u hits, more than its bound", org[0],
                 org[1], org[2], p, c);
        }
        v->count[p] = 0;
    }
}

/* Checks (2): along the ray (hits sorted by t) no part comes later whose rank
 * is below that of a part met more than `tie` earlier. Hits within `tie` of
 * the eye are skipped: an eye lying on a surface sees it edge-on (no
 * fragment, and the near plane clips it), so its part has no place in the
 * order from there. */
static void check_order(verifier *v, const float org[3])
{
    const vhit *h = v->line;
    size_t n = v->line_n, j = 0;
    if (n < 2)
        return;
    while (n > 0 && h[0].t <= v->tie)
        h++, n--;
    uint32_t max_rank = 0, max_part = 0;
    int have = 0;
    for (size_t i = 0; i < n; i++) {
        for (; j < i && h[j].t < h[i].t - v->tie; j++)
            if (!have || v->rank[h[j].part] > max_rank) {
                max_rank = v->rank[h[j].part];
                max_part = h[j].part;
                have = 1;
            }
        uint32_t r = v->rank[h[i].part];
        if (r == UINT32_MAX || (have && r < max_rank)) {
            v->rep->order_violations++;
            note(v, "ray from (%g %g %g): part %u is met after part %u but ordered before it",
                 org[0], org[1], org[2], h[i].part, max_part);
            return;
        }
    }
}

static oit_status order_from(verifier *v, const float eye[3], oit_error *err)
{
    uint32_t n = 0;
    oit_status s = oit_order_compute(v->order, eye, v->ordered, &n, err);
    if (s)
        return s;
    for (uint32_t p = 0; p < v->nparts; p++)
        v->rank[p] = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++)
        v->rank[v->ordered[i]] = i;
    return OIT_OK;
}

/* Sorts the hits into one list per ray, by t, and checks each ray against
 * the order of its viewpoint. */
static oit_status check_all(verifier *v, oit_error *err)
{
    size_t n = v->ray.n;
    size_t *first = calloc((size_t)v->nrays + 1, sizeof *first);
    vhit *sorted = malloc((n ? n : 1) * sizeof *sorted);
    if (!first || !sorted) {
        free(first);
        free(sorted);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %zu ray hits: out of memory",
                             oit_partfile_name(v->pf), n);
    }
    for (size_t i = 0; i < n; i++)
        first[v->ray.hits[i].ray + 1]++;
    for (uint32_t r = 0; r < v->nrays; r++)
        first[r + 1] += first[r];
    for (size_t i = 0; i < n; i++)
        sorted[first[v->ray.hits[i].ray]++] = v->ray.hits[i].h;
    for (uint32_t r = v->nrays; r > 0; r--)
        first[r] = first[r - 1];
    first[0] = 0;
    free(v->ray.hits);
    v->ray.hits = NULL;
    oit_status s = OIT_OK;
    uint32_t view = UINT32_MAX;
    for (uint32_t r = 0; r < v->nrays && !s; r++) {
        if (v->rays[r].view != view) {
            view = v->rays[r].view;
            s = order_from(v, v->eyes[view], err);
            if (s)
                break;
        }
        v->line = sorted + first[r];
        v->line_n = first[r + 1] - first[r];
        if (v->line_n > 1)
            qsort(v->line, v->line_n, sizeof *v->line, cmp_hit_t);
        v->rep->rays++;
        v->rep->hits += v->line_n;
        v->rep->rays_hitting += v->line_n > 0;
        check_layers(v, v->rays[r].org);
        check_order(v, v->rays[r].org);
    }
    v->line = NULL;
    free(first);
    free(sorted);
    return s;
}

/* The rays are drawn up front, in the order and with the random draws the
 * checks use, so a run is reproducible whatever the chunking. */
static int add_view(verifier *v, const float eye[3])
{
    float(*e)[3] = realloc(v->eyes, ((size_t)v->nviews + 1) * sizeof *e);
    if (!e)
        return 0;
    v->eyes = e;
    memcpy(e[v->nviews++], eye, sizeof e[0]);
    return 1;
}

static int add_ray(verifier *v, const float org[3], const float dir[3], uint32_t *cap)
{
    if (v->nrays == *cap) {
        uint32_t c = *cap ? 2 * *cap : 4096;
        vray *r = realloc(v->rays, (size_t)c * sizeof *r);
        if (!r)
            return 0;
        v->rays = r;
        *cap = c;
    }
    vray *r = &v->rays[v->nrays++];
    memcpy(r->org, org, sizeof r->org);
    memcpy(r->dir, dir, sizeof r->dir);
    r->view = v->nviews - 1;
    return 1;
}

static void basis(const float d[3], float u[3], float w[3])
{
    float a[3] = {fabsf(d[0]) < 0.6f ? 1.0f : 0.0f, fabsf(d[0]) < 0.6f ? 0.0f : 1.0f, 0};
    oit_cross3f(d, a, u);
    float l = sqrtf(oit_dot3f(u, u)); /* > 0.5 for a unit d: a is far from it */
    for (int k = 0; k < 3; k++)
        u[k] /= l;
    oit_cross3f(d, u, w);
}

static int bundles(verifier *v, const oit_verify_options *o, uint64_t *rng, uint32_t *cap)
{
    uint32_t side = o->bundle_side ? o->bundle_side : 24;
    for (uint32_t b = 0; b < o->directions; b++) {
        float d[3], u[3], w[3], eye[3];
        random_direction(rng, d);
        basis(d, u, w);
        for (int k = 0; k < 3; k++)
            eye[k] = v->centre[k] - d[k] * v->radius * 1e4f;
        if (!add_view(v, eye))
            return 0;
        for (uint32_t i = 0; i < side * side; i++) {
            double a = ((i % side) + rng_unit(rng)) / side * 2 - 1;
            double c = ((i / side) + rng_unit(rng)) / side * 2 - 1;
            float org[3];
            for (int k = 0; k < 3; k++)
                org[k] = (float)(v->centre[k] - d[k] * 2 * v->radius +
                                 v->radius * (a * u[k] + c * w[k]));
            if (!add_ray(v, org, d, cap))
                return 0;
        }
    }
    return 1;
}

static int points(verifier *v, const oit_verify_options *o, uint64_t *rng, uint32_t *cap)
{
    uint32_t rays = o->rays_per_point ? o->rays_per_point : 1024;
    for (uint32_t p = 0; p < o->viewpoints; p++) {
        float eye[3];
        for (int k = 0; k < 3; k++) {
            /* The centre first; then points in the bounds grown by half. */
            double ext = v->hi[k] - v->lo[k];
            eye[k] = p == 0 ? v->centre[k]
                            : (float)(v->lo[k] - ext * 0.25 + rng_unit(rng) * ext * 1.5);
        }
        if (!add_view(v, eye))
            return 0;
        for (uint32_t i = 0; i < rays; i++) {
            float d[3];
            random_direction(rng, d);
            if (!add_ray(v, eye, d, cap))
                return 0;
        }
    }
    return 1;
}

static oit_status verify_open(verifier *v, const char *path, oit_error *err)
{
    oit_status s = oit_partfile_open(path, NULL, &v->pf, err);
    if (s)
        return s;
    s = oit_order_create(v->pf, &v->order, err);
    if (s)
        return s;
    oit_partfile_summary sum;
    oit_partfile_get_summary(v->pf, &sum);
    v->rep->measured_bounds = sum.measured_bounds;
    v->nparts = oit_partfile_part_count(v->pf);
    size_t n = v->nparts ? v->nparts : 1;
    v->rank = malloc(n * sizeof *v->rank);
    v->ordered = malloc(n * sizeof *v->ordered);
    v->count = calloc(n, sizeof *v->count);
    v->touched = malloc(n * sizeof *v->touched);
    v->bound = malloc(n * sizeof *v->bound);
    v->reached = calloc(n, 1);
    if (!v->rank || !v->ordered || !v->count || !v->touched || !v->bound || !v->reached)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", path);
    for (uint32_t p = 0; p < v->nparts; p++) {
        v->bound[p] = oit_partfile_parts(v->pf)[p].layer_bound;
        v->rep->max_layer_bound =
            v->bound[p] > v->rep->max_layer_bound ? v->bound[p] : v->rep->max_layer_bound;
    }
    double r2 = 0;
    for (int k = 0; k < 3; k++) {
        v->lo[k] = sum.bounds_min[k];
        v->hi[k] = sum.bounds_max[k];
        v->centre[k] = 0.5f * (v->lo[k] + v->hi[k]);
        r2 += 0.25 * ((double)v->hi[k] - v->lo[k]) * ((double)v->hi[k] - v->lo[k]);
    }
    v->radius = (float)fmax(sqrt(r2), 1e-6);
    v->tie = v->radius * 1e-5f;
    v->rep->parts = v->nparts;
    v->dev = rtcNewDevice("threads=1");
    if (!v->dev)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create an Embree device", path);
    return OIT_OK;
}

/* Vertices of part p outside lo <= n.x <= hi (slab i's planes), judged
 * exactly: a cutting plane's seam vertices lie on it to the last bit. */
static oit_status count_outside(verifier *v, uint32_t i, uint32_t p, double lo, double hi,
                                oit_error *err)
{
    const float *n = oit_partfile_slab_at(v->pf, i)->normal;
    oit_partfile_part_view pv;
    oit_status s = oit_partfile_part_data(v->pf, p, &v->decoded, &pv, err);
    uint32_t nv = s ? 0 : oit_partfile_parts(v->pf)[p].vertex_count;
    for (uint32_t k = 0; k < nv; k++) {
        float q[3];
        memcpy(q, (const char *)pv.positions + (size_t)k * pv.stride, sizeof q);
        double x = (double)n[0] * q[0] + (double)n[1] * q[1] + (double)n[2] * q[2];
        if ((lo > -INFINITY && oit_plane_side_exact(n, lo, q) < 0) ||
            (hi < INFINITY && oit_plane_side_exact(n, hi, q) > 0)) {
            note(v, "a vertex at n.x = %.9g, outside %.9g..%.9g (slab %u, part %u)", x, lo, hi, i,
                 p);
            v->rep->slab_violations++;
        }
    }
    return s;
}

/* A part to check against a slab's planes. */
typedef struct slab_side {
    uint32_t part, slab;
    double lo, hi;
} slab_side;

static int side_cmp(const void *a, const void *b)
{
    const slab_side *x = a, *y = b;
    if (x->part != y->part)
        return x->part < y->part ? -1 : 1;
    return (x->slab > y->slab) - (x->slab < y->slab);
}

/* Checked in file order, the pages read dropped every 64 MiB of file: a
 * fault maps its neighbours too, so slab parts spread over a 1.3 GB file
 * held 770 MB when checked slab by slab. */
static oit_status check_slabs(verifier *v, oit_error *err)
{
    uint32_t ns = oit_partfile_slab_count(v->pf);
    v->rep->slabs = ns;
    size_t n = 0, cap = 0;
    slab_side *list = NULL;
    for (uint32_t i = 0; i < ns; i++) {
        const oit_partfile_slab *sl = oit_partfile_slab_at(v->pf, i);
        uint32_t m = 0;
        const uint32_t *in = oit_partfile_slab_inside(v->pf, i, &m);
        if (n + m + 2 > cap) {
            cap = 2 * (n + m + 2);
            slab_side *p = realloc(list, cap * sizeof *p);
            if (!p) {
                free(list);
                return oit_error_set(err, OIT_ERR_NOMEM, "%s: slab check: out of memory",
                                     oit_partfile_name(v->pf));
            }
            list = p;
        }
        list[n++] = (slab_side){sl->part_below, i, -INFINITY, sl->d0};
        list[n++] = (slab_side){sl->part_above, i, sl->d1, INFINITY};
        for (uint32_t k = 0; k < m; k++)
            list[n++] = (slab_side){in[k], i, sl->d0, sl->d1};
    }
    if (n > 1)
        qsort(list, n, sizeof *list, side_cmp);
    oit_status s = OIT_OK;
    const oit_partfile_part *parts = oit_partfile_parts(v->pf);
    uint32_t drop_from = 0;
    for (size_t k = 0; k < n && !s; k++) {
        uint32_t p = list[k].part;
        s = count_outside(v, list[k].slab, p, list[k].lo, list[k].hi, err);
        /* By the span of file passed, not the bytes read: fault-around maps
         * the pages between the parts read too. */
        if (parts[p].data_offset - parts[drop_from].data_offset >= ((uint64_t)64 << 20) ||
            k + 1 == n) {
            oit_partfile_drop_part_data(v->pf, drop_from, p + 1 - drop_from);
            drop_from = p + 1 < v->nparts ? p + 1 : p;
        }
    }
    free(list);
    return s;
}

/* Check (4): the distinct source indices of all parts, in a bitmap of
 * triangles_in bits, against the triangles the converter kept. */
static oit_status check_sources(verifier *v, oit_error *err)
{
    oit_partfile_summary sum;
    oit_partfile_get_summary(v->pf, &sum);
    uint64_t words = sum.triangles_in / 64 + 1;
    uint64_t *seen = words <= SIZE_MAX / 8 ? calloc((size_t)words, 8) : NULL;
    if (!seen)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: source index map of %llu triangles: out "
                             "of memory", oit_partfile_name(v->pf),
                             (unsigned long long)sum.triangles_in);
    uint64_t found = 0;
    for (uint32_t p = 0; p < v->nparts; p++) {
        oit_partfile_part_view pv;
        oit_status s = oit_partfile_part_data(v->pf, p, &v->decoded, &pv, err);
        if (s) {
            free(seen);
            return s;
        }
        for (uint64_t t = 0; t < pv.index_count / 3; t++) {
            uint32_t i = oit_partfile_source(&pv, t); /* < triangles_in: validated */
            uint64_t bit = 1ull << (i % 64);
            found += !(seen[i / 64] & bit);
            seen[i / 64] |= bit;
        }
        oit_partfile_drop_part_data(v->pf, p, 1);
    }
    free(seen);
    v->rep->sources_kept = sum.triangles_in - sum.triangles_dropped;
    v->rep->sources_found = found;
    v->rep->sources_lost = found < v->rep->sources_kept ? v->rep->sources_kept - found : 0;
    if (v->rep->sources_lost && !v->rep->first_violation[0])
        snprintf(v->rep->first_violation, sizeof v->rep->first_violation,
                 "%llu of the %llu source triangles kept are in no part",
                 (unsigned long long)v->rep->sources_lost,
                 (unsigned long long)v->rep->sources_kept);
    return OIT_OK;
}

oit_status oit_verify(const char *path, const oit_verify_options *o, oit_verify_report *rep,
                      oit_error *err)
{
    memset(rep, 0, sizeof *rep);
    verifier v = {.rep = rep};
    rtcInitIntersectContext(&v.ray.rtc);
    oit_status s = verify_open(&v, path, err);
    uint64_t rng = o->seed ? o->seed : 0x6f69747072657031ull;
    uint32_t cap = 0;
    if (!s)
        s = check_slabs(&v, err);
    if (!s)
        s = check_sources(&v, err);
    if (!s && !(bundles(&v, o, &rng, &cap) && points(&v, o, &rng, &cap)))
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: rays: out of memory", path);
    if (!s)
        s = cast_all(&v, o->chunk_triangles ? o->chunk_triangles : OIT_VERIFY_CHUNK_TRIANGLES,
                     err);
    if (!s)
        s = check_all(&v, err);
    if (v.dev)
        rtcReleaseDevice(v.dev);
    oit_order_destroy(v.order);
    oit_partfile_close(v.pf);
    free(v.part_of_prim);
    oit_partfile_buffer_free(&v.decoded);
    free(v.rank);
    free(v.ordered);
    free(v.count);
    free(v.touched);
    free(v.bound);
    free(v.reached);
    free(v.ray.hits);
    free(v.rays);
    free(v.eyes);
    return s;
}

void oit_verify_print(FILE *f, const char *path, const oit_verify_report *r)
{
    fprintf(f, "%s: %llu rays (%llu hitting), %llu hits, %u parts (%u Embree scene%s)\n", path,
            (unsigned long long)r->rays, (unsigned long long)r->rays_hitting,
            (unsigned long long)r->hits, r->parts, r->chunks, r->chunks == 1 ? "" : "s");
    if (r->measured_bounds)
        fprintf(f, "  layers (measured bounds, not guaranteed): most hits of one part on one "
                   "ray %u (its bound %u; max bound %u); %llu parts reached their bound; %llu "
                   "part-rays over it, by at most %u (reported, not a failure)\n",
                r->max_hits_per_part, r->worst_part_bound, r->max_layer_bound,
                (unsigned long long)r->parts_at_bound, (unsigned long long)r->bound_exceeded,
                r->most_over_bound);
    else
        fprintf(f, "  layers: most hits of one part on one ray %u (its bound %u; max bound %u); "
                   "%llu parts reached their bound; %llu violations\n",
                r->max_hits_per_part, r->worst_part_bound, r->max_layer_bound,
                (unsigned long long)r->parts_at_bound, (unsigned long long)r->layer_violations);
    fprintf(f, "  order: %llu violations\n", (unsigned long long)r->order_violations);
    fprintf(f, "  slabs: %u, %llu vertices on the wrong side\n", r->slabs,
            (unsigned long long)r->slab_violations);
    fprintf(f, "  source triangles: %llu kept, %llu in the parts, %llu lost\n",
            (unsigned long long)r->sources_kept, (unsigned long long)r->sources_found,
            (unsigned long long)r->sources_lost);
    if (r->first_violation[0])
        fprintf(f, "  first violation: %s\n", r->first_violation);
}
