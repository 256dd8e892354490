/* Where the fast scheme's top grid puts its faces (prepare/convert/convert.c).
 *
 * The top grid's cell faces clip every triangle they cross, blindly: on a
 * 12M-triangle plant they made 93% of the clipped triangles (the kd below
 * picks planes that cross few). The cell size is fixed by the triangle
 * count and the bounds; the faces' phase, the origin modulo the cell, is
 * free. This counts, over one pass of the triangles, how many a face would
 * cross at each of OIT_GRID_PHASES phases per axis (multiples of cell / 256,
 * exact floats like the cell faces themselves: a power-of-two fraction of a
 * power of two), and moves each axis's origin to the phase that crosses
 * fewest, fewer cells breaking ties. A triangle that only touches a face is
 * not crossed (clipping leaves it whole). */
#ifndef OIT_PREPROCESS_GRID_PHASE_H
#define OIT_PREPROCESS_GRID_PHASE_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "prepare/convert/bin.h"

#define OIT_GRID_PHASES 256

typedef struct oit_grid_phase {
    double base[3], cell;                   /* phase 0 lies at base + i cell */
    int64_t diff[3][OIT_GRID_PHASES + 1];   /* crossings, as differences over phases */
} oit_grid_phase;

/* For the grid g (its cell size; its origin is replaced by _apply). */
void oit_grid_phase_init(oit_grid_phase *p, const oit_bin_grid *g);
void oit_grid_phase_add(oit_grid_phase *p, const oit_triangle *t, size_t n);
/* Sets g's origin and dims: per axis the phase of fewest crossings whose
 * grid still covers [mn, mx]. */
void oit_grid_phase_apply(const oit_grid_phase *p, const float mn[3], const float mx[3],
                          oit_bin_grid *g);

#endif
