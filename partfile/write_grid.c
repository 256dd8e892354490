/* The management tree's records (write.h): the top grid, subgrids and
 * slabs, each checked against what was added before it. Apart from
 * write.c as the calls that build the tree, not the file. */
#include "oit/partfile.h"

#include "partfile/write.h"
#include "partfile/write_internal.h"

#include <stdint.h>
#include <string.h>

static oit_status add_grid(oit_partfile_writer *w, const oit_partfile_grid_desc *g, bool top,
                           oit_error *err)
{
    uint64_t cells = (uint64_t)g->dims[0] * g->dims[1];
    if (!g->dims[0] || !g->dims[1] || !g->dims[2] || cells > UINT32_MAX / g->dims[2] ||
        !g->cell_counts)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: grid %zu: bad dims %ux%ux%u", w->path,
                             w->grids.count, g->dims[0], g->dims[1], g->dims[2]);
    cells *= g->dims[2];
    vec *cv = top ? &w->top_cells : &w->sub_cells;
    vec *lv = top ? &w->top_list : &w->sub_list;
    oit_partfile_grid rec;
    memset(&rec, 0, sizeof rec);
    memcpy(rec.dims, g->dims, sizeof rec.dims);
    memcpy(rec.origin, g->origin, sizeof rec.origin);
    memcpy(rec.cell_size, g->cell_size, sizeof rec.cell_size);
    rec.parent_grid = top ? OIT_PARTFILE_NONE : g->parent_grid;
    rec.parent_cell = top ? OIT_PARTFILE_NONE : g->parent_cell;
    rec.cell_first = cv->count;
    rec.cell_count = cells;
    if (!top) {
        const oit_partfile_grid *parent = (const oit_partfile_grid *)w->grids.data + g->parent_grid;
        rec.depth = parent->depth + 1;
    }
    uint64_t list_total = 0;
    for (uint64_t c = 0; c < cells; c++)
        list_total += g->cell_counts[c];
    if (list_total && !g->cell_parts)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: grid %zu: cell lists missing", w->path,
                             w->grids.count);
    size_t cell0 = cv->count;
    oit_status s = pf_vec_push(cv, NULL, cells, sizeof(oit_partfile_cell), err);
    uint64_t list_first = lv->count;
    for (uint64_t c = 0; !s && c < cells; c++) {
        oit_partfile_cell *cell = (oit_partfile_cell *)cv->data + cell0 + c;
        cell->list_first = list_first;
        cell->list_count = g->cell_counts[c];
        list_first += cell->list_count;
    }
    if (!s)
        s = pf_vec_push(lv, g->cell_parts, list_total, sizeof(uint32_t), err);
    if (!s)
        s = pf_vec_push(&w->grids, &rec, 1, sizeof rec, err);
    return s;
}

oit_status oit_partfile_writer_set_grid(oit_partfile_writer *w, const oit_partfile_grid_desc *g,
                                        oit_error *err)
{
    if (w->have_grid)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: the top grid is already set", w->path);
    oit_status s = add_grid(w, g, true, err);
    w->have_grid = !s;
    return s;
}

/* The cell of grid `grid`, or NULL when either index is out of range. */
static oit_partfile_cell *writer_cell(oit_partfile_writer *w, uint32_t grid, uint32_t cell)
{
    if (grid >= w->grids.count)
        return NULL;
    const oit_partfile_grid *g = (const oit_partfile_grid *)w->grids.data + grid;
    if (cell >= g->cell_count)
        return NULL;
    vec *cv = grid == 0 ? &w->top_cells : &w->sub_cells;
    return (oit_partfile_cell *)cv->data + g->cell_first + cell;
}

oit_status oit_partfile_writer_add_subgrid(oit_partfile_writer *w, const oit_partfile_grid_desc *g,
                                           uint32_t *grid, oit_error *err)
{
    oit_partfile_cell *parent = w->have_grid ? writer_cell(w, g->parent_grid, g->parent_cell) : NULL;
    if (!parent || parent->subgrid)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: subgrid %zu: parent grid %u cell %u is missing or already "
                             "refined",
                             w->path, w->grids.count, g->parent_grid, g->parent_cell);
    uint32_t n = (uint32_t)w->grids.count;
    oit_status s = add_grid(w, g, false, err);
    if (s)
        return s;
    writer_cell(w, g->parent_grid, g->parent_cell)->subgrid = n; /* add_grid may move cells */
    if (grid)
        *grid = n;
    return OIT_OK;
}

oit_status oit_partfile_writer_add_slab(oit_partfile_writer *w, const oit_partfile_slab_desc *sd,
                                        uint32_t *slab, oit_error *err)
{
    oit_partfile_cell *cell = writer_cell(w, sd->grid, sd->cell);
    uint32_t n = (uint32_t)w->slabs.count;
    if (!cell || cell->slab || (sd->inside_count && !sd->inside))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: slab %u: grid %u cell %u is missing or already has a slab",
                             w->path, n, sd->grid, sd->cell);
    oit_partfile_slab rec;
    memset(&rec, 0, sizeof rec);
    memcpy(rec.normal, sd->normal, sizeof rec.normal);
    rec.d0 = sd->d0;
    rec.d1 = sd->d1;
    rec.grid = sd->grid;
    rec.cell = sd->cell;
    rec.part_below = sd->part_below;
    rec.part_above = sd->part_above;
    rec.inside_count = sd->inside_count;
    rec.inside_first = w->slab_list.count;
    oit_status s = pf_vec_push(&w->slab_list, sd->inside, sd->inside_count, sizeof(uint32_t), err);
    if (!s)
        s = pf_vec_push(&w->slabs, &rec, 1, sizeof rec, err);
    if (s)
        return s;
    cell->slab = n + 1;
    if (slab)
        *slab = n;
    return OIT_OK;
}
