/* The part file writer's inside (write.h), shared by its files: write.c
 * (create, the byte output, finish), write_part.c (parts and pieces),
 * write_grid.c (grids, subgrids, slabs) and write_sections.c (the
 * management sections, header and table finish writes). Nothing outside
 * partfile/ includes it. */
#ifndef OIT_PARTFILE_WRITE_INTERNAL_H
#define OIT_PARTFILE_WRITE_INTERNAL_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "oit/partfile.h"

#include "base/minmax.h"
#include "partfile/write.h"

/* A growable array of records (pf_vec_push). */
typedef struct vec {
    void *data;
    size_t count, capacity;
} vec;

struct oit_partfile_writer {
    char *path, *tmp_path;
    FILE *file;
    uint32_t K, part_align, attributes;
    double origin[3];
    char *source_name, *options;
    bool skip_verify, have_grid, measured_bounds;
    oit_partfile_order order;
    uint64_t pos;        /* bytes written so far            */
    uint64_t data_start; /* PART_DATA offset                */
    uint32_t data_crc;   /* running CRC of PART_DATA        */
    uint64_t triangles;
    uint64_t sources_end; /* 1 + the largest source index written, 0 before */
    vec parts, pieces;
    vec grids;                 /* oit_partfile_grid, 0 = top   */
    vec top_cells, sub_cells;  /* oit_partfile_cell            */
    vec top_list, sub_list;    /* uint32_t                     */
    vec slabs, slab_list;
};

/* Appends n items of size bytes (zeros when items is NULL), growing v by
 * doubling; OIT_ERR_NOMEM (v unchanged) when it cannot. */
oit_status pf_vec_push(vec *v, const void *items, size_t n, size_t size, oit_error *err);

/* Writes n bytes at the file's end (w->pos advances); OIT_ERR_IO naming
 * the temporary file. */
oit_status pf_write_bytes(oit_partfile_writer *w, const void *p, size_t n, oit_error *err);

/* Zero-fills up to the next multiple of align; *crc (if any) covers it. */
oit_status pf_pad_to(oit_partfile_writer *w, uint64_t align, uint32_t *crc, oit_error *err);

/* An empty box (min +inf, max -inf), which pf_bounds_add grows. Inline, as
 * it was in the one file: it runs per vertex. */
static inline void pf_bounds_reset(float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
}

/* Grows the box [lo, hi] to hold the point p. */
static inline void pf_bounds_add(float lo[3], float hi[3], const float *p)
{
    for (int k = 0; k < 3; k++) {
        lo[k] = oit_min_f(lo[k], p[k]);
        hi[k] = oit_max_f(hi[k], p[k]);
    }
}

/* ---- write_sections.c ---- */

/* At finish: META, PARTS, PIECES, GRID, SUBGRIDS and SLABS after the part
 * data, then the header and table at offset 0, then flush and fsync. */
oit_status pf_write_sections(oit_partfile_writer *w, const oit_partfile_stats *st, oit_error *err);

#endif
