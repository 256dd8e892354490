/* `oitprep verify`: checks a part file against the oracles of DESIGN.md with
 * rays, independently of the converter.
 *
 * The parts go into Embree scenes of at most chunk_triangles triangles, built,
 * cast and released one at a time (primitive -> part map); an intersect
 * filter records every hit and rejects it, so each ray sees all surfaces,
 * and the hits of all chunks are merged per ray before the checks.
 * Rays: (a) parallel bundles from M directions spread over the sphere,
 * covering the scene bounds, ordered for an eye far back along the
 * direction; (b) rays in random directions from V viewpoints inside and
 * around the bounds (the centre first), ordered for the viewpoint. Checks:
 * (1) no part yields more hits along a ray than its layer_bound (for a file
 * of measured bounds, the fast scheme's, the hits over it are reported,
 * not failed: the bound is an estimate there); (2) the
 * parts met along a ray, sorted by distance, never go back in the order that
 * partfile/order.h computes for the ray's origin (hits closer than a tolerance,
 * e.g. on a shared cell face, are ties); (3) every slab's part_below lies in
 * n.x <= d0 and its part_above in n.x >= d1, vertex by vertex and exactly,
 * and its inside parts between (docs/part-file.md leaves this to us);
 * (4) no triangle lost: every source triangle the converter kept (META's
 * triangles_in less triangles_dropped, the degenerate and non-finite ones)
 * is the source index of at least one part triangle. A triangle wholly
 * lost (all its clipped pieces rounded away) fails it.
 */
#ifndef OIT_PREPROCESS_VERIFY_H
#define OIT_PREPROCESS_VERIFY_H

#include <stdint.h>
#include <stdio.h>

#include "oit/status.h"

typedef struct oit_verify_options {
    uint32_t directions;      /* parallel bundles */
    uint32_t viewpoints;      /* point sources */
    uint32_t bundle_side;     /* rays per bundle = side^2; 0: 24 */
    uint32_t rays_per_point;  /* 0: 1024 */
    uint64_t seed;            /* 0: a fixed default */
    uint64_t chunk_triangles; /* most triangles in one Embree scene; 0: default */
} oit_verify_options;

/* Scenes of at most this many triangles (whole parts) are built, cast and
 * released one after another: memory holds one chunk's BVH, not the file's.
 * About 100 bytes a triangle while a chunk is held. */
#define OIT_VERIFY_CHUNK_TRIANGLES (4u << 20)

typedef struct oit_verify_report {
    uint64_t rays, hits, rays_hitting;
    uint32_t parts, max_hits_per_part; /* most hits one part gave one ray */
    uint32_t max_layer_bound;          /* of the parts */
    uint32_t worst_part_bound;         /* layer bound of the part that gave most */
    uint64_t parts_at_bound;           /* parts that reached their bound somewhere */
    uint64_t layer_violations, order_violations;
    /* A file of measured bounds (the fast scheme's) guarantees none:
     * a part giving a ray more hits than its bound is counted here instead
     * of in layer_violations, with the largest excess, and fails nothing. */
    int measured_bounds;
    uint64_t bound_exceeded;
    uint32_t most_over_bound;
    uint32_t slabs;
    uint64_t slab_violations; /* vertices on the wrong side of a slab plane */
    uint64_t sources_kept;    /* triangles_in - triangles_dropped */
    uint64_t sources_found;   /* distinct source indices in the parts */
    uint64_t sources_lost;    /* kept source triangles no part carries */
    uint32_t chunks;          /* Embree scenes built one after another */
    char first_violation[256];
} oit_verify_report;

oit_status oit_verify(const char *path, const oit_verify_options *o, oit_verify_report *rep,
                      oit_error *err);
void oit_verify_print(FILE *f, const char *path, const oit_verify_report *rep);

#endif
