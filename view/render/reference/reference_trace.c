/* One reference worker (reference_job.h): per pixel, a ray whose every hit
 * the intersect filter records; the hits de-duplicated (spatial splits may
 * report a triangle twice), clipped to [znear, zfar] in view depth like GL
 * and by the section planes, keyed by the tie rule, sorted by (key, prim)
 * and composited in double precision with shade.h; and the ambiguity test,
 * which traces the neighbouring rays. */
#include "view/render/reference/reference_job.h"

#include "base/sort.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* rtcore_ray.h offers the SOA accessors to C++ only; these are the same
 * offsets (RTCRayN: tfar is the 9th float array; RTCHitN: u, v, primID are
 * the 4th, 5th and 6th). */
static float soa_float(const void *base, unsigned field, unsigned N, unsigned i)
{
    return ((const float *)base)[field * N + i];
}

static uint32_t soa_uint(const void *base, unsigned field, unsigned N, unsigned i)
{
    return ((const uint32_t *)base)[field * N + i];
}

void oit_reference_record_hit(const struct RTCFilterFunctionNArguments *args)
{
    ray_ctx *rc = (ray_ctx *)args->context;
    for (unsigned i = 0; i < args->N; i++) {
        if (args->valid[i] != -1)
            continue;
        args->valid[i] = 0; /* reject: traversal goes on to the next hit */
        if (rc->n == rc->cap) {
            size_t ncap = rc->cap ? rc->cap * 2 : 64;
            hit_rec *p = realloc(rc->hits, ncap * sizeof *p);
            if (!p) {
                rc->oom = 1;
                continue;
            }
            rc->hits = p;
            rc->cap = ncap;
        }
        hit_rec *h = &rc->hits[rc->n++];
        h->t = soa_float(args->ray, 8, args->N, i);
        h->u = soa_float(args->hit, 3, args->N, i);
        h->v = soa_float(args->hit, 4, args->N, i);
        h->prim = soa_uint(args->hit, 5, args->N, i);
    }
}

/* The orders of a ray's hits, as typed sorts (base/sort.h): no comparator
 * call through a pointer per comparison, in a loop run for every pixel. */
static int less_prim_t(const hit_rec *x, const hit_rec *y)
{
    return x->prim != y->prim ? x->prim < y->prim : x->t < y->t;
}

static int less_key_prim(const hit_rec *x, const hit_rec *y)
{
    return x->key != y->key ? x->key < y->key : x->prim < y->prim;
}

OIT_SORT_DEFINE(sort_prim_t, hit_rec, less_prim_t)
OIT_SORT_DEFINE(sort_key_prim, hit_rec, less_key_prim)

/* A line meets a triangle at most once, so repeated prims are duplicates of
 * one hit; keeps the nearest copy. Returns the new count. */
static size_t dedupe_hits(hit_rec *h, size_t n)
{
    if (n < 2)
        return n;
    sort_prim_t(h, n);
    size_t m = 1;
    for (size_t i = 1; i < n; i++)
        if (h[i].prim != h[m - 1].prim)
            h[m++] = h[i];
    return m;
}

static void make_ray(const double org[3], const double dir[3], struct RTCRayHit *rh)
{
    memset(rh, 0, sizeof *rh);
    rh->ray.org_x = (float)org[0];
    rh->ray.org_y = (float)org[1];
    rh->ray.org_z = (float)org[2];
    rh->ray.dir_x = (float)dir[0];
    rh->ray.dir_y = (float)dir[1];
    rh->ray.dir_z = (float)dir[2];
    rh->ray.tnear = 0.0f;
    rh->ray.tfar = INFINITY;
    rh->ray.mask = 0xffffffffu;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
}

static int depth_kept(const ref_job *job, double t, const double dir[3])
{
    return oit_ray_depth_kept(&job->basis, t, dir);
}

/* The transmittance a fragment arriving now would be tested against by an
 * early termination (capture.h): the largest channel, before any
 * absorption on the way to it. */
static int saturated_now(const ref_job *job, const oit_pixel_state *st)
{
    double e = job->saturation_epsilon;
    return e > 0.0 && st->T[0] < e && st->T[1] < e && st->T[2] < e;
}

/* Composites hits already in (t, prim) order that pass the view-depth clip;
 * returns how many were kept, and in *saturated how many of them came after
 * the pixel saturated (saturated_now). */
static uint32_t composite_hits(const ref_job *job, const hit_rec *hits, size_t n,
                               const double org[3], const double dir[3], float rgb[3],
                               uint32_t *ties, uint32_t *saturated)
{
    oit_pixel_state st;
    oit_pixel_begin(&st);
    uint32_t kept = 0;
    float last_key = -1.0f;
    *ties = 0;
    *saturated = 0;
    /* Shading looks back along the ray: from the eye, or (orthographic) from
     * the ray's origin on the near plane. */
    float from[3];
    for (int k = 0; k < 3; k++)
        from[k] = job->basis.ortho ? (float)org[k] : job->cam->eye[k];
    for (size_t i = 0; i < n; i++) {
        if (!depth_kept(job, hits[i].t, dir))
            continue;
        *ties += kept > 0 && hits[i].key - last_key <= hits[i].key * 0x1p-18f;
        last_key = hits[i].key;
        float bary[3] = {1.0f - hits[i].u - hits[i].v, hits[i].u, hits[i].v};
        oit_shaded_fragment f;
        oit_shade_fragment(&job->shading, &job->mesh->tris[hits[i].prim], hits[i].prim, bary,
                           from, hits[i].key, &f);
        *saturated += (uint32_t)saturated_now(job, &st);
        oit_pixel_add(&st, &job->shading, &f);
        kept++;
    }
    oit_pixel_end(&st, &job->shading, rgb);
    return kept;
}

size_t oit_reference_trace(RTCScene scene, ray_ctx *rc, const double org[3], const double dir[3])
{
    struct RTCRayHit rh;
    make_ray(org, dir, &rh);
    rc->n = 0;
    rtcIntersect1(scene, &rc->rtc, &rh);
    return dedupe_hits(rc->hits, rc->n);
}

/* Traces one ray; leaves its de-duplicated hits in wk->ray sorted by prim
 * and returns their count. */
static size_t trace_ray(ref_worker *wk, double px, double py, double org[3], double dir[3])
{
    ref_job *job = wk->job;
    oit_ray_basis_pixel(&job->basis, px, py, job->out->width, job->out->height, org, dir);
    return oit_reference_trace(job->scene, &wk->ray, org, dir);
}

/* Kept prims of the hits (sorted by prim) into wk->prims; returns the count
 * or SIZE_MAX when the array cannot grow. */
static size_t kept_prims(ref_worker *wk, size_t n, const double dir[3], uint32_t *out)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (depth_kept(wk->job, wk->ray.hits[i].t, dir)) {
            if (out && out[m] != wk->ray.hits[i].prim)
                return SIZE_MAX; /* differs from the centre */
            m++;
        }
    return m;
}

static int save_centre_prims(ref_worker *wk, size_t n, const double dir[3])
{
    if (n > wk->prims_cap) {
        uint32_t *p = realloc(wk->prims, n * sizeof *p);
        if (!p)
            return 0;
        wk->prims = p;
        wk->prims_cap = n;
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (depth_kept(wk->job, wk->ray.hits[i].t, dir))
            wk->prims[m++] = wk->ray.hits[i].prim;
    return 1;
}

/* 1 when any of four rays ambiguity_px off the centre meets a different
 * set of triangles than the centre ray (centre_n prims in wk->prims). */
static int hit_set_changes(ref_worker *wk, int x, int y, size_t centre_n)
{
    static const int offs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    double d = wk->job->ambiguity_px, org[3], dir[3];
    for (int k = 0; k < 4; k++) {
        size_t n = trace_ray(wk, x + 0.5 + offs[k][0] * d, y + 0.5 + offs[k][1] * d, org, dir);
        if (kept_prims(wk, n, dir, NULL) != centre_n || kept_prims(wk, n, dir, wk->prims) != centre_n)
            return 1;
    }
    return 0;
}

/* Each hit's sort key from its triangle's plane (shade.h), computed as the
 * GL methods do: the normal rotated into view space by the float view
 * matrix, the pixel's view-space ray from the ray map, so that both sides
 * round alike where they can. */
static void key_hits(const ref_job *job, hit_rec *h, size_t n, int x, int y)
{
    oit_ray_pixel p;
    oit_ray_pixel_at(&job->keying, x, y, &p);
    for (size_t i = 0; i < n; i++)
        h[i].clipped = !oit_ray_key_hit(&job->keying, &p, &job->mesh->tris[h[i].prim], h[i].t,
                                        &h[i].key);
}

/* Drops the hits a section plane removes; returns how many are left. */
static size_t drop_clipped(hit_rec *h, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!h[i].clipped)
            h[m++] = h[i];
    return m;
}

static void trace_pixel(ref_worker *wk, int x, int y)
{
    ref_job *job = wk->job;
    int w = job->out->width;
    double org[3], dir[3];
    size_t n = trace_ray(wk, x + 0.5, y + 0.5, org, dir);
    size_t centre_n = job->ambiguous ? kept_prims(wk, n, dir, NULL) : 0;
    if (job->ambiguous && !save_centre_prims(wk, n, dir))
        wk->ray.oom = 1;
    key_hits(job, wk->ray.hits, n, x, y);
    if (job->keying.clip_count > 0)
        n = drop_clipped(wk->ray.hits, n);
    if (n > 1)
        sort_key_prim(wk->ray.hits, n);
    float *px = job->out->rgba + ((size_t)y * w + x) * 4;
    uint32_t ties, saturated;
    uint32_t kept = composite_hits(job, wk->ray.hits, n, org, dir, px, &ties, &saturated);
    wk->saturated += saturated;
    if (job->ties)
        job->ties[(size_t)y * w + x] = ties;
    px[3] = 1.0f;
    if (job->counts)
        job->counts[(size_t)y * w + x] = kept;
    wk->fragments += kept;
    if (kept > wk->max_layers)
        wk->max_layers = kept;
    if (job->ambiguous)
        job->ambiguous[(size_t)y * w + x] =
            (uint8_t)(!wk->ray.oom && hit_set_changes(wk, x, y, centre_n));
}

void *oit_reference_render_rows(void *arg)
{
    ref_worker *wk = arg;
    ref_job *job = wk->job;
    rtcInitIntersectContext(&wk->ray.rtc);
    for (;;) {
        int y = atomic_fetch_add(&job->next_row, 1);
        if (y >= job->out->height || atomic_load(&job->oom))
            break;
        for (int x = 0; x < job->out->width; x++)
            trace_pixel(wk, x, y);
        if (wk->ray.oom)
            atomic_store(&job->oom, 1);
    }
    return NULL;
}
