/* Shares of a part file's management tree (share.h).
 *
 * Triangles per cell are summed once, children before parents (a subgrid
 * has a larger index than its parent grid, which the reader checks), so a
 * node's weight is a sum over its cell range. The descent and the walk of a
 * share's cells keep explicit stacks, as order.c does, so a deep subgrid
 * chain cannot overflow the C stack. */
#include "partfile/share.h"

#include <stdlib.h>
#include <string.h>

#include "partfile/order.h"

struct oit_shares {
    uint32_t count;
    uint32_t part_count;
    uint32_t *owner;      /* per part: its share or OIT_SHARE_NONE */
    uint32_t *parts;      /* per share */
    uint64_t *triangles;  /* per share */
    uint32_t *seen;       /* per share: stamp of the last oit_shares_order */
    uint32_t stamp;
};

typedef struct share_node {
    uint32_t grid;
    uint32_t lo[3], hi[3];
    uint32_t r0, r1; /* shares [r0, r1) */
} share_node;

typedef struct build_ctx {
    const oit_partfile *pf;
    oit_shares *s;
    uint32_t grids;
    uint64_t **cell_w; /* per grid, per cell: triangles under it */
    uint32_t *walk;    /* grids pending in a share's walk */
    oit_error *err;
} build_ctx;

static uint64_t part_triangles(const oit_partfile *pf, uint32_t p)
{
    return oit_partfile_parts(pf)[p].index_count / 3u;
}

static uint64_t cell_index(const oit_partfile_grid *g, uint32_t x, uint32_t y, uint32_t z)
{
    return x + (uint64_t)g->dims[0] * (y + (uint64_t)g->dims[1] * z);
}

/* What order.c draws for a cell: its subgrid in its place, else its list. */
static uint32_t cell_subgrid(const build_ctx *b, uint32_t grid, uint64_t cell)
{
    uint32_t sub = oit_partfile_cells(b->pf, grid)[cell].subgrid;
    return sub > grid && sub < b->grids ? sub : 0;
}

static oit_status weigh_cells(build_ctx *b)
{
    for (uint32_t g = b->grids; g-- > 0;) {
        const oit_partfile_grid *gr = oit_partfile_grid_at(b->pf, g);
        for (uint64_t c = 0; c < gr->cell_count; c++) {
            uint32_t sub = cell_subgrid(b, g, c);
            uint64_t w = 0;
            if (sub) {
                const oit_partfile_grid *sg = oit_partfile_grid_at(b->pf, sub);
                for (uint64_t k = 0; k < sg->cell_count; k++)
                    w += b->cell_w[sub][k];
            } else {
                uint32_t n = 0;
                const uint32_t *list = oit_partfile_cell_parts(b->pf, g, c, &n);
                for (uint32_t i = 0; i < n; i++)
                    w += part_triangles(b->pf, list[i]);
            }
            b->cell_w[g][c] = w;
        }
    }
    return OIT_OK;
}

static uint64_t range_weight(const build_ctx *b, uint32_t grid, const uint32_t lo[3],
                             const uint32_t hi[3])
{
    const oit_partfile_grid *g = oit_partfile_grid_at(b->pf, grid);
    uint64_t w = 0;
    for (uint32_t z = lo[2]; z < hi[2]; z++)
        for (uint32_t y = lo[1]; y < hi[1]; y++)
            for (uint32_t x = lo[0]; x < hi[0]; x++)
                w += b->cell_w[grid][cell_index(g, x, y, z)];
    return w;
}

static oit_status take_list(build_ctx *b, uint32_t grid, uint64_t cell, uint32_t share)
{
    uint32_t n = 0;
    const uint32_t *list = oit_partfile_cell_parts(b->pf, grid, cell, &n);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t p = list[i], *o = &b->s->owner[p];
        if (*o == share)
            continue;
        if (*o != OIT_SHARE_NONE)
            return oit_error_set(b->err, OIT_ERR_FORMAT, "%s: part %u is listed by cells of "
                                 "two shares (%u and %u): the file breaks the contract of one "
                                 "leaf cell a part (partfile/order.h), so no share order holds",
                                 oit_partfile_name(b->pf), p, *o, share);
        *o = share;
        b->s->parts[share]++;
        b->s->triangles[share] += part_triangles(b->pf, p);
    }
    return OIT_OK;
}

/* Every part under a cell range goes to share; subgrids whole. */
static oit_status take_range(build_ctx *b, const share_node *nd, uint32_t share)
{
    const oit_partfile_grid *g = oit_partfile_grid_at(b->pf, nd->grid);
    uint32_t top = 0;
    oit_status st = OIT_OK;
    for (uint32_t z = nd->lo[2]; z < nd->hi[2] && st == OIT_OK; z++)
        for (uint32_t y = nd->lo[1]; y < nd->hi[1] && st == OIT_OK; y++)
            for (uint32_t x = nd->lo[0]; x < nd->hi[0] && st == OIT_OK; x++) {
                uint64_t c = cell_index(g, x, y, z);
                uint32_t sub = cell_subgrid(b, nd->grid, c);
                if (sub)
                    b->walk[top++] = sub; /* each grid has one parent cell */
                else
                    st = take_list(b, nd->grid, c, share);
            }
    while (top > 0 && st == OIT_OK) {
        uint32_t grid = b->walk[--top];
        const oit_partfile_grid *sg = oit_partfile_grid_at(b->pf, grid);
        for (uint64_t c = 0; c < sg->cell_count && st == OIT_OK; c++) {
            uint32_t sub = cell_subgrid(b, grid, c);
            if (sub)
                b->walk[top++] = sub;
            else
                st = take_list(b, grid, c, share);
        }
    }
    return st;
}

/* Shares for the two halves: the split that makes the larger of
 * weight / shares least; a half without triangles gets none. */
static uint32_t shares_below(uint64_t wa, uint64_t wb, uint32_t n)
{
    if (wa == 0)
        return 0;
    if (wb == 0)
        return n;
    uint32_t best = 1;
    double best_load = -1.0;
    for (uint32_t na = 1; na < n; na++) {
        double la = (double)wa / na, lb = (double)wb / (n - na);
        double load = la > lb ? la : lb;
        if (best_load < 0.0 || load < best_load) {
            best_load = load;
            best = na;
        }
    }
    return best;
}

static size_t stack_need(const oit_partfile *pf, uint32_t grids)
{
    size_t need = 2;
    for (uint32_t g = 0; g < grids; g++) {
        const oit_partfile_grid *gr = oit_partfile_grid_at(pf, g);
        for (int k = 0; k < 3; k++)
            for (uint32_t d = gr->dims[k]; d > 1; d = (d + 1) / 2)
                need++;
        need += 2;
    }
    return need;
}

static oit_status descend(build_ctx *b)
{
    size_t cap = stack_need(b->pf, b->grids), top = 0;
    share_node *stack = calloc(cap, sizeof *stack);
    if (!stack)
        return oit_error_set(b->err, OIT_ERR_NOMEM, "%s: cannot allocate the share descent",
                             oit_partfile_name(b->pf));
    const oit_partfile_grid *g0 = oit_partfile_grid_at(b->pf, 0);
    stack[top++] = (share_node){0, {0, 0, 0}, {g0->dims[0], g0->dims[1], g0->dims[2]},
                                0, b->s->count};
    oit_status st = OIT_OK;
    while (top > 0 && st == OIT_OK) {
        share_node nd = stack[--top];
        const oit_partfile_grid *g = oit_partfile_grid_at(b->pf, nd.grid);
        uint64_t cells = (uint64_t)(nd.hi[0] - nd.lo[0]) * (nd.hi[1] - nd.lo[1]) *
                         (nd.hi[2] - nd.lo[2]);
        if (cells == 0)
            continue;
        uint32_t sub = cells == 1 ? cell_subgrid(b, nd.grid, cell_index(g, nd.lo[0], nd.lo[1],
                                                                        nd.lo[2]))
                                  : 0;
        if (nd.r1 - nd.r0 == 1 || (cells == 1 && !sub)) {
            st = take_range(b, &nd, nd.r0);
            continue;
        }
        if (top + 2 > cap) {
            st = oit_error_set(b->err, OIT_ERR_FORMAT, "%s: shares: grid %u nests deeper "
                               "than its subgrid links allow", oit_partfile_name(b->pf), nd.grid);
            break;
        }
        if (sub) {
            const oit_partfile_grid *sg = oit_partfile_grid_at(b->pf, sub);
            stack[top++] = (share_node){sub, {0, 0, 0},
                                        {sg->dims[0], sg->dims[1], sg->dims[2]}, nd.r0, nd.r1};
            continue;
        }
        int axis;
        uint32_t mid;
        oit_order_split_range(g, nd.lo, nd.hi, &axis, &mid);
        share_node a = nd, c = nd;
        a.hi[axis] = mid;
        c.lo[axis] = mid;
        uint32_t na = shares_below(range_weight(b, a.grid, a.lo, a.hi),
                                   range_weight(b, c.grid, c.lo, c.hi), nd.r1 - nd.r0);
        /* A half given no share has no triangles; its parts (if any are
         * empty) join the first share of the other half, where they draw
         * nothing. */
        a.r1 = na == 0 ? nd.r0 + 1 : nd.r0 + na;
        c.r0 = na == nd.r1 - nd.r0 ? nd.r1 - 1 : nd.r0 + na;
        stack[top++] = c;
        stack[top++] = a;
    }
    free(stack);
    return st;
}

oit_status oit_shares_check(const oit_partfile *pf, uint32_t count, uint32_t index,
                            oit_error *err)
{
    if (count > OIT_SHARES_MAX || (count > 1 && index >= count) || (count <= 1 && index != 0))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: share %u of %u: expected a share "
                             "below a count of 1..%u (0: no shares)", oit_partfile_name(pf),
                             index, count, OIT_SHARES_MAX);
    return OIT_OK;
}

oit_status oit_shares_create(const oit_partfile *pf, uint32_t count, oit_shares **out,
                             oit_error *err)
{
    *out = NULL;
    if (count < 1 || count > OIT_SHARES_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %u shares: expected 1..%u",
                             oit_partfile_name(pf), count, OIT_SHARES_MAX);
    oit_shares *s = calloc(1, sizeof *s);
    build_ctx b = {pf, s, oit_partfile_grid_count(pf), NULL, NULL, err};
    uint32_t parts = oit_partfile_part_count(pf);
    if (s) {
        s->count = count;
        s->part_count = parts;
        s->owner = malloc((parts ? parts : 1) * sizeof *s->owner);
        s->parts = calloc(count, sizeof *s->parts);
        s->triangles = calloc(count, sizeof *s->triangles);
        s->seen = calloc(count, sizeof *s->seen);
        b.cell_w = calloc(b.grids ? b.grids : 1, sizeof *b.cell_w);
        b.walk = calloc(b.grids ? b.grids : 1, sizeof *b.walk);
    }
    int ok = s && s->owner && s->parts && s->triangles && s->seen && b.cell_w && b.walk;
    for (uint32_t g = 0; ok && g < b.grids; g++) {
        b.cell_w[g] = calloc(oit_partfile_grid_at(pf, g)->cell_count + 1, sizeof **b.cell_w);
        ok = b.cell_w[g] != NULL;
    }
    oit_status st = ok ? OIT_OK
                       : oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %u shares of "
                                       "%u parts", oit_partfile_name(pf), count, parts);
    if (st == OIT_OK) {
        for (uint32_t p = 0; p < parts; p++)
            s->owner[p] = OIT_SHARE_NONE;
        st = weigh_cells(&b);
    }
    if (st == OIT_OK && b.grids)
        st = descend(&b);
    for (uint32_t g = 0; b.cell_w && g < b.grids; g++)
        free(b.cell_w[g]);
    free(b.cell_w);
    free(b.walk);
    if (st != OIT_OK) {
        oit_shares_destroy(s);
        return st;
    }
    *out = s;
    return OIT_OK;
}

void oit_shares_destroy(oit_shares *s)
{
    if (!s)
        return;
    free(s->owner);
    free(s->parts);
    free(s->triangles);
    free(s->seen);
    free(s);
}

uint32_t oit_shares_count(const oit_shares *s)
{
    return s->count;
}

uint32_t oit_shares_of_part(const oit_shares *s, uint32_t part)
{
    return part < s->part_count ? s->owner[part] : OIT_SHARE_NONE;
}

uint32_t oit_shares_parts(const oit_shares *s, uint32_t share)
{
    return share < s->count ? s->parts[share] : 0;
}

uint64_t oit_shares_triangles(const oit_shares *s, uint32_t share)
{
    return share < s->count ? s->triangles[share] : 0;
}

void oit_shares_order(oit_shares *s, const uint32_t *parts, uint32_t n, uint32_t *out)
{
    if (++s->stamp == 0) {
        memset(s->seen, 0, s->count * sizeof *s->seen);
        s->stamp = 1;
    }
    uint32_t k = 0;
    for (uint32_t i = 0; i < n && k < s->count; i++) {
        uint32_t sh = oit_shares_of_part(s, parts[i]);
        if (sh == OIT_SHARE_NONE || s->seen[sh] == s->stamp)
            continue;
        s->seen[sh] = s->stamp;
        out[k++] = sh;
    }
    for (uint32_t sh = 0; sh < s->count; sh++)
        if (s->seen[sh] != s->stamp)
            out[k++] = sh;
}
