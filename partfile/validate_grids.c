/* The management sections' checks (validate_internal.h): GRID and SUBGRIDS
 * (loaded into the unified grid, cell and list arrays), SLABS, and the links
 * between grids, cells, slabs and parts. Apart from validate.c, which runs
 * them in order, as the checks of the tree the traversal order walks. */
#include "partfile/validate_internal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- GRID and SUBGRIDS -------------------------------------------------------- */

static oit_status check_grid(const oit_partfile *pf, uint32_t g, uint64_t cell_first,
                             oit_error *err)
{
    const oit_partfile_grid *gr = &pf->grids[g];
    const char *sec = g ? "SUBGRIDS" : "GRID";
    uint64_t xy = (uint64_t)gr->dims[0] * gr->dims[1];
    if (!gr->dims[0] || !gr->dims[1] || !gr->dims[2] || xy > UINT64_MAX / gr->dims[2] ||
        xy * gr->dims[2] != gr->cell_count || gr->cell_first != cell_first)
        return pf_bad(pf, err, "section %s: grid %u: %ux%ux%u dims, %llu cells from %llu", sec, g,
                      gr->dims[0], gr->dims[1], gr->dims[2], (unsigned long long)gr->cell_count,
                      (unsigned long long)gr->cell_first);
    if (!pf_finite3(gr->origin) || !pf_finite3(gr->cell_size) || !(gr->cell_size[0] > 0) ||
        !(gr->cell_size[1] > 0) || !(gr->cell_size[2] > 0))
        return pf_bad(pf, err, "section %s: grid %u: origin or cell size not finite or <= 0", sec,
                      g);
    if (g == 0 && (gr->depth || gr->parent_grid != OIT_PARTFILE_NONE ||
                   gr->parent_cell != OIT_PARTFILE_NONE))
        return pf_bad(pf, err, "section GRID: the top grid has depth %u, parent %u", gr->depth,
                      gr->parent_grid);
    if (g > 0 && (gr->parent_grid >= g ||
                  gr->parent_cell >= pf->grids[gr->parent_grid].cell_count ||
                  gr->depth != pf->grids[gr->parent_grid].depth + 1))
        return pf_bad(pf, err, "section SUBGRIDS: record %u: parent grid %u cell %u depth %u: the "
                      "parent must be an earlier grid, one level up", g - 1, gr->parent_grid,
                      gr->parent_cell, gr->depth);
    return OIT_OK;
}

static oit_status check_cell_list(const oit_partfile *pf, const char *sec, uint64_t c,
                                  const uint32_t *list, uint64_t list_first,
                                  const oit_partfile_cell *cell, oit_error *err)
{
    if (cell->reserved || cell->list_first != list_first)
        return pf_bad(pf, err, "section %s: cell %llu: list from %llu, expected %llu", sec,
                      (unsigned long long)c, (unsigned long long)cell->list_first,
                      (unsigned long long)list_first);
    for (uint32_t k = 0; k < cell->list_count; k++) {
        uint32_t part = list[cell->list_first + k];
        if (part >= pf->hdr.part_count || (k && part <= list[cell->list_first + k - 1]))
            return pf_bad(pf, err, "section %s: cell %llu: part %u is missing or out of order "
                          "(%llu parts)", sec, (unsigned long long)c, part,
                          (unsigned long long)pf->hdr.part_count);
    }
    return OIT_OK;
}

typedef struct grid_block {
    pf_grid_block head;
    const uint8_t *grids, *cells, *list;
} grid_block;

static oit_status parse_block(const oit_partfile *pf, uint32_t type, grid_block *b,
                              oit_error *err)
{
    const char *sec = pf_section_name(type);
    uint64_t size = pf_sec_size(pf, type);
    const uint8_t *p = pf_sec_data(pf, type);
    if (size < sizeof b->head)
        return pf_bad(pf, err, "section %s: %llu bytes, shorter than its head", sec,
                      (unsigned long long)size);
    memcpy(&b->head, p, sizeof b->head);
    const pf_grid_block *h = &b->head;
    /* Bounding each count by the size keeps the byte total below 2^64. */
    if (h->reserved || h->grid_count > size / sizeof(oit_partfile_grid) ||
        h->cell_count > size / sizeof(oit_partfile_cell) || h->list_count > size / 4 ||
        size != pf_grid_block_bytes(h->grid_count, h->cell_count, h->list_count) ||
        (type == PF_SEC_GRID && h->grid_count != 1))
        return pf_bad(pf, err, "section %s: %llu bytes cannot hold the %u grids, %llu cells and "
                      "%llu list entries its head claims", sec, (unsigned long long)size,
                      h->grid_count, (unsigned long long)h->cell_count,
                      (unsigned long long)h->list_count);
    b->grids = p + sizeof *h;
    b->cells = b->grids + h->grid_count * sizeof(oit_partfile_grid);
    b->list = b->cells + h->cell_count * sizeof(oit_partfile_cell);
    return OIT_OK;
}

/* Appends a block to the unified grid, cell and list arrays. */
static oit_status append_block(oit_partfile *pf, const grid_block *b, oit_error *err)
{
    const pf_grid_block *h = &b->head;
    uint64_t grids = (uint64_t)pf->grid_count + h->grid_count;
    if (grids > UINT32_MAX)
        return pf_bad(pf, err, "section SUBGRIDS: too many grids");
    void *g = realloc(pf->grids, grids * sizeof *pf->grids);
    if (g)
        pf->grids = g;
    void *c = realloc(pf->cells, (pf->cell_count + h->cell_count + 1) * sizeof *pf->cells);
    if (c)
        pf->cells = c;
    void *l = realloc(pf->lists, (pf->list_count + h->list_count + 1) * sizeof *pf->lists);
    if (l)
        pf->lists = l;
    if (!g || !c || !l)
        return pf_nomem(pf, err);
    memcpy(pf->grids + pf->grid_count, b->grids, h->grid_count * sizeof *pf->grids);
    memcpy(pf->cells + pf->cell_count, b->cells, h->cell_count * sizeof *pf->cells);
    memcpy(pf->lists + pf->list_count, b->list, h->list_count * sizeof *pf->lists);
    return OIT_OK;
}

/* Checks the block just appended, then shifts its offsets to unified ones. */
static oit_status check_block(oit_partfile *pf, uint32_t type, const pf_grid_block *h,
                              oit_error *err)
{
    const char *sec = pf_section_name(type);
    uint32_t g0 = pf->grid_count;
    uint64_t cells = 0, list = 0;
    for (uint32_t g = g0; g < g0 + h->grid_count; g++) {
        oit_status s = check_grid(pf, g, cells, err);
        if (s)
            return s;
        cells += pf->grids[g].cell_count;
        if (cells > h->cell_count)
            break;
    }
    if (cells != h->cell_count)
        return pf_bad(pf, err, "section %s: grids own %llu cells, the head says %llu", sec,
                      (unsigned long long)cells, (unsigned long long)h->cell_count);
    oit_partfile_cell *cell = pf->cells + pf->cell_count;
    const uint32_t *lst = pf->lists + pf->list_count;
    for (uint64_t c = 0; c < h->cell_count; c++) {
        if (cell[c].list_count > h->list_count - list)
            return pf_bad(pf, err, "section %s: cell %llu: list runs past the %llu entries", sec,
                          (unsigned long long)c, (unsigned long long)h->list_count);
        oit_status s = check_cell_list(pf, sec, c, lst, list, &cell[c], err);
        if (s)
            return s;
        list += cell[c].list_count;
    }
    if (list != h->list_count)
        return pf_bad(pf, err, "section %s: cells use %llu of %llu list entries", sec,
                      (unsigned long long)list, (unsigned long long)h->list_count);
    for (uint32_t g = g0; g < g0 + h->grid_count; g++)
        pf->grids[g].cell_first += pf->cell_count;
    for (uint64_t c = 0; c < h->cell_count; c++)
        cell[c].list_first += pf->list_count;
    pf->grid_count += h->grid_count;
    pf->cell_count += h->cell_count;
    pf->list_count += h->list_count;
    return OIT_OK;
}

oit_status pf_load_grids(oit_partfile *pf, oit_error *err)
{
    static const uint32_t types[2] = {PF_SEC_GRID, PF_SEC_SUBGRIDS};
    for (int i = 0; i < 2; i++) {
        grid_block b;
        oit_status s = parse_block(pf, types[i], &b, err);
        if (!s)
            s = append_block(pf, &b, err);
        if (!s)
            s = check_block(pf, types[i], &b.head, err);
        if (s)
            return s;
    }
    return OIT_OK;
}

/* ---- SLABS ------------------------------------------------------------------ */

oit_status pf_load_slabs(oit_partfile *pf, oit_error *err)
{
    uint64_t size = pf_sec_size(pf, PF_SEC_SLABS);
    const uint8_t *p = pf_sec_data(pf, PF_SEC_SLABS);
    pf_slab_block h;
    if (size < sizeof h)
        return pf_bad(pf, err, "section SLABS: %llu bytes, shorter than its head",
                      (unsigned long long)size);
    memcpy(&h, p, sizeof h);
    if (h.reserved || h.slab_count > size / sizeof(oit_partfile_slab) || h.list_count > size / 4 ||
        size != pf_slab_block_bytes(h.slab_count, h.list_count))
        return pf_bad(pf, err, "section SLABS: %llu bytes cannot hold the %u slabs and %llu list "
                      "entries its head claims", (unsigned long long)size, h.slab_count,
                      (unsigned long long)h.list_count);
    pf->slab_count = h.slab_count;
    pf->slab_list_count = h.list_count;
    pf->slabs = pf_copy_out(p + sizeof h, h.slab_count, sizeof *pf->slabs);
    pf->slab_list = pf_copy_out(p + sizeof h + h.slab_count * sizeof *pf->slabs, h.list_count,
                                sizeof *pf->slab_list);
    return pf->slabs && pf->slab_list ? OIT_OK : pf_nomem(pf, err);
}

static bool cell_has_part(const oit_partfile *pf, const oit_partfile_cell *cell, uint32_t part)
{
    const uint32_t *l = pf->lists + cell->list_first;
    uint32_t lo = 0, hi = cell->list_count;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (l[mid] < part)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < cell->list_count && l[lo] == part;
}

static oit_status check_slab(const oit_partfile *pf, uint32_t i, uint64_t list_first,
                             oit_error *err)
{
    const oit_partfile_slab *s = &pf->slabs[i];
    float len2 = s->normal[0] * s->normal[0] + s->normal[1] * s->normal[1] +
                 s->normal[2] * s->normal[2];
    /* A cutting plane keeps its integer normal (partfile.h). */
    if (!pf_finite3(s->normal) || !(len2 > 0) || !isfinite(len2))
        return pf_bad(pf, err, "section SLABS: record %u: normal (%g %g %g) zero or not finite", i,
                      s->normal[0], s->normal[1], s->normal[2]);
    if (!isfinite(s->d0) || !isfinite(s->d1) || s->d0 > s->d1)
        return pf_bad(pf, err, "section SLABS: record %u: planes d0 %g > d1 %g or not finite", i,
                      s->d0, s->d1);
    if (s->grid >= pf->grid_count || s->cell >= pf->grids[s->grid].cell_count)
        return pf_bad(pf, err, "section SLABS: record %u: grid %u cell %u does not exist", i,
                      s->grid, s->cell);
    const oit_partfile_cell *cell = &pf->cells[pf->grids[s->grid].cell_first + s->cell];
    if (cell->slab != i + 1)
        return pf_bad(pf, err, "section SLABS: record %u: its cell names slab %u", i, cell->slab);
    if (s->inside_first != list_first || s->inside_count > pf->slab_list_count - list_first)
        return pf_bad(pf, err, "section SLABS: record %u: list %llu..+%u, expected from %llu "
                      "within %llu", i, (unsigned long long)s->inside_first, s->inside_count,
                      (unsigned long long)list_first, (unsigned long long)pf->slab_list_count);
    if (s->part_below == s->part_above || !cell_has_part(pf, cell, s->part_below) ||
        !cell_has_part(pf, cell, s->part_above))
        return pf_bad(pf, err, "section SLABS: record %u: parts %u and %u are not two parts of its "
                      "cell", i, s->part_below, s->part_above);
    for (uint32_t k = 0; k < s->inside_count; k++) {
        uint32_t p = pf->slab_list[list_first + k];
        if ((k && p <= pf->slab_list[list_first + k - 1]) || p == s->part_below ||
            p == s->part_above || !cell_has_part(pf, cell, p))
            return pf_bad(pf, err, "section SLABS: record %u: inside part %u is out of order, "
                          "repeated or not in its cell", i, p);
    }
    return OIT_OK;
}

oit_status pf_check_slabs(const oit_partfile *pf, oit_error *err)
{
    uint64_t list = 0;
    for (uint32_t i = 0; i < pf->slab_count; i++) {
        oit_status s = check_slab(pf, i, list, err);
        if (s)
            return s;
        list += pf->slabs[i].inside_count;
    }
    if (list != pf->slab_list_count)
        return pf_bad(pf, err, "section SLABS: slabs use %llu of %llu list entries",
                      (unsigned long long)list, (unsigned long long)pf->slab_list_count);
    return OIT_OK;
}

/* ---- links between grids, cells, slabs and parts ------------------------------ */

static void cell_box(const oit_partfile_grid *g, uint64_t cell, double lo[3], double hi[3])
{
    uint64_t idx[3] = {cell % g->dims[0], cell / g->dims[0] % g->dims[1],
                       cell / g->dims[0] / g->dims[1]};
    for (int k = 0; k < 3; k++) {
        lo[k] = g->origin[k] + (double)idx[k] * g->cell_size[k];
        hi[k] = lo[k] + g->cell_size[k];
    }
}

/* A subgrid covers the region its parent cell stands for: the cell's box
 * within its own grid's region (to rounding). It may reach beyond it, so a
 * two-cell subgrid can put its one boundary anywhere inside. region holds 6
 * doubles per grid, filled in grid order (parents come first). */
static bool subgrid_fits(const oit_partfile *pf, uint32_t sg, double *region)
{
    const oit_partfile_grid *sub = &pf->grids[sg];
    const oit_partfile_grid *parent = &pf->grids[sub->parent_grid];
    double lo[3], hi[3], *r = &region[6 * sg], *pr = &region[6 * sub->parent_grid];
    cell_box(parent, sub->parent_cell, lo, hi);
    for (int k = 0; k < 3; k++) {
        r[k] = lo[k] > pr[k] ? lo[k] : pr[k];
        r[3 + k] = hi[k] < pr[3 + k] ? hi[k] : pr[3 + k];
        /* Float origins and sizes: deep cells are only a few ulps wide. */
        double mag = fabs(lo[k]) > fabs(hi[k]) ? fabs(lo[k]) : fabs(hi[k]);
        double tol = 1e-4 * (hi[k] - lo[k]) + 8.0 * FLT_EPSILON * mag;
        double slo = sub->origin[k], shi = slo + (double)sub->dims[k] * sub->cell_size[k];
        if (!(r[k] < r[3 + k]) || slo > r[k] + tol || shi < r[3 + k] - tol)
            return false;
    }
    return true;
}

static oit_status check_cell_links(const oit_partfile *pf, uint32_t g, uint64_t c,
                                   double *region, oit_error *err)
{
    const oit_partfile_cell *cell = &pf->cells[pf->grids[g].cell_first + c];
    uint32_t sg = cell->subgrid;
    if (sg && (sg >= pf->grid_count || pf->grids[sg].parent_grid != g ||
               pf->grids[sg].parent_cell != c || !subgrid_fits(pf, sg, region)))
        return pf_bad(pf, err, "section %s: grid %u cell %llu: subgrid %u does not refine this "
                      "cell", g ? "SUBGRIDS" : "GRID", g, (unsigned long long)c, sg);
    if (cell->slab > pf->slab_count)
        return pf_bad(pf, err, "section %s: grid %u cell %llu: slab %u of %u does not exist",
                      g ? "SUBGRIDS" : "GRID", g, (unsigned long long)c, cell->slab - 1,
                      pf->slab_count);
    return OIT_OK;
}

oit_status pf_check_links(const oit_partfile *pf, oit_error *err)
{
    if (!pf->grid_count)
        return OIT_OK;
    double *region = malloc(6 * sizeof *region * pf->grid_count);
    if (!region)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: grid regions: out of memory", pf->name);
    const oit_partfile_grid *top = &pf->grids[0];
    for (int k = 0; k < 3; k++) {
        region[k] = top->origin[k];
        region[3 + k] = top->origin[k] + (double)top->dims[k] * top->cell_size[k];
    }
    for (uint32_t g = 0; g < pf->grid_count; g++)
        for (uint64_t c = 0; c < pf->grids[g].cell_count; c++) {
            oit_status s = check_cell_links(pf, g, c, region, err);
            if (s) {
                free(region);
                return s;
            }
        }
    free(region);
    for (uint32_t g = 1; g < pf->grid_count; g++) {
        const oit_partfile_grid *gr = &pf->grids[g];
        const oit_partfile_grid *parent = &pf->grids[gr->parent_grid];
        if (pf->cells[parent->cell_first + gr->parent_cell].subgrid != g)
            return pf_bad(pf, err, "section SUBGRIDS: record %u: its parent cell does not name it",
                          g - 1);
    }
    return OIT_OK;
}

/* A part in no cell would never be ordered, so never drawn. */
oit_status pf_check_coverage(const oit_partfile *pf, oit_error *err)
{
    uint32_t n = (uint32_t)pf->hdr.part_count;
    unsigned char *seen = calloc(n ? n : 1, 1);
    if (!seen)
        return pf_nomem(pf, err);
    for (uint64_t i = 0; i < pf->list_count; i++)
        seen[pf->lists[i]] = 1;
    uint32_t missing = n;
    for (uint32_t i = 0; i < n && missing == n; i++)
        if (!seen[i])
            missing = i;
    free(seen);
    if (missing != n)
        return pf_bad(pf, err, "section PARTS: record %u: the part is in no grid cell", missing);
    return OIT_OK;
}
