/* Whether a part file was made from a mesh: oitbench compares the two only
 * when it was (bench_models.h), never two models by mistake.
 *
 * Part files record the source's name but no digest of it, so the test is
 * on what clipping preserves: the triangles read (META triangles_in against
 * the mesh's delivered plus non-finite dropped, as oitprep counts), the
 * origin (exactly), the bounds (to 1/1000 of the diagonal: dropped
 * degenerate triangles may shrink them), and the surface's area and
 * area-weighted centroid (to 1e-4 relative and 1e-4 of the diagonal): a
 * clip splits a triangle into pieces of the same total area and moment, so
 * a file of the same model agrees to rounding, and one of another model
 * with as many triangles and the same box does not. The area pass reads
 * every part once. */
#ifndef OIT_OITBENCH_BENCH_MATCH_H
#define OIT_OITBENCH_BENCH_MATCH_H

#include <stddef.h>

#include "oit/mesh.h"
#include "oit/partfile.h"

/* why gets "" when pf was made from mesh, else what differs (a phrase that
 * follows "was not made from MESH: "). Fails only when a part cannot be
 * read (the reader's status, naming the file) or memory runs out. */
oit_status oit_bench_match(const oit_mesh *mesh, oit_partfile *pf, char *why, size_t cap,
                           oit_error *err);

#endif
