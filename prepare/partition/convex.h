/* Greedy convex clustering of triangles (DESIGN.md, "Layer bound").
 *
 * A piece is a set of triangles such that, for each triangle's plane, every
 * vertex of the piece lies on one side of it (exact orient3d), and no two
 * coplanar triangles of the piece overlap in their plane (coplanar triangles
 * facing opposite ways never share a piece: a double-sided face is two
 * layers). A line not lying in one of its planes meets such a piece at most
 * twice, so K/2 pieces give at most K layers.
 *
 * Greedy and deterministic: the lowest unassigned triangle seeds a piece,
 * which grows breadth-first over shared edges (equal vertex positions),
 * accepting a neighbour when the piece stays convex. Each triangle is tested
 * at most once per piece: adding triangles only adds constraints, so a
 * rejection is final for that piece.
 *
 * Input triangles must be non-degenerate (clip.h drops degenerate ones).
 */
#ifndef OIT_PARTITION_CONVEX_H
#define OIT_PARTITION_CONVEX_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_CONVEX_MAX_PIECE_DEFAULT 4096u

typedef struct oit_convex_params {
    /* Stop growing a piece at this many triangles (0: 4096). A piece's test
     * costs O(its vertices + planes) per candidate, so the cap bounds the
     * work per triangle on large convex regions. */
    uint32_t max_piece_triangles;
} oit_convex_params;

typedef struct oit_convex_result {
    uint32_t *piece_of;    /* per triangle: its piece, numbered in seed order */
    uint32_t *plane_of;    /* per triangle: its plane within its piece, 0..  */
    uint32_t *plane_count; /* per piece: distinct supporting planes          */
    uint32_t piece_count;
} oit_convex_result;

/* Clusters tris[0..n). params may be NULL. On success fills out (free with
 * oit_convex_result_free). Fails only with OIT_ERR_NOMEM. */
oit_status oit_convex_cluster(const oit_triangle *tris, size_t n, const oit_convex_params *params,
                              oit_convex_result *out, oit_error *err);
void oit_convex_result_free(oit_convex_result *r);

/* Brute-force check of the definition above for the triangles tris[idx[i]],
 * i < count (every vertex against every plane, every coplanar pair). Returns
 * 1 when they form a convex piece. O(count^2); for tests and the verifier. */
int oit_convex_check(const oit_triangle *tris, const uint32_t *idx, size_t count);

#ifdef __cplusplus
}
#endif
#endif
