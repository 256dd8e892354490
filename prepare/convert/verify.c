/* Ray-cast verification of a part file (verify.h). This file opens the
 * file, draws the rays, runs the checks in order and prints the report;
 * rays are cast in verify_cast.c, their hits checked in verify_hits.c,
 * slabs and source triangles in verify_data.c (verify_internal.h). */
#include "prepare/convert/verify.h"
#include "base/vec.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/partfile.h"
#include "partfile/order.h"
#include "prepare/convert/verify_internal.h"

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
        s = oit_verify_check_slabs(&v, err);
    if (!s)
        s = oit_verify_check_sources(&v, err);
    if (!s && !(bundles(&v, o, &rng, &cap) && points(&v, o, &rng, &cap)))
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: rays: out of memory", path);
    if (!s)
        s = oit_verify_cast_all(
            &v, o->chunk_triangles ? o->chunk_triangles : OIT_VERIFY_CHUNK_TRIANGLES, err);
    if (!s)
        s = oit_verify_check_rays(&v, err);
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
