/* Per-view visibility order of the parts of a part file.
 *
 * Contract with the converter (docs/part-file.md): every part lies inside the
 * closed box of each leaf cell that lists it, and a leaf cell lists at most
 * one part, or two parts separated by the cell's slab (part_below in
 * n.x <= d0, part_above in n.x >= d1, the slab's inside parts between). Under
 * that contract the order below is a valid visibility order from ANY eye
 * position (outside the model, inside it, on a cell boundary): grids are
 * traversed as implicit kd-trees (index ranges halved, near half first
 * relative to the eye), subgrids recursively in place of their parent cell,
 * slab cells by the eye's side of the slab planes. A part listed by several
 * leaf cells is emitted once, at its first cell in the traversal; that is
 * only valid when the cells it spans are consecutive in every order, which
 * the converter guarantees by listing each part in exactly one leaf cell.
 * Work per call is O(cells + parts); no O(parts^2) work. */
#ifndef OIT_PARTFILE_ORDER_H
#define OIT_PARTFILE_ORDER_H

#include <stdint.h>

#include "oit/partfile.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_order oit_order;

/* pf must outlive the order object. */
oit_status oit_order_create(const oit_partfile *pf, oit_order **out, oit_error *err);
void oit_order_destroy(oit_order *o);

/* Writes the parts front to back as seen from eye into parts (capacity
 * oit_partfile_part_count(pf)); *count receives how many were written (all
 * parts that some cell lists). */
oit_status oit_order_compute(oit_order *o, const float eye[3], uint32_t *parts,
                             uint32_t *count, oit_error *err);
/* The same, leaving out every grid range whose box lies wholly outside one
 * of the planes (a x + b y + c z + d >= 0 inside; oit_camera_frustum): none
 * of its parts can be seen. Boxes are grown by how far nested subgrids reach
 * beyond their parent cells, so the test holds under the file's contract
 * alone. The parts kept are in the same relative order; a view inside a
 * large model then orders only what lies in front of it. planes NULL: the
 * full order. */
oit_status oit_order_compute_culled(oit_order *o, const float eye[3], const float (*planes)[4],
                                    uint32_t *parts, uint32_t *count, oit_error *err);
/* The same for parallel rays along dir (an orthographic view's direction,
 * any length, not 0): a split or slab plane's near side is the one rays
 * come from, by the sign of dir . n (0: rays along the plane meet one side
 * only, either order holds); no eye point is involved. */
oit_status oit_order_compute_parallel(oit_order *o, const float dir[3],
                                      const float (*planes)[4], uint32_t *parts,
                                      uint32_t *count, oit_error *err);

/* The implicit kd-tree's one split rule: a cell index range [lo, hi) of g
 * with more than one cell splits on its longest side in world units (among
 * sides of more than one cell) into [lo, mid) and [mid, hi) on *axis. The
 * view only picks which half comes first; the shares (share.h) cut the
 * same tree, so the order of a view keeps each share's parts together. */
void oit_order_split_range(const oit_partfile_grid *g, const uint32_t lo[3], const uint32_t hi[3],
                           int *axis, uint32_t *mid);

#ifdef __cplusplus
}
#endif
#endif
