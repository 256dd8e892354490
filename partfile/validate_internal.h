/* What the part file's checks share (validate.c, validate_parts.c,
 * validate_grids.c, part_blob.c): a section's bytes and the float tests of
 * every record, inline as they were when the checks were one file (they run
 * per vertex), and the record checks validate.c runs in order. Each check
 * may rely on those pf_validate_all runs before it (handle.h). Nothing
 * outside partfile/ includes it. */
#ifndef OIT_PARTFILE_VALIDATE_INTERNAL_H
#define OIT_PARTFILE_VALIDATE_INTERNAL_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "partfile/handle.h"

/* The bytes of section type (a PF_SEC_ value), which the checked section
 * table places inside the file. */
static inline const uint8_t *pf_sec_data(const oit_partfile *pf, uint32_t type)
{
    return pf->base + pf->sec[type - 1].offset;
}

/* The byte size of section type. */
static inline uint64_t pf_sec_size(const oit_partfile *pf, uint32_t type)
{
    return pf->sec[type - 1].size;
}

/* All three coordinates finite. */
static inline bool pf_finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* A box whose corners are finite and min <= max on every axis. */
static inline bool pf_box_ok(const float lo[3], const float hi[3])
{
    return pf_finite3(lo) && pf_finite3(hi) && lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2];
}

/* ---- validate_parts.c: PARTS and PIECES ---- */

/* Copies PARTS and PIECES into pf->parts and pf->pieces (pf->piece_count):
 * whole records, as many parts as the header says, fewer than 2^32. Needs
 * the checked header and table. */
oit_status pf_load_parts(oit_partfile *pf, oit_error *err);

/* Every part's record, its blob's place in PART_DATA (aligned, in order,
 * inside) and its pieces (contiguous, covering its triangles, inside its
 * bounds); the parts' triangles add up to the header's. Needs META loaded. */
oit_status pf_check_parts(const oit_partfile *pf, oit_error *err);

/* META's scene bounds are exactly the union of the parts' bounds. */
oit_status pf_check_scene_bounds(const oit_partfile *pf, oit_error *err);

/* ---- validate_grids.c: GRID, SUBGRIDS, SLABS and their links ---- */

/* Parses GRID and SUBGRIDS into the unified grid, cell and list arrays,
 * each grid, cell and list checked (lists name existing parts, ascending),
 * offsets shifted to unified ones. Needs the checked header and table. */
oit_status pf_load_grids(oit_partfile *pf, oit_error *err);

/* Copies SLABS into pf->slabs and pf->slab_list (sizes checked only). */
oit_status pf_load_slabs(oit_partfile *pf, oit_error *err);

/* Every slab: its planes, its cell (which names it back), its two parts and
 * inside list among the cell's parts. Needs grids and slabs loaded. */
oit_status pf_check_slabs(const oit_partfile *pf, oit_error *err);

/* Subgrids refine the cell that names them (and only that one), inside
 * the region it stands for; cells name existing slabs. */
oit_status pf_check_links(const oit_partfile *pf, oit_error *err);

/* Every part is in at least one cell's list. */
oit_status pf_check_coverage(const oit_partfile *pf, oit_error *err);

#endif
