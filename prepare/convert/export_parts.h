/* `oitprep parts`: a part file's parts as a coloured PLY, to look at the
 * decomposition rather than read its counts.
 *
 * Every triangle is written with its part's colour (positions offset back by
 * the file's origin, in double, so a georeferenced model keeps its place):
 * - OIT_EXPORT_BY_PART: each part a hue of its own (a hash of its index, so
 *   neighbours differ), the file's alpha kept;
 * - OIT_EXPORT_BY_KIND: grey for parts an axis split made, blue for the
 *   parts of a separating slab, orange for those of a cutting plane, red for
 *   wide parts (layer bound over K).
 * Rendered with oitstream (any method), cut seams and slab gaps show as
 * colour edges. Memory: one part at a time (the PLY writer streams). */
#ifndef OIT_PREPROCESS_EXPORT_PARTS_H
#define OIT_PREPROCESS_EXPORT_PARTS_H

#include <stdint.h>

#include "oit/status.h"

typedef enum oit_export_colour {
    OIT_EXPORT_BY_PART = 0,
    OIT_EXPORT_BY_KIND
} oit_export_colour;

typedef struct oit_export_counts {
    uint64_t parts, triangles;
    uint64_t separating_parts, cutting_parts, wide_parts; /* BY_KIND's classes */
} oit_export_counts;

/* Writes part file `path` to `out` (.ply). alpha: 0 keeps the file's alpha
 * (255 where it stores none), else every triangle gets it. counts may be
 * NULL. Errors name the file. */
oit_status oit_export_parts(const char *path, const char *out, oit_export_colour colour,
                            uint8_t alpha, oit_export_counts *counts, oit_error *err);

#endif
