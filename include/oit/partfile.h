/* The part file: a converted scene as oitstream reads it (its format:
 * part-file.md, installed in share/doc/oit).
 *
 * EXPERIMENTAL: everything in this header (the records, the reader and the
 * traversal of grids, cells and slabs) follows the file format
 * (OIT_PARTFILE_VERSION) and may change between minor versions of liboit,
 * whose package accepts only its own minor version. oit/liboit.h is the
 * stable way to draw a part file. Part files are written by oitprep; the
 * writer is not part of liboit.
 *
 * A part is at most K/2 convex pieces, so it yields at most K fragments per
 * pixel from any viewpoint (in a file flagged OIT_PARTFILE_FLAG_MEASURED_BOUNDS,
 * oitprep's fast scheme, a part's bound is measured instead, not
 * guaranteed); grids, subgrids and slabs order the parts per
 * view. One part's vertices and indices are one contiguous, aligned byte
 * range, so a streaming loader reads a part with one pread.
 *
 * Reader: maps the file read-only and validates every byte that it will hand
 * out before oit_partfile_open returns: header, section table, checksums,
 * record counts and every cross-reference. With defer_part_data the per-part
 * vertex/index/source blobs are validated instead by oit_partfile_validate_part,
 * which the loader calls before it first uses a part; oit_partfile_part_data
 * refuses a part that has not passed it. The records returned below are
 * decoded copies; part data is stored encoded (version 5) and decoded into
 * a caller's buffer (oit_partfile_part_data).
 *
 * The reader (and oitprep's writer) need a little-endian host with IEEE-754
 * floats (the file is little-endian and vertex data is handed to GL as
 * stored).
 */
#ifndef OIT_PARTFILE_H
#define OIT_PARTFILE_H

#include "oit/export.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_PARTFILE_VERSION 5u
/* The oldest version this build reads. Versions 1 to 3 store no source
 * triangle indices, version 4 stores its parts unencoded; all are refused
 * with a message that says to convert the model again. */
#define OIT_PARTFILE_VERSION_MIN 5u
#define OIT_PARTFILE_NONE 0xFFFFFFFFu /* "no grid / no cell" in parent links */
/* A part's layer bound is at most K, except for a wide part: where more than
 * K layers meet at one vertex no box separates them, so the part keeps its
 * bound (up to this) and the renderer captures it over smaller tiles. */
#define OIT_PARTFILE_MAX_LAYERS 64u
/* Header flag (version 3): the parts' layer bounds are measured (oitprep's
 * fast scheme counts them along sampled lines), not guaranteed. A part's
 * bound is then 1..OIT_PARTFILE_MAX_LAYERS whatever its pieces, and a ray
 * may meet more of its surfaces. Files without it are Wang & Xie's guarantee.
 * Builds before this flag refuse such a file (unknown flag), which is
 * right: they would take the bounds for guarantees. */
#define OIT_PARTFILE_FLAG_MEASURED_BOUNDS 1u

/* Decoded records. Their layout is the file's record layout (the reader
 * copies sections into them); part-file.md states every invariant. */
typedef struct oit_partfile_part {
    float bounds_min[3];    /* of the part's vertices, exactly              */
    float bounds_max[3];
    uint32_t layer_bound;   /* 1..2*piece_count: fragments per pixel; > K: wide;
                               measured bounds (header flag): 1..64, measured */
    uint32_t attributes;    /* OIT_ATTR_* stored per vertex (rgba8 if != 0)  */
    uint32_t piece_first;   /* range in the piece array                     */
    uint32_t piece_count;
    uint32_t index_bits;    /* 16 or 32                                     */
    uint32_t vertex_count;
    uint64_t index_count;   /* 3 per triangle                               */
    uint64_t data_offset;   /* file offset of the part's stored (encoded)
                               streams (aligned)                            */
    uint64_t data_bytes;    /* the decoded blob: vertices, pad to 4, indices,
                               pad to 4, source indices
                               (oit_partfile_source_offset)                 */
    uint64_t vertex_offset; /* within the decoded blob (0)                  */
    uint64_t vertex_bytes;
    uint64_t index_offset;  /* within the decoded blob                      */
    uint64_t index_bytes;
    uint32_t data_crc;      /* CRC-32C of the stored_bytes at data_offset   */
    uint32_t reserved;
    /* Version 5: the stored streams at data_offset, back to back
     * (part-file.md, PART_DATA): meshopt vertex codec, meshopt index
     * sequence codec, delta-varint source indices. */
    uint64_t stored_bytes;  /* their sum: one read                          */
    uint64_t stored_vertex_bytes;
    uint64_t stored_index_bytes;
    uint64_t stored_source_bytes;
} oit_partfile_part; /* 144 bytes */

typedef struct oit_partfile_piece {
    float bounds_min[3];     /* of the piece's triangles, exactly      */
    float bounds_max[3];
    uint32_t part;           /* owning part                           */
    uint32_t plane_count;    /* distinct supporting planes, >= 1      */
    uint64_t triangle_first; /* within the part's triangles           */
    uint64_t triangle_count;
} oit_partfile_piece; /* 48 bytes */

/* Grid 0 is the top grid; grid g >= 1 is subgrid g-1 of the SUBGRIDS
 * section. Cells are x-fastest: cell = x + dims[0]*(y + dims[1]*z). */
typedef struct oit_partfile_grid {
    uint32_t dims[3];
    uint32_t depth;       /* 0 for the top grid, parent depth + 1 otherwise */
    float origin[3];
    float cell_size[3];
    uint32_t parent_grid; /* OIT_PARTFILE_NONE for the top grid            */
    uint32_t parent_cell;
    uint64_t cell_first;  /* into the reader's unified cell array          */
    uint64_t cell_count;  /* dims[0]*dims[1]*dims[2]                       */
} oit_partfile_grid; /* 64 bytes */

typedef struct oit_partfile_cell {
    uint64_t list_first; /* into the section's part-index list     */
    uint32_t list_count; /* parts overlapping the cell (ascending) */
    uint32_t subgrid;    /* 0: none; g: grid g refines this cell   */
    uint32_t slab;       /* 0: none; s+1: slab s separates the cell */
    uint32_t reserved;
} oit_partfile_cell; /* 24 bytes */

/* Two parallel planes n.x = d0 <= d1 in one cell: part_below lies in
 * n.x <= d0, part_above in n.x >= d1, the inside parts between them. The
 * normal need not be unit (version 3): a cutting plane (d0 = d1) has an
 * integer normal so that its seam vertices lie on it exactly. */
typedef struct oit_partfile_slab {
    float normal[3];
    float d0, d1;
    uint32_t grid, cell;
    uint32_t part_below, part_above;
    uint32_t inside_count;
    uint64_t inside_first; /* into the SLABS part-index list */
} oit_partfile_slab; /* 48 bytes */

typedef struct oit_partfile_summary {
    uint32_t version;
    uint32_t K;
    uint64_t triangles;     /* stored (after dropping and splitting)        */
    uint64_t triangles_in;  /* read from the source                         */
    uint64_t triangles_dropped;
    uint64_t triangles_split;
    uint64_t parts;
    uint64_t pieces;
    uint64_t slabs;
    uint64_t cells;         /* top grid and subgrids together               */
    uint64_t subgrids;
    uint32_t subgrid_depth; /* deepest subgrid; 0 without subgrids          */
    uint32_t layer_bound;   /* max over parts                               */
    uint32_t attributes;    /* OIT_ATTR_* of the source                     */
    uint32_t part_align;
    uint64_t parts_index16;
    uint64_t parts_index32;
    uint64_t bytes;         /* file size                                    */
    uint64_t data_bytes;    /* PART_DATA section size                       */
    float bounds_min[3];
    float bounds_max[3];
    double origin[3];       /* positions are relative to it (oit_mesh_info) */
    uint64_t cut_slabs;     /* of slabs, cutting planes (d0 = d1)           */
    bool measured_bounds;   /* OIT_PARTFILE_FLAG_MEASURED_BOUNDS is set     */
} oit_partfile_summary;

/* ---- reader: EXPERIMENTAL ---------------------------------------------- */

typedef struct oit_partfile oit_partfile;

typedef struct oit_partfile_open_desc {
    /* false (default): open validates every part's blob (checksum, index
     * values, vertices inside bounds). true: open reads only the management
     * sections, and each part must pass oit_partfile_validate_part before
     * oit_partfile_part_data hands it out. */
    bool defer_part_data;
} oit_partfile_open_desc;

/* desc may be NULL. On failure *out is NULL and err names the file. */
OIT_API oit_status oit_partfile_open(const char *path, const oit_partfile_open_desc *desc,
                                     oit_partfile **out, oit_error *err);
/* The same over bytes already in memory (not copied: they must outlive the
 * handle). name is used in messages. */
OIT_API oit_status oit_partfile_open_memory(const void *data, size_t size, const char *name,
                                            const oit_partfile_open_desc *desc,
                                            oit_partfile **out, oit_error *err);
OIT_API void oit_partfile_close(oit_partfile *pf);

OIT_API void oit_partfile_get_summary(const oit_partfile *pf, oit_partfile_summary *out);
OIT_API const char *oit_partfile_name(const oit_partfile *pf);
OIT_API const char *oit_partfile_source_name(const oit_partfile *pf); /* NUL-terminated */
OIT_API const char *oit_partfile_options(const oit_partfile *pf);     /* NUL-terminated */

OIT_API uint32_t oit_partfile_part_count(const oit_partfile *pf);
OIT_API const oit_partfile_part *oit_partfile_parts(const oit_partfile *pf);
OIT_API uint64_t oit_partfile_piece_count(const oit_partfile *pf);
OIT_API const oit_partfile_piece *oit_partfile_pieces(const oit_partfile *pf);

/* Checks part's blob: checksum, index values < vertex_count, vertices
 * finite and inside the part bounds, triangles inside their piece bounds,
 * source indices < the file's triangles_in.
 * Idempotent; distinct parts may be validated from different threads. */
OIT_API oit_status oit_partfile_validate_part(oit_partfile *pf, uint32_t part, oit_error *err);

typedef struct oit_partfile_part_view {
    const void *blob;     /* the decoded blob, data_bytes (in the buffer) */
    const float *positions; /* vertex i at (const char*)positions + i*stride */
    const uint8_t *rgba;  /* NULL when the part stores no colour           */
    uint32_t stride;      /* 12, or 16 with rgba                          */
    uint32_t index_bits;  /* 16 or 32                                     */
    const void *indices;
    uint64_t index_count;
    /* index_count / 3 u32: each triangle's source index, its 0-based
     * position among the triangles the mesh reader delivered for the source
     * file (oit_mesh_read), < triangles_in. A clipped piece carries the index
     * of the triangle it was cut from; a triangle in several parts carries
     * it in each. Read with oit_partfile_source. */
    const void *sources;
} oit_partfile_part_view;

/* Where parts are decoded to: grown as needed, reused across parts, so a
 * loader decoding part after part allocates once. Zero-initialise; free
 * with oit_partfile_buffer_free. One buffer holds one decoded part: a view
 * lasts until the buffer is reused or freed. */
typedef struct oit_partfile_buffer {
    void *data;
    size_t capacity;
} oit_partfile_buffer;
OIT_API void oit_partfile_buffer_free(oit_partfile_buffer *buf);

/* Decodes a validated part into buf and points the view at it. Fails with
 * OIT_ERR_ARGUMENT for an index out of range, or for a part not validated
 * yet when the file was opened with defer_part_data; OIT_ERR_NOMEM. */
OIT_API oit_status oit_partfile_part_data(const oit_partfile *pf, uint32_t part,
                                          oit_partfile_buffer *buf, oit_partfile_part_view *out,
                                          oit_error *err);
/* oit_partfile_validate_part and oit_partfile_part_data in one decode: the
 * loader's path (a part is decoded once a use, also on its first). */
OIT_API oit_status oit_partfile_part_load(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                                          oit_partfile_part_view *out, oit_error *err);
/* A hint that parts [first, first + count) will not be read for a while:
 * the pages of a mapped file that hold their data leave the process (they
 * stay in the page cache and fault back in when read), so a tool that reads
 * every part once does not end holding the whole file. Views handed out
 * stay valid. No effect on a file read into memory; out-of-range parts are
 * ignored. */
OIT_API void oit_partfile_drop_part_data(const oit_partfile *pf, uint32_t first, uint32_t count);

/* Index i (< index_count) of a part view, whatever its width. Loads through
 * memcpy: a file opened from a caller's buffer (oit_partfile_open_memory)
 * need not be aligned even though offsets inside it are. */
static inline uint32_t oit_partfile_index(const oit_partfile_part_view *v, uint64_t i)
{
    if (v->index_bits == 16) {
        uint16_t h;
        memcpy(&h, (const uint8_t *)v->indices + i * 2, sizeof h);
        return h;
    }
    uint32_t x;
    memcpy(&x, (const uint8_t *)v->indices + i * 4, sizeof x);
    return x;
}

/* Source index of triangle i (< index_count / 3) of a part view (memcpy,
 * as oit_partfile_index). */
static inline uint32_t oit_partfile_source(const oit_partfile_part_view *v, uint64_t i)
{
    uint32_t x;
    memcpy(&x, (const uint8_t *)v->sources + i * 4, sizeof x);
    return x;
}

/* Where a part's source indices start within its blob: after the index
 * stream, rounded up to 4 (part-file.md). */
static inline uint64_t oit_partfile_source_offset(const oit_partfile_part *p)
{
    return (p->index_offset + p->index_bytes + 3u) & ~(uint64_t)3u;
}

/* ---- traversal: EXPERIMENTAL ------------------------------------------- */
/* The management tree as stored (the order oitstream draws parts in is
 * computed from it per view). Like the whole header it follows the file
 * format and may change between minor versions.
 *
 * Grids: index 0 is the top grid, 1..grid_count-1 the subgrids. NULL when
 * out of range. */
OIT_API uint32_t oit_partfile_grid_count(const oit_partfile *pf);
OIT_API const oit_partfile_grid *oit_partfile_grid_at(const oit_partfile *pf, uint32_t grid);
/* The cells of a grid (cell_count of them), NULL when out of range. */
OIT_API const oit_partfile_cell *oit_partfile_cells(const oit_partfile *pf, uint32_t grid);
/* The ascending part indices of one cell; *count set (0 when out of range). */
OIT_API const uint32_t *oit_partfile_cell_parts(const oit_partfile *pf, uint32_t grid,
                                                uint64_t cell, uint32_t *count);

OIT_API uint32_t oit_partfile_slab_count(const oit_partfile *pf);
OIT_API const oit_partfile_slab *oit_partfile_slab_at(const oit_partfile *pf, uint32_t slab);
OIT_API const uint32_t *oit_partfile_slab_inside(const oit_partfile *pf, uint32_t slab,
                                                 uint32_t *count);

#ifdef __cplusplus
}
#endif
#endif
