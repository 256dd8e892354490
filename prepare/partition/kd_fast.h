/* The fast scheme's subdivision of one grid cell into parts (DESIGN.md
 * "Visibility order"; OIT_SCHEME_FAST, prepare/convert/convert.h).
 *
 * Built for streaming speed, not for a layer guarantee: no convex pieces.
 * A node holding more than part_triangles triangles is split by an axis
 * plane (kd_split.h's candidates: sixteenths of the node and the triangles'
 * own coordinates, where a plane crosses nothing that ends on it; its
 * larger half keeps at most 3/4 of the node, so the depth stays
 * logarithmic; fewest crossed triangles, then balance),
 * the triangles crossing it are clipped to the two closed halves (clip.h:
 * canonical new vertices, a triangle in the plane goes below), and both
 * halves recurse. A node of at most part_triangles triangles is one part.
 * The result is the same kd-tree of 2x1x1 subgrids as prepare/partition/kd.h's, at
 * most one part a leaf, each part inside its leaf's closed box: the
 * contract of partfile/order.h, so the parts are exactly ordered per view.
 * Triangles are clipped only where a tree plane crosses them.
 *
 * Each part's layer_bound is its measured layer count (layers_measured.h:
 * sampled, not a guarantee). A part measured above OIT_PARTFILE_MAX_LAYERS
 * is split further, whatever its size, up to OIT_KD_FAST_EXTRA_DEPTH more
 * levels (a stack of many sheets halves its layers a level); one still
 * above then is recorded at that limit and counted in clamped_parts (a star
 * of sheets around one vertex keeps its layers in every box around it).
 * The result has one piece a part (plane_count = its triangle count: the
 * planes are not counted) and no slabs. wide_parts stays 0: a wide part is
 * the guaranteed scheme's node where more than K layers meet at a vertex
 * and no box separates them; a part here holds up to T triangles whatever
 * its layers, and the default captures need no bound (max_measured and
 * clamped_parts say how deep the parts are).
 */
#ifndef OIT_PARTITION_KD_FAST_H
#define OIT_PARTITION_KD_FAST_H

#include <stddef.h>
#include <stdint.h>

#include "prepare/partition/kd.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_KD_FAST_EXTRA_DEPTH 12u

typedef struct oit_kd_fast_params {
    uint32_t part_triangles; /* T: a node of at most T triangles is a part; >= 1 */
    uint32_t max_layers;     /* K of the file (not used: no part is wide here) */
    uint32_t max_depth;      /* splits below the cell; 0: 48 */
    uint64_t max_triangles;  /* the parts may hold in all; 0: no limit */
} oit_kd_fast_params;

/* Subdivides the box [lo, hi] holding tris[0..n) with their source indices
 * src[0..n) (NULL: i), both only read; out->src carries each one to the
 * pieces of its triangle, in input order within a part. Fails with
 * OIT_ERR_UNSUPPORTED when the parts would exceed max_triangles (the message
 * says so), OIT_ERR_ARGUMENT for part_triangles 0, or OIT_ERR_NOMEM. */
oit_status oit_kd_build_fast(const float lo[3], const float hi[3], const oit_triangle *tris,
                             const uint32_t *src, size_t n, const oit_kd_fast_params *params,
                             oit_kd_result *out, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
