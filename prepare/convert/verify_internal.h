/* The verifier's inside (verify.h), shared by its files: verify.c (the
 * file opened, the rays drawn, the checks run in order, the report),
 * verify_cast.c (rays cast through Embree scenes of a chunk of parts),
 * verify_hits.c (checks (1) and (2) on each ray's hits) and verify_data.c
 * (checks (3) and (4), which read the parts, not rays). verify.c uses the
 * other three; nothing outside prepare/convert/ includes it. */
#ifndef OIT_PREPROCESS_VERIFY_INTERNAL_H
#define OIT_PREPROCESS_VERIFY_INTERNAL_H

#include <embree3/rtcore.h>
#include <stdint.h>
#include <stdio.h>

#include "oit/partfile.h"
#include "partfile/order.h"
#include "prepare/convert/verify.h"

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

/* The first violation's message, kept in the report (later ones are
 * counted only). */
static inline void oit_verify_note(verifier *v, const char *fmt, double a, double b, double c,
                                   unsigned p, unsigned q)
{
    if (v->rep->first_violation[0])
        return;
    snprintf(v->rep->first_violation, sizeof v->rep->first_violation, fmt, a, b, c, p, q);
}

/* ---- verify_cast.c ---- */

/* Every ray through every chunk of at most chunk_triangles triangles (a
 * part is never divided), each chunk an Embree scene built, cast and
 * released in turn; the hits gather in v->ray. */
oit_status oit_verify_cast_all(verifier *v, uint64_t chunk_triangles, oit_error *err);

/* ---- verify_hits.c ---- */

/* Sorts the hits into one list per ray, by t, and checks each ray: (1)
 * hits per part against its layer bound, (2) the parts' order from the
 * ray's viewpoint. Counts into v->rep; frees the gathered hits. */
oit_status oit_verify_check_rays(verifier *v, oit_error *err);

/* ---- verify_data.c ---- */

/* (3) Every part of a slab on its side of the slab's planes, judged
 * exactly, in file order. */
oit_status oit_verify_check_slabs(verifier *v, oit_error *err);

/* (4) The distinct source indices of all parts against the triangles the
 * converter kept. */
oit_status oit_verify_check_sources(verifier *v, oit_error *err);

#endif
