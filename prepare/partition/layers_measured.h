/* A part's measured layer count, for the fast scheme (prepare/partition/kd_fast.h).
 *
 * What is measured: for each of OIT_LAYERS_DIRECTIONS fixed directions (the
 * 3 axes, the 6 face diagonals, the 4 body diagonals), the triangles are
 * projected onto the plane perpendicular to the direction, a
 * OIT_LAYERS_GRID x OIT_LAYERS_GRID grid is laid over their projected
 * bounds, and at every cell centre the triangles whose projection contains
 * it are counted. The result is the largest count over all centres and
 * directions: the most surfaces one of those 13 x 4096 parallel lines
 * crosses inside the part.
 *
 * What it is NOT: a bound. A line between the sampled centres, or in another
 * direction, or from a perspective eye, may cross more triangles (a thin
 * feature missed by the grid, a fold seen edge-on in a direction we do not
 * sample), and a rasterizer may count a triangle that the centre test did
 * not. Wang & Xie's convex pieces give a guarantee (prepare/partition/kd.h); this is
 * an estimate of the part's depth complexity, cheap and deterministic. The
 * counted capture (view/render/capture/capture_counted.h) needs no bound at all; the
 * K-slot packs take it as their layer budget, so there a pixel that gets
 * more is counted as overflow, never hidden.
 *
 * Cell centres are offset from the grid by an irrational fraction, so that
 * on axis-aligned (CAD) geometry they avoid the shared edges and vertices
 * where a line would meet two triangles of one surface. Triangles seen
 * edge-on in a direction project to no area and count for none of its
 * lines. The result depends only on the triangles (not their order or the
 * thread): the same input gives the same part file.
 */
#ifndef OIT_PARTITION_LAYERS_MEASURED_H
#define OIT_PARTITION_LAYERS_MEASURED_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "oit/status.h"

#define OIT_LAYERS_DIRECTIONS 13u
#define OIT_LAYERS_GRID 64u

/* Sets *layers to the measured count (1 for an empty or edge-on part: a part
 * file's layer bound is at least 1). Returns OIT_ERR_NOMEM (err says for
 * how many triangles) when the count grid cannot be allocated. */
oit_status oit_layers_measure(const oit_triangle *tris, size_t n, uint32_t *layers,
                              oit_error *err);

#endif
