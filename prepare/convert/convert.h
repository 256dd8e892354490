/* oitprep's conversion: mesh file in, part file out (DESIGN.md).
 *
 * Pass 1 streams the input for bounds and count; pass 2 bins triangles into
 * a regular top grid (prepare/convert/bin.h), dropping degenerate ones, each
 * with its source index (its position among the triangles the reader
 * delivers, counted before dropping), which every piece of it keeps to the
 * part file (docs/part-file.md, PART_DATA); cells are
 * partitioned in parallel (prepare/convert/cell.h) and written in cell order, so
 * the file is byte-identical for any thread count; every kd split becomes a
 * 2x1x1-style subgrid of its cell; each leaf cell lists its one part.
 */
#ifndef OIT_PREPROCESS_CONVERT_H
#define OIT_PREPROCESS_CONVERT_H

#include <stddef.h>
#include <stdint.h>

#include "oit/status.h"
#include "prepare/partition/kd.h"

/* How parts are formed and managed (Wang & Xie, Table 1). */
typedef enum oit_manage {
    OIT_MANAGE_GRID = 0,  /* a top grid of cells, each kd-subdivided into parts of
                             convex pieces (the default) */
    OIT_MANAGE_KD_PARTS,  /* one kd-tree over the whole model's convex pieces, one
                             part a leaf: the top grid is grid 1 (one cell an
                             axis, two where the model's bounds straddle a
                             power-of-two coordinate, since cells are aligned
                             to their size: the tree's first splits) */
    OIT_MANAGE_KD_FACETS  /* one kd-tree over facets: every triangle a piece of
                             its own (1 layer), leaves of at most K facets */
} oit_manage;

/* How cells become parts. */
typedef enum oit_scheme {
    OIT_SCHEME_FAST = 0,  /* the default: large parts of at most part_triangles
                             triangles, measured layer counts, no convexity
                             (prepare/partition/kd_fast.h); OIT_MANAGE_GRID only */
    OIT_SCHEME_GUARANTEED /* Wang & Xie: convex pieces, at most K layers a part
                             (prepare/partition/kd.h), for the paper's comparisons */
} oit_scheme;

/* Triangles a fast-scheme part may hold unless part_triangles says
 * otherwise. Measured (bench/fast-scheme-llvmpipe.md, 512x512 llvmpipe):
 * 32K streamed faster than 2K and 8K on the large models, and 128K faster
 * than 32K on the 1M plant in both runs that had it (482 against 559 ms),
 * where it also clips nothing (1.000x against 1.124x: its planes fall
 * between the plant's blocks); models below 128K triangles become 1-2
 * parts either way. */
#define OIT_FAST_PART_TRIANGLES 131072u

/* The scheme's name ("fast", "guaranteed"), as oitprep spells it. */
const char *oit_scheme_name(oit_scheme s);
/* The management's name ("grid", ...), as oitprep spells it. */
const char *oit_manage_name(oit_manage m);
/* The slab kinds' name ("all", ...), as oitprep spells it. */
const char *oit_slabs_name(oit_kd_slabs s);

typedef struct oit_convert_options {
    const char *input, *output;
    uint32_t K;                   /* even, 2..1024 */
    size_t memory;                /* bin budget in bytes */
    uint32_t threads;             /* >= 1 */
    uint32_t grid;                /* cells along the longest axis; 0: fast scheme
                                     cells of >= max(256K, 8 * part_triangles)
                                     triangles, guaranteed ~64K a cell */
    uint32_t max_piece_triangles; /* 0: convex.h default */
    oit_manage manage;            /* not GRID: grid must be 0 or 1, and for
                                     KD_FACETS max_piece_triangles 0 or 1 */
    oit_kd_slabs slabs;           /* all (default), separating, none;
                                     the fast scheme has no slabs */
    oit_scheme scheme;            /* 0: OIT_SCHEME_FAST */
    uint32_t part_triangles;      /* fast scheme: 0 = OIT_FAST_PART_TRIANGLES */
    int progress;                 /* oit_progress_mode (progress.h): off, a
                                     bar (a terminal) or periodic lines */
    double progress_period_s;     /* lines: seconds between them; 0: 5 */
    double deflection;            /* STEP/IGES tessellation (oit_read_desc's,
                                     oit/mesh.h): 0 for its default */
} oit_convert_options;

typedef struct oit_convert_stats {
    uint64_t triangles_in, triangles_out, degenerate_dropped, nonfinite_dropped;
    int64_t split_added;
    uint64_t pieces, parts, cells, subgrids, spilled_bytes;
    uint64_t pieces_clustered; /* convex pieces before subdivision clipped them */
    uint64_t wide_parts;       /* parts whose layer bound exceeds K (kd.h) */
    uint64_t slabs;            /* leaves split by a slab (kd_slab.h)     */
    uint64_t cut_slabs;        /* of them, cutting planes (kd_cut.h)     */
    uint32_t max_layer_bound;
    uint64_t clamped_parts;    /* fast scheme: measured above the file's 64, stored as 64 */
    uint32_t max_measured;     /* fast scheme: largest measured count before clamping */
    uint32_t subgrid_depth, grid_dims[3], threads, K;
    double seconds_total, seconds_bounds, seconds_bin, seconds_partition, seconds_write;
    uint64_t peak_rss_bytes;
    double deflection;         /* the reader's (oit_mesh_info): 0 but for STEP/IGES */
} oit_convert_stats;

/* oitprep's defaults for a conversion, so that a tool converting on the fly
 * (oitbench) makes the file oitprep would and follows it when a default
 * changes: K 8, 2G of bins, every online core, the default scheme and
 * management, no progress; input and output NULL. */
void oit_convert_options_init(oit_convert_options *o);

/* Exit-code mapping as usual: OIT_ERR_FORMAT / OIT_ERR_UNSUPPORTED are bad
 * input (3). The message names the input or output file. */
oit_status oit_convert(const oit_convert_options *o, oit_convert_stats *st, oit_error *err);

#endif
