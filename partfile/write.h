/* The part-file writer: what oitprep and the tests that build part files
 * link (the static library oit_partfile_write, with libmeshoptimizer's
 * encoders). Internal: liboit.so neither exports nor installs it; the
 * reader and the records it writes are oit/partfile.h.
 *
 * Parts are appended one at a time (their data goes to disk at once, only
 * the small records stay in memory); grids, subgrids and slabs follow;
 * oit_partfile_writer_finish writes the management sections and the header
 * to "<path>.tmp", validates that file with the reader and renames it to
 * <path>. The same calls give the same bytes.
 */
#ifndef OIT_PARTFILE_WRITE_H
#define OIT_PARTFILE_WRITE_H

#include <stdbool.h>
#include <stdint.h>

#include "oit/partfile.h"


typedef struct oit_partfile_writer oit_partfile_writer;

/* What the writer may reorder within a part before encoding it: smaller
 * encoded streams (meshoptimizer), the same triangles. */
typedef enum oit_partfile_order {
    OIT_PARTFILE_ORDER_KEEP = 0, /* stored as given                          */
    OIT_PARTFILE_ORDER_VERTICES, /* vertices renumbered in first-use order
                                    (fetch order); triangles keep theirs     */
    OIT_PARTFILE_ORDER_CACHE     /* (not used by oitprep: docs/part-file.md)
                                    also each piece's triangles in vertex-
                                    cache order, source indices with them    */
} oit_partfile_order;

typedef struct oit_partfile_writer_desc {
    uint32_t K;             /* layers per part; even, 2..1024; default 8      */
    uint32_t part_align;    /* blob alignment; power of two, 8..1 MiB;
                               default 4096 (page: one read, no split page) */
    uint32_t attributes;    /* OIT_ATTR_* of the source                       */
    const char *source_name; /* recorded in META; default ""                  */
    const char *options;     /* converter options, recorded; default ""       */
    double origin[3];        /* of the source's positions (oit_mesh_info);
                                finite; default 0                            */
    bool skip_verify;        /* default false: finish re-opens the file with the
                                reader before renaming it into place         */
    bool measured_bounds;    /* sets OIT_PARTFILE_FLAG_MEASURED_BOUNDS: every
                                part gives its layer_bound (1..64), not
                                bounded by its pieces                        */
    oit_partfile_order order; /* default OIT_PARTFILE_ORDER_KEEP            */
} oit_partfile_writer_desc;

/* Creates "<path>.tmp". desc may be NULL. */
oit_status oit_partfile_writer_create(const char *path, const oit_partfile_writer_desc *desc,
                                      oit_partfile_writer **out, oit_error *err);

typedef struct oit_partfile_piece_desc {
    uint64_t triangle_count; /* consecutive triangles of the part */
    uint32_t plane_count;
} oit_partfile_piece_desc;

typedef struct oit_partfile_part_desc {
    const float *positions;  /* vertex_count x 3                         */
    const uint8_t *rgba;     /* vertex_count x 4, or NULL: not stored    */
    uint32_t vertex_count;
    const uint32_t *indices; /* index_count, 3 per triangle; stored as 16-bit
                                when vertex_count <= 65536                */
    uint64_t index_count;
    const uint32_t *sources; /* index_count / 3: each triangle's source index
                                (oit_partfile_part_view.sources); required,
                                each < the finish stats' triangles_in    */
    const oit_partfile_piece_desc *pieces; /* cover the triangles in order */
    uint32_t piece_count;
    uint32_t layer_bound;    /* 0: min(K, 2*piece_count); with measured
                                bounds 1..64, required                    */
    uint32_t attributes;     /* OIT_ATTR_* the rgba holds; 0 with rgba
                                means OIT_ATTR_COLOUR|OIT_ATTR_ALPHA      */
} oit_partfile_part_desc;

/* Writes the part's blob now; bounds are computed from the data. */
oit_status oit_partfile_writer_add_part(oit_partfile_writer *w, const oit_partfile_part_desc *part,
                                        uint32_t *index, oit_error *err);

typedef struct oit_partfile_grid_desc {
    uint32_t dims[3];
    float origin[3];
    float cell_size[3];
    uint32_t parent_grid;        /* subgrids only: grid index (0 = top)  */
    uint32_t parent_cell;
    const uint32_t *cell_counts; /* parts per cell, dims product of them */
    const uint32_t *cell_parts;  /* the lists, concatenated, ascending   */
} oit_partfile_grid_desc;

/* Exactly once, before subgrids and slabs. */
oit_status oit_partfile_writer_set_grid(oit_partfile_writer *w, const oit_partfile_grid_desc *g,
                                        oit_error *err);
/* Returns the new grid's index (1, 2, ...). Parents come before children. */
oit_status oit_partfile_writer_add_subgrid(oit_partfile_writer *w, const oit_partfile_grid_desc *g,
                                           uint32_t *grid, oit_error *err);

typedef struct oit_partfile_slab_desc {
    float normal[3];
    float d0, d1;
    uint32_t grid, cell;
    uint32_t part_below, part_above;
    const uint32_t *inside; /* ascending */
    uint32_t inside_count;
} oit_partfile_slab_desc;

oit_status oit_partfile_writer_add_slab(oit_partfile_writer *w, const oit_partfile_slab_desc *s,
                                        uint32_t *slab, oit_error *err);

typedef struct oit_partfile_stats {
    uint64_t triangles_in;
    uint64_t triangles_dropped; /* degenerate or non-finite */
    uint64_t triangles_split;   /* added by splitting       */
} oit_partfile_stats;

/* Writes management sections and header, verifies, renames. Consumes w on
 * success and on failure (the .tmp file is removed on failure). stats may be
 * NULL: then triangles_in is the file's triangle count (a synthetic file
 * whose every triangle is its own source), nothing dropped or split. */
oit_status oit_partfile_writer_finish(oit_partfile_writer *w, const oit_partfile_stats *stats,
                                      oit_error *err);
/* Discards w and its .tmp file. NULL is allowed. */
void oit_partfile_writer_abort(oit_partfile_writer *w);

#endif
