/* A cell's results given to the part file writer (convert_internal.h):
 * its parts with vertices deduplicated, and the grids: the top grid, each
 * kd split as a subgrid, each slab leaf as a slab. Apart as the mapping
 * from kd results to part file records. */
#include "prepare/convert/convert_internal.h"

#include <stdlib.h>
#include <string.h>

#include "prepare/partition/kd_split.h"

static uint64_t hash_vertex(const oit_vertex *v)
{
    uint64_t h = 1469598103934665603ull, w[2];
    memcpy(w, v, sizeof w);
    for (int i = 0; i < 2; i++)
        h = (h ^ w[i]) * 1099511628211ull, h ^= h >> 31;
    return h;
}

static int reserve(part_buf *b, size_t tris, size_t pieces)
{
    if (tris > b->tri_cap) {
        size_t cap = tris * 2;
        float *p = realloc(b->pos, 9 * cap * sizeof *p);
        if (p) b->pos = p;
        uint8_t *c = realloc(b->rgba, 12 * cap);
        if (c) b->rgba = c;
        uint32_t *i = realloc(b->idx, 3 * cap * sizeof *i);
        if (i) b->idx = i;
        uint32_t *s = realloc(b->slot, 12 * cap * sizeof *s); /* >= the pow2 >= 6n */
        if (s) b->slot = s;
        if (!p || !c || !i || !s)
            return -1;
        b->tri_cap = cap;
    }
    if (pieces > b->piece_cap) {
        oit_partfile_piece_desc *p = realloc(b->pieces, pieces * sizeof *p);
        if (!p)
            return -1;
        b->pieces = p;
        b->piece_cap = pieces;
    }
    return 0;
}

/* Vertices deduplicated by exact position and colour. */
static uint32_t dedupe_vertices(part_buf *b, const oit_triangle *t, size_t n)
{
    size_t cap = 1;
    while (cap < 6 * n)
        cap *= 2;
    memset(b->slot, 0, cap * sizeof *b->slot);
    uint32_t nv = 0;
    for (size_t i = 0; i < 3 * n; i++) {
        const oit_vertex *v = &t[i / 3].v[i % 3];
        size_t h = hash_vertex(v) & (cap - 1);
        while (b->slot[h] && (memcmp(&b->pos[3 * (b->slot[h] - 1)], v->pos, 12) ||
                              memcmp(&b->rgba[4 * (b->slot[h] - 1)], v->rgba, 4)))
            h = (h + 1) & (cap - 1);
        if (!b->slot[h]) {
            memcpy(&b->pos[3 * nv], v->pos, 12);
            memcpy(&b->rgba[4 * nv], v->rgba, 4);
            b->slot[h] = ++nv;
        }
        b->idx[i] = b->slot[h] - 1;
    }
    return nv;
}

oit_status oit_convert_write_parts(oit_partfile_writer *w, part_buf *b, const oit_kd_result *kd,
                                   uint32_t attributes, oit_error *err)
{
    for (size_t p = 0; p < kd->part_count; p++) {
        const oit_kd_part *part = &kd->parts[p];
        if (reserve(b, part->tri_count, part->piece_count))
            return oit_error_set(err, OIT_ERR_NOMEM, "part of %zu triangles: out of memory",
                                 part->tri_count);
        uint32_t nv = dedupe_vertices(b, kd->tris + part->tri_first, part->tri_count);
        for (uint32_t i = 0; i < part->piece_count; i++)
            b->pieces[i] = (oit_partfile_piece_desc){kd->pieces[part->piece_first + i].triangle_count,
                                                     kd->pieces[part->piece_first + i].plane_count};
        oit_partfile_part_desc d = {
            .positions = b->pos,
            .rgba = attributes ? b->rgba : NULL,
            .vertex_count = nv,
            .indices = b->idx,
            .index_count = 3 * (uint64_t)part->tri_count,
            .sources = kd->src + part->tri_first,
            .pieces = b->pieces,
            .piece_count = part->piece_count,
            .layer_bound = part->layer_bound,
            .attributes = attributes,
        };
        uint32_t index;
        oit_status s = oit_partfile_writer_add_part(w, &d, &index, err);
        if (s)
            return s;
    }
    return OIT_OK;
}

/* ---- writing grids ----------------------------------------------------------- */

/* A leaf's part list, ascending: none, its part, or a slab's two parts. */
static uint32_t leaf_list(const cell_out *c, uint32_t node, uint32_t *entry)
{
    const oit_kd_node *n = &c->kd.nodes[node];
    if (n->axis >= 0 || n->part < 0)
        return 0;
    if (n->slab < 0) {
        *entry = c->part_base + (uint32_t)n->part;
        return 1;
    }
    const oit_kd_slab_leaf *sl = &c->kd.slabs[n->slab];
    uint32_t a = c->part_base + sl->part_below, b = c->part_base + sl->part_above;
    entry[0] = a < b ? a : b;
    entry[1] = a < b ? b : a;
    return 2;
}

/* The cell's slab leaves, once their grids exist (loc: grid and cell per
 * node, as write_subgrids fills it). */
static oit_status write_slabs(oit_partfile_writer *w, const cell_out *c, const uint32_t *loc,
                              oit_error *err)
{
    for (size_t i = 0; i < c->kd.node_count; i++) {
        const oit_kd_node *n = &c->kd.nodes[i];
        if (n->axis >= 0 || n->slab < 0)
            continue;
        const oit_kd_slab_leaf *sl = &c->kd.slabs[n->slab];
        oit_partfile_slab_desc d = {
            .normal = {sl->planes.normal[0], sl->planes.normal[1], sl->planes.normal[2]},
            .d0 = sl->planes.d0,
            .d1 = sl->planes.d1,
            .grid = loc[2 * i],
            .cell = loc[2 * i + 1],
            .part_below = c->part_base + sl->part_below,
            .part_above = c->part_base + sl->part_above,
        };
        oit_status s = oit_partfile_writer_add_slab(w, &d, NULL, err);
        if (s)
            return s;
    }
    return OIT_OK;
}

static oit_status write_subgrids(oit_partfile_writer *w, const cell_out *c, uint64_t cell,
                                 uint32_t *loc, oit_error *err)
{
    const oit_kd_result *kd = &c->kd;
    loc[0] = 0;
    loc[1] = (uint32_t)cell;
    for (size_t i = 0; i < kd->node_count; i++) {
        const oit_kd_node *n = &kd->nodes[i];
        if (n->axis < 0)
            continue;
        oit_partfile_grid_desc g = {.dims = {1, 1, 1}, .parent_grid = loc[2 * i],
                                    .parent_cell = loc[2 * i + 1]};
        g.dims[n->axis] = 2;
        if (!oit_kd_split_cells(n->lo, n->hi, n->axis, n->split, g.origin, g.cell_size))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "cell %llu: split at %g is not a subgrid "
                                 "boundary in float", (unsigned long long)cell, n->split);
        uint32_t counts[2], parts[4], np = 0;
        for (int h = 0; h < 2; h++) {
            counts[h] = leaf_list(c, n->child + h, &parts[np]);
            np += counts[h];
        }
        g.cell_counts = counts;
        g.cell_parts = parts;
        uint32_t gi;
        oit_status s = oit_partfile_writer_add_subgrid(w, &g, &gi, err);
        if (s)
            return s;
        for (int h = 0; h < 2; h++) {
            loc[2 * (n->child + h)] = gi;
            loc[2 * (n->child + h) + 1] = (uint32_t)h;
        }
    }
    return write_slabs(w, c, loc, err);
}

oit_status oit_convert_write_grids(oit_partfile_writer *w, const cell_run *r, oit_error *err)
{
    uint32_t *counts = calloc(r->ncells, sizeof *counts);
    uint32_t *parts = calloc(2 * r->ncells, sizeof *parts); /* two in a slab cell */
    size_t maxnodes = 1;
    for (uint64_t c = 0; c < r->ncells; c++)
        maxnodes = r->res[c].kd.node_count > maxnodes ? r->res[c].kd.node_count : maxnodes;
    uint32_t *loc = malloc(2 * maxnodes * sizeof *loc);
    if (!counts || !parts || !loc) {
        free(counts);
        free(parts);
        free(loc);
        return oit_error_set(err, OIT_ERR_NOMEM, "grid of %llu cells: out of memory",
                             (unsigned long long)r->ncells);
    }
    uint32_t np = 0;
    for (uint64_t c = 0; c < r->ncells; c++) {
        counts[c] = r->res[c].kd.node_count ? leaf_list(&r->res[c], 0, &parts[np]) : 0;
        np += counts[c];
    }
    oit_partfile_grid_desc g = {
        .dims = {r->grid.dims[0], r->grid.dims[1], r->grid.dims[2]},
        .origin = {r->grid.origin[0], r->grid.origin[1], r->grid.origin[2]},
        .cell_size = {r->grid.cell, r->grid.cell, r->grid.cell},
        .cell_counts = counts,
        .cell_parts = parts,
    };
    oit_status s = oit_partfile_writer_set_grid(w, &g, err);
    for (uint64_t c = 0; c < r->ncells && !s; c++)
        if (r->res[c].kd.node_count)
            s = write_subgrids(w, &r->res[c], c, loc, err);
    free(counts);
    free(parts);
    free(loc);
    return s;
}
