/* Out-of-core binning of triangles into the cells of a regular grid.
 *
 * A triangle goes to every cell its bounding box overlaps (closed boxes, so a
 * triangle lying in a cell face reaches both cells; the clip that follows
 * decides). Every triangle carries its source index (its position among the
 * triangles the reader delivered), kept in a parallel array: a triangle in
 * several cells carries it in each. Bins are kept in memory until their
 * total exceeds the budget; then every bin is appended to one spill file as
 * a chunk record (cell id, count, triangles, source indices) and freed. A cell's triangles are read back as its chunks
 * in spill order followed by its in-memory tail: the input order, whether or
 * not anything was spilled. The spill file is unlinked as soon as it is
 * created, so nothing is left behind. Reading cells is thread-safe (pread)
 * once adding has finished.
 */
#ifndef OIT_PREPROCESS_BIN_H
#define OIT_PREPROCESS_BIN_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "oit/status.h"

typedef struct oit_bin_grid {
    float origin[3];
    float cell;       /* cell edge: a power of two, so cell faces are exact */
    uint32_t dims[3];
} oit_bin_grid;

typedef struct oit_bins oit_bins;

/* spill_path: where the spill file is created (and unlinked) if needed. */
oit_status oit_bins_create(const oit_bin_grid *grid, size_t memory_budget, const char *spill_path,
                           oit_bins **out, oit_error *err);
/* src[i]: triangle i's source index. */
oit_status oit_bins_add(oit_bins *b, const oit_triangle *tris, const uint32_t *src, size_t count,
                        oit_error *err);
/* The cell's triangles and their source indices in new malloc'd arrays
 * (both NULL when empty). A cell is read once: its in-memory part is
 * released (a second read finds only what was spilled). */
oit_status oit_bins_read_cell(oit_bins *b, uint64_t cell, oit_triangle **tris, uint32_t **src,
                              size_t *count, oit_error *err);
uint64_t oit_bins_spilled_bytes(const oit_bins *b);
void oit_bins_destroy(oit_bins *b);

/* Cells overlapped by the box [mn, mx], as inclusive index ranges. */
void oit_bin_cell_range(const oit_bin_grid *g, const float mn[3], const float mx[3],
                        uint32_t lo[3], uint32_t hi[3]);

#endif
