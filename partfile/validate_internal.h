/* What the part file's checks share (validate.c, validate_parts.c,
 * validate_grids.c, part_blob.c): a section's bytes and the float tests of
 * every record. Inline, as they were when the checks were one file: they run
 * per vertex. Nothing outside partfile/ includes it. */
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

#endif
