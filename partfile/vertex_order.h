/* Vertex-cache order for one part (oit_partfile_writer_desc.order): with
 * `triangles`, each piece's triangles reordered by meshopt_optimizeVertexCache (within
 * the piece, so piece ranges and bounds stay as they are), every triangle's
 * source index moved with it and its vertices kept in their order (the tie
 * rule's plane starts at vertex 0, docs/ties.md); then the vertices
 * renumbered in first-use order (meshopt_optimizeVertexFetchRemap), unused
 * ones after the used, so no vertex is dropped and the bounds do not move.
 * Positions and colours are copied bit for bit.
 */
#ifndef OIT_PARTFILE_VERTEX_ORDER_H
#define OIT_PARTFILE_VERTEX_ORDER_H

#include <stdbool.h>
#include <stdint.h>

#include "partfile/write.h"

/* The reordered arrays, owned (pf_ordered_free). */
typedef struct pf_ordered {
    float *positions;
    uint8_t *rgba; /* NULL when the part has none */
    uint32_t *indices;
    uint32_t *sources;
} pf_ordered;

/* Returns 0, or -1 when out of memory or when the optimiser returned a
 * triangle it was not given (out then holds nothing). */
int pf_cache_order(const oit_partfile_part_desc *p, bool triangles, pf_ordered *out);
void pf_ordered_free(pf_ordered *o);

#endif
