/* Vertex-cache order for one part (vertex_order.h). */
#include "partfile/vertex_order.h"

#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

void pf_ordered_free(pf_ordered *o)
{
    free(o->positions);
    free(o->rgba);
    free(o->indices);
    free(o->sources);
    memset(o, 0, sizeof *o);
}

/* Input triangles by first vertex (CSR), to find which input triangle an
 * optimised triangle is: the optimiser emits each triangle's three indices
 * unchanged, so (a, b, c) names it, up to exact duplicates, which are the
 * same geometry and may swap source indices with no effect on any image. */
typedef struct by_first {
    uint32_t *start; /* vertex_count + 1 */
    uint64_t *tri;
    unsigned char *used;
} by_first;

static int by_first_build(by_first *b, const uint32_t *idx, uint64_t tris, uint32_t verts)
{
    b->start = calloc((size_t)verts + 1, sizeof *b->start);
    b->tri = malloc((size_t)(tris ? tris : 1) * sizeof *b->tri);
    b->used = calloc((size_t)(tris ? tris : 1), 1);
    if (!b->start || !b->tri || !b->used)
        return -1;
    for (uint64_t t = 0; t < tris; t++)
        b->start[idx[3 * t] + 1]++;
    for (uint32_t v = 0; v < verts; v++)
        b->start[v + 1] += b->start[v];
    uint32_t *fill = malloc(((size_t)verts + 1) * sizeof *fill);
    if (!fill)
        return -1;
    memcpy(fill, b->start, ((size_t)verts + 1) * sizeof *fill);
    for (uint64_t t = 0; t < tris; t++)
        b->tri[fill[idx[3 * t]]++] = t;
    free(fill);
    return 0;
}

static void by_first_free(by_first *b)
{
    free(b->start);
    free(b->tri);
    free(b->used);
}

/* The unused input triangle (relative to the piece) with these indices. */
static uint64_t by_first_take(by_first *b, const uint32_t *idx, const uint32_t *abc)
{
    for (uint32_t k = b->start[abc[0]]; k < b->start[abc[0] + 1]; k++) {
        uint64_t t = b->tri[k];
        if (!b->used[t] && idx[3 * t + 1] == abc[1] && idx[3 * t + 2] == abc[2]) {
            b->used[t] = 1;
            return t;
        }
    }
    return UINT64_MAX; /* the optimiser changed a triangle: refuse, do not guess */
}

/* Reorders one piece's triangles [first, first + count) into out. */
static int order_piece(const oit_partfile_part_desc *p, uint64_t first, uint64_t count,
                       pf_ordered *out)
{
    const uint32_t *in = p->indices + 3 * first;
    uint32_t *dst = out->indices + 3 * first;
    meshopt_optimizeVertexCache(dst, in, (size_t)(3 * count), p->vertex_count);
    by_first b = {0};
    int rc = by_first_build(&b, in, count, p->vertex_count);
    for (uint64_t t = 0; !rc && t < count; t++) {
        uint64_t from = by_first_take(&b, in, dst + 3 * t);
        rc = from == UINT64_MAX ? -1 : 0;
        if (!rc)
            out->sources[first + t] = p->sources[first + from];
    }
    by_first_free(&b);
    return rc;
}

/* Vertices renumbered in first-use order, unused ones last. */
static int order_vertices(const oit_partfile_part_desc *p, pf_ordered *out)
{
    uint32_t n = p->vertex_count;
    uint32_t *remap = malloc((size_t)n * sizeof *remap);
    if (!remap)
        return -1;
    size_t used = meshopt_optimizeVertexFetchRemap(remap, out->indices, (size_t)p->index_count, n);
    for (uint32_t v = 0; v < n; v++)
        if (remap[v] == ~0u)
            remap[v] = (uint32_t)used++;
    for (uint64_t i = 0; i < p->index_count; i++)
        out->indices[i] = remap[out->indices[i]];
    for (uint32_t v = 0; v < n; v++) {
        memcpy(out->positions + (size_t)remap[v] * 3, p->positions + (size_t)v * 3, 12);
        if (out->rgba)
            memcpy(out->rgba + (size_t)remap[v] * 4, p->rgba + (size_t)v * 4, 4);
    }
    free(remap);
    return 0;
}

int pf_cache_order(const oit_partfile_part_desc *p, bool triangles, pf_ordered *out)
{
    memset(out, 0, sizeof *out);
    uint64_t tris = p->index_count / 3;
    out->positions = malloc((size_t)p->vertex_count * 12);
    out->rgba = p->rgba ? malloc((size_t)p->vertex_count * 4) : NULL;
    out->indices = malloc((size_t)p->index_count * 4);
    out->sources = malloc((size_t)(tris ? tris : 1) * 4);
    int rc = !out->positions || (p->rgba && !out->rgba) || !out->indices || !out->sources;
    uint64_t first = 0;
    if (!rc && !triangles) {
        memcpy(out->indices, p->indices, (size_t)p->index_count * 4);
        memcpy(out->sources, p->sources, (size_t)tris * 4);
    }
    for (uint32_t k = 0; !rc && triangles && k < p->piece_count; k++) {
        rc = order_piece(p, first, p->pieces[k].triangle_count, out);
        first += p->pieces[k].triangle_count;
    }
    if (!rc)
        rc = order_vertices(p, out);
    if (rc)
        pf_ordered_free(out);
    return rc ? -1 : 0;
}
