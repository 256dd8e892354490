/* One top-grid cell of the conversion: clip its binned triangles to the
 * cell's closed box, cluster them into convex pieces, subdivide into parts
 * (prepare/partition/kd.h); or, in the fast scheme, subdivide the clipped triangles
 * into large parts with measured layer counts (prepare/partition/kd_fast.h). Independent of every other cell, so cells run in
 * parallel. */
#ifndef OIT_PREPROCESS_CELL_H
#define OIT_PREPROCESS_CELL_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "oit/status.h"
#include "prepare/partition/kd.h"

typedef struct oit_cell_params {
    float lo[3], hi[3];
    /* Per axis: the lower face is shared with a cell below. A triangle lying
     * in such a face belongs to the cell below (as in kd splits), so no
     * surface is stored twice. */
    int lo_shared[3];
    uint32_t K;
    uint32_t max_piece_triangles;
    uint32_t max_depth;
    oit_kd_slabs slabs;
    /* 0: Wang & Xie's guaranteed scheme (convex pieces, prepare/partition/kd.h); else
     * the fast scheme (prepare/partition/kd_fast.h) with parts of at most this many
     * triangles and no convex clustering. */
    uint32_t fast_part_triangles;
} oit_cell_params;

/* The cell's parts may hold at most this many times its clipped triangles,
 * plus 2^20 (prepare/partition/kd.h max_triangles). A fixed ratio, not a share of
 * the memory budget, so the file stays the same whatever the memory and
 * threads. */
#define OIT_CELL_MAX_GROWTH 64u

typedef struct oit_cell_counts {
    uint64_t clipped;      /* triangles after the box clip */
    uint64_t pieces_cell;  /* convex pieces before subdivision */
} oit_cell_counts;

/* src[i]: triangle i's source index; every triangle of out carries its
 * triangle's (out->src), a clipped piece that of the triangle it was cut
 * from. */
oit_status oit_cell_partition(const oit_cell_params *p, const oit_triangle *tris,
                              const uint32_t *src, size_t n, oit_kd_result *out,
                              oit_cell_counts *counts, oit_error *err);

#endif
