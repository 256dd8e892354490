/* The conversion's inside (convert.h), shared by its files: convert.c (the
 * passes over the input and the pipeline's order), convert_grid.c (the top
 * grid's cells), convert_cells.c (cells partitioned in parallel, consumed in
 * order) and convert_write.c (each cell's parts and grids given to the
 * writer). convert.c uses the other three, convert_cells.c uses
 * convert_write.c; nothing outside prepare/convert/ includes it. */
#ifndef OIT_PREPROCESS_CONVERT_INTERNAL_H
#define OIT_PREPROCESS_CONVERT_INTERNAL_H

#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "oit/partfile.h"
#include "partfile/write.h"
#include "prepare/partition/kd.h"
#include "prepare/convert/bin.h"
#include "prepare/convert/cell.h"
#include "prepare/convert/convert.h"

/* One top cell's result, filled by a worker (done set under the run's
 * lock), consumed by the writer in cell order. */
typedef struct cell_out {
    oit_kd_result kd;
    oit_cell_counts counts;
    oit_status status;
    oit_error err;
    int done;
    uint32_t part_base;
} cell_out;

typedef struct cell_run {
    const oit_convert_options *o;
    oit_bin_grid grid;
    oit_bins *bins;
    cell_out *res;
    uint64_t ncells;
    atomic_uint_fast64_t next;
    uint64_t written; /* cells the writer has consumed; workers stay close */
    int stop;
    pthread_mutex_t lock;
    pthread_cond_t cond;
} cell_run;

/* A part's arrays as the writer takes them, reused from part to part. */
typedef struct part_buf {
    float *pos;
    uint8_t *rgba;
    uint32_t *idx;
    uint32_t *slot; /* hash of vertex -> index + 1 */
    oit_partfile_piece_desc *pieces;
    size_t tri_cap, piece_cap;
} part_buf;

/* ---- convert_grid.c ---- */

/* The top grid (Cubic cells whose edge is a power of two, origin on a
 * multiple of it) over [mn, mx]: want cells along the longest axis, or
 * when want is 0 as few as give triangles / per_cell cells, at most 1024
 * an axis. */
void oit_convert_choose_grid(const float mn[3], const float mx[3], uint64_t triangles,
                             uint32_t want, double per_cell, oit_bin_grid *g);

/* The fast scheme's origin: moved down to a multiple of cell / 2^j (j up to
 * 8) where that gives fewer cells along an axis. */
void oit_convert_shift_origin(const float mn[3], const float mx[3], oit_bin_grid *g);

/* The fast scheme's grid without a grid given: a cell twice or four times larger
 * (origin shifted as above) when it still gives at least want cells and
 * fewer than g has. */
void oit_convert_fewest_cells(const float mn[3], const float mx[3], uint64_t want,
                              oit_bin_grid *g);

/* ---- convert_cells.c ---- */

/* Starts r->o->threads workers that partition r's cells (prepare/convert/cell.h)
 * within a window of the writer, and writes each cell's parts to w in cell
 * order, adding up st; sets each cell's part_base and frees all of its kd
 * result but the tree (for the grids). Joins the workers before it returns,
 * also on failure. */
oit_status oit_convert_partition_and_write(cell_run *r, oit_partfile_writer *w,
                                           uint32_t attributes, oit_convert_stats *st,
                                           oit_error *err);

/* ---- convert_write.c ---- */

/* kd's parts, each with its vertices deduplicated (exact position and
 * colour) in b, added to w in part order. */
oit_status oit_convert_write_parts(oit_partfile_writer *w, part_buf *b, const oit_kd_result *kd,
                                   uint32_t attributes, oit_error *err);

/* The top grid (each cell listing its root leaf's parts), then per cell its
 * kd splits as 2x1x1-style subgrids and its slab leaves, in cell order. */
oit_status oit_convert_write_grids(oit_partfile_writer *w, const cell_run *r, oit_error *err);

#endif
