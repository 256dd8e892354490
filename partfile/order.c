/* Per-view visibility order of the parts (order.h).
 *
 * Each grid is an implicit kd-tree over its cell index box: a node is an
 * index range, split at the middle of its longest side (in world units); the
 * half on the eye's side of the split plane is visited first. A plane
 * separates everything in the two halves, so every ray from the eye meets
 * the near half's content before the far half's. The traversal keeps an
 * explicit stack (sized in create from the grids' shapes), so a file with a
 * deep subgrid chain cannot overflow the C stack and a frame allocates
 * nothing. Emitted parts are marked with the frame's stamp, so no per-frame
 * clearing is needed either. */
#include "partfile/order.h"
#include "base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct order_node {
    uint32_t grid;
    uint32_t lo[3], hi[3]; /* cell index range, hi exclusive */
    int inside;            /* wholly inside the planes: no more tests below */
} order_node;

struct oit_order {
    const oit_partfile *pf;
    uint32_t grid_count;
    const oit_partfile_grid **grids;
    const oit_partfile_cell **cells;
    uint32_t *stamp; /* per part: frame number when last emitted */
    uint32_t frame;
    order_node *stack;
    size_t stack_cap;
    uint32_t *scratch; /* slab inside parts, sorted per view */
    uint32_t scratch_cap;
    double *reach; /* per grid: how far parts under it may lie beyond a range's box */
};

static uint32_t ceil_log2(uint32_t v)
{
    uint32_t n = 0;
    while (n < 32 && (1ull << n) < v)
        n++;
    return n;
}

/* Nodes pending at once: the far halves along one root-to-leaf path of each
 * grid on a chain of nested subgrids, plus the node being split. */
static size_t stack_need(const oit_partfile *pf, uint32_t grids)
{
    size_t need = 1;
    for (uint32_t g = 0; g < grids; g++) {
        const oit_partfile_grid *gr = oit_partfile_grid_at(pf, g);
        need += 2 + ceil_log2(gr->dims[0]) + ceil_log2(gr->dims[1]) + ceil_log2(gr->dims[2]);
    }
    return need;
}

static uint32_t max_inside(const oit_partfile *pf)
{
    uint32_t m = 0, n = oit_partfile_slab_count(pf);
    for (uint32_t s = 0; s < n; s++) {
        uint32_t c = 0;
        oit_partfile_slab_inside(pf, s, &c);
        m = c > m ? c : m;
    }
    return m;
}

/* A subgrid may be larger than its parent cell (docs/part-file.md), and the
 * parts in its cells need only lie in those cells. So a range of cells holds
 * its parts within its box grown by reach[g]: the most any subgrid of g, with
 * its own reach, sticks out of its parent cell. Children have larger indices
 * than their parents (the reader checks it), so one backward pass does. */
static void compute_reach(oit_order *o)
{
    for (uint32_t g = o->grid_count; g-- > 0;)
        o->reach[g] = 0.0;
    for (uint32_t g = o->grid_count; g-- > 1;) {
        const oit_partfile_grid *s = o->grids[g];
        if (s->parent_grid >= g)
            continue;
        const oit_partfile_grid *p = o->grids[s->parent_grid];
        uint32_t c = s->parent_cell, idx[3] = {c % p->dims[0], c / p->dims[0] % p->dims[1],
                                               c / p->dims[0] / p->dims[1]};
        double out = 0.0;
        for (int k = 0; k < 3; k++) {
            double clo = (double)p->origin[k] + (double)idx[k] * p->cell_size[k];
            double chi = clo + p->cell_size[k];
            double slo = s->origin[k], shi = slo + (double)s->dims[k] * s->cell_size[k];
            out = fmax(out, fmax(clo - slo, shi - chi));
        }
        out += o->reach[g];
        if (out > o->reach[s->parent_grid])
            o->reach[s->parent_grid] = out;
    }
}

oit_status oit_order_create(const oit_partfile *pf, oit_order **out, oit_error *err)
{
    *out = NULL;
    oit_order *o = calloc(1, sizeof *o);
    if (!o)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the part order",
                             oit_partfile_name(pf));
    o->pf = pf;
    o->grid_count = oit_partfile_grid_count(pf);
    o->stack_cap = stack_need(pf, o->grid_count);
    o->scratch_cap = max_inside(pf);
    uint32_t parts = oit_partfile_part_count(pf);
    o->grids = calloc(o->grid_count ? o->grid_count : 1, sizeof *o->grids);
    o->cells = calloc(o->grid_count ? o->grid_count : 1, sizeof *o->cells);
    o->stamp = calloc(parts ? parts : 1, sizeof *o->stamp);
    o->stack = calloc(o->stack_cap, sizeof *o->stack);
    o->scratch = calloc(o->scratch_cap ? o->scratch_cap : 1, sizeof *o->scratch);
    o->reach = calloc(o->grid_count ? o->grid_count : 1, sizeof *o->reach);
    if (!o->grids || !o->cells || !o->stamp || !o->stack || !o->scratch || !o->reach) {
        uint32_t grids = o->grid_count; /* o is gone when the message is written */
        oit_order_destroy(o);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the part order "
                             "(%u grids, %u parts)", oit_partfile_name(pf), grids, parts);
    }
    for (uint32_t g = 0; g < o->grid_count; g++) {
        o->grids[g] = oit_partfile_grid_at(pf, g);
        o->cells[g] = oit_partfile_cells(pf, g);
    }
    compute_reach(o);
    *out = o;
    return OIT_OK;
}

void oit_order_destroy(oit_order *o)
{
    if (!o)
        return;
    free(o->grids);
    free(o->cells);
    free(o->stamp);
    free(o->stack);
    free(o->scratch);
    free(o->reach);
    free(o);
}

typedef struct emit_ctx {
    oit_order *o;
    const float *eye;
    const float *dir; /* parallel rays along dir (orthographic); NULL: from eye */
    uint32_t *parts;
    uint32_t count, cap;
} emit_ctx;

static void emit(emit_ctx *e, uint32_t part)
{
    if (part >= e->cap || e->o->stamp[part] == e->o->frame)
        return;
    e->o->stamp[part] = e->o->frame;
    e->parts[e->count++] = part;
}

/* Interval of n.x over the part's box. */
static void box_extent(const oit_partfile_part *p, const float n[3], float *lo, float *hi)
{
    *lo = *hi = 0.0f;
    for (int k = 0; k < 3; k++) {
        float a = n[k] * p->bounds_min[k], b = n[k] * p->bounds_max[k];
        *lo += a < b ? a : b;
        *hi += a < b ? b : a;
    }
}

/* 1 when a plane (a world axis or the slab normal) separates the boxes of a
 * and b with the eye on a's side, so a must come first. */
static int must_precede(const oit_partfile_part *a, const oit_partfile_part *b,
                        const float n[3], const float eye[3], const float *dir)
{
    static const float axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int k = 0; k < 4; k++) {
        const float *d = k < 3 ? axes[k] : n;
        float alo, ahi, blo, bhi;
        box_extent(a, d, &alo, &ahi);
        box_extent(b, d, &blo, &bhi);
        if (dir) {
            /* Parallel rays cross the plane in the direction of d . dir's
             * sign; along it (0) they meet one side only. */
            float s = oit_dot3f(d, dir);
            if ((ahi <= blo && s > 0.0f) || (bhi <= alo && s < 0.0f))
                return 1;
            continue;
        }
        float e = oit_dot3f(d, eye);
        if ((ahi <= blo && e <= ahi) || (bhi <= alo && e >= alo))
            return 1;
    }
    return 0;
}

/* The slab's inside parts are the pieces of its cuboid, cut by planes; sort
 * them so that a part comes before every part it is separated from on the
 * far side (insertion: m is a handful). */
static void emit_inside(emit_ctx *e, const oit_partfile_slab *sl, uint32_t slab)
{
    uint32_t m = 0;
    const uint32_t *in = oit_partfile_slab_inside(e->o->pf, slab, &m);
    const oit_partfile_part *parts = oit_partfile_parts(e->o->pf);
    uint32_t *s = e->o->scratch;
    for (uint32_t i = 0; i < m; i++) {
        uint32_t at = i;
        for (uint32_t j = 0; j < i; j++)
            if (must_precede(&parts[in[i]], &parts[s[j]], sl->normal, e->eye, e->dir)) {
                at = j;
                break;
            }
        memmove(s + at + 1, s + at, (size_t)(i - at) * sizeof *s);
        s[at] = in[i];
    }
    for (uint32_t i = 0; i < m; i++)
        emit(e, s[i]);
}

static void emit_slab_cell(emit_ctx *e, uint32_t slab)
{
    const oit_partfile_slab *sl = oit_partfile_slab_at(e->o->pf, slab);
    /* In double: a cutting plane (d0 = d1) has geometry on it, and the eye
     * should be put on its side to far below a float's rounding. */
    const float *x = e->dir ? e->dir : e->eye;
    double side = (double)sl->normal[0] * x[0] + (double)sl->normal[1] * x[1] +
                  (double)sl->normal[2] * x[2];
    /* Parallel rays: those going up n (side > 0) meet the part below first,
     * those going down the part above; rays along the planes (side = 0)
     * meet one side only, so either order holds. */
    int below_first = e->dir ? side >= 0.0 : side <= sl->d0;
    int above_first = e->dir ? side < 0.0 : side >= sl->d1;
    if (below_first) {
        emit(e, sl->part_below);
        emit_inside(e, sl, slab);
        emit(e, sl->part_above);
    } else if (above_first) {
        emit(e, sl->part_above);
        emit_inside(e, sl, slab);
        emit(e, sl->part_below);
    } else {
        /* Between the planes a ray leaves the slab through one plane only,
         * so the two sides never meet on one ray. */
        emit_inside(e, sl, slab);
        emit(e, sl->part_below);
        emit(e, sl->part_above);
    }
}

static void emit_cell(emit_ctx *e, uint32_t grid, uint64_t cell)
{
    const oit_partfile_cell *c = &e->o->cells[grid][cell];
    if (c->slab)
        emit_slab_cell(e, c->slab - 1);
    /* The cell's list: everything when it has no slab; with one, the parts
     * the slab names are already out and this only adds any it does not. */
    uint32_t n = 0;
    const uint32_t *list = oit_partfile_cell_parts(e->o->pf, grid, cell, &n);
    for (uint32_t i = 0; i < n; i++)
        emit(e, list[i]);
}

static void push(oit_order *o, size_t *top, uint32_t grid, const uint32_t lo[3],
                 const uint32_t hi[3], int inside)
{
    order_node *nd = &o->stack[(*top)++];
    nd->grid = grid;
    nd->inside = inside;
    memcpy(nd->lo, lo, sizeof nd->lo);
    memcpy(nd->hi, hi, sizeof nd->hi);
}

void oit_order_split_range(const oit_partfile_grid *g, const uint32_t lo[3], const uint32_t hi[3],
                           int *axis, uint32_t *mid)
{
    int a = 0;
    float best = -1.0f;
    for (int k = 0; k < 3; k++) {
        float len = (float)(hi[k] - lo[k]) * g->cell_size[k];
        if (hi[k] - lo[k] > 1 && len > best) {
            best = len;
            a = k;
        }
    }
    *axis = a;
    *mid = lo[a] + (hi[a] - lo[a]) / 2;
}

/* Splits nd at the middle of its longest side; pushes the far half, then the
 * near half (popped first). */
static void split(oit_order *o, size_t *top, const order_node *nd, const float eye[3],
                  const float *dir)
{
    const oit_partfile_grid *g = o->grids[nd->grid];
    int axis;
    uint32_t mid;
    oit_order_split_range(g, nd->lo, nd->hi, &axis, &mid);
    float plane = g->origin[axis] + (float)mid * g->cell_size[axis];
    uint32_t lo2[3], hi1[3];
    memcpy(lo2, nd->lo, sizeof lo2);
    memcpy(hi1, nd->hi, sizeof hi1);
    lo2[axis] = mid;
    hi1[axis] = mid;
    order_node a = *nd; /* nd points into the stack, which push overwrites */
    /* The near half: the eye's side of the plane, or for parallel rays the
     * side they come from (going up the axis: the lower half; along the
     * plane they meet one half only, so either order holds). */
    if (dir ? dir[axis] > 0.0f : eye[axis] < plane) {
        push(o, top, a.grid, lo2, a.hi, a.inside);
        push(o, top, a.grid, a.lo, hi1, a.inside);
    } else {
        push(o, top, a.grid, a.lo, hi1, a.inside);
        push(o, top, a.grid, lo2, a.hi, a.inside);
    }
}

static void push_grid(oit_order *o, size_t *top, uint32_t grid, int inside)
{
    static const uint32_t zero[3] = {0, 0, 0};
    push(o, top, grid, zero, o->grids[grid]->dims, inside);
}

/* Where a range's parts lie against the planes: -1 wholly outside one of
 * them, 1 inside all, 0 across. In double, with the box grown by the grid's
 * reach and a relative margin for the floats its corners were made of. */
static int classify(const oit_order *o, const order_node *nd, const float (*planes)[4])
{
    const oit_partfile_grid *g = o->grids[nd->grid];
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = (double)g->origin[k] + (double)nd->lo[k] * g->cell_size[k];
        hi[k] = (double)g->origin[k] + (double)nd->hi[k] * g->cell_size[k];
        double grow = o->reach[nd->grid] + 1e-5 * (hi[k] - lo[k] + fabs(lo[k]) + fabs(hi[k]));
        lo[k] -= grow;
        hi[k] += grow;
    }
    int inside = 1;
    for (int i = 0; i < 6; i++) {
        double most = planes[i][3], least = planes[i][3];
        for (int k = 0; k < 3; k++) {
            double a = planes[i][k] * lo[k], b = planes[i][k] * hi[k];
            most += fmax(a, b);
            least += fmin(a, b);
        }
        if (most < 0)
            return -1;
        inside &= least >= 0;
    }
    return inside;
}

oit_status oit_order_compute(oit_order *o, const float eye[3], uint32_t *parts,
                             uint32_t *count, oit_error *err)
{
    return oit_order_compute_culled(o, eye, NULL, parts, count, err);
}

static oit_status order_compute(oit_order *o, const float eye[3], const float *dir,
                                const float (*planes)[4], uint32_t *parts, uint32_t *count,
                                oit_error *err);

oit_status oit_order_compute_culled(oit_order *o, const float eye[3], const float (*planes)[4],
                                    uint32_t *parts, uint32_t *count, oit_error *err)
{
    *count = 0;
    if (!(eye[0] == eye[0] && eye[1] == eye[1] && eye[2] == eye[2]))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part order: eye is not a number",
                             oit_partfile_name(o->pf));
    return order_compute(o, eye, NULL, planes, parts, count, err);
}

oit_status oit_order_compute_parallel(oit_order *o, const float dir[3],
                                      const float (*planes)[4], uint32_t *parts,
                                      uint32_t *count, oit_error *err)
{
    *count = 0;
    if (!(isfinite(dir[0]) && isfinite(dir[1]) && isfinite(dir[2])) ||
        (dir[0] == 0.0f && dir[1] == 0.0f && dir[2] == 0.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part order: the view direction "
                             "(%g, %g, %g) is zero or not a number", oit_partfile_name(o->pf),
                             dir[0], dir[1], dir[2]);
    return order_compute(o, dir, dir, planes, parts, count, err);
}

static oit_status order_compute(oit_order *o, const float eye[3], const float *dir,
                                const float (*planes)[4], uint32_t *parts, uint32_t *count,
                                oit_error *err)
{
    if (++o->frame == 0) { /* the stamp wrapped: forget every old mark */
        memset(o->stamp, 0, (size_t)oit_partfile_part_count(o->pf) * sizeof *o->stamp);
        o->frame = 1;
    }
    emit_ctx e = {o, eye, dir, parts, 0, oit_partfile_part_count(o->pf)};
    size_t top = 0;
    if (o->grid_count)
        push_grid(o, &top, 0, planes == NULL);
    while (top > 0) {
        order_node nd = o->stack[--top];
        if (!nd.inside) {
            int c = classify(o, &nd, planes);
            if (c < 0)
                continue;
            nd.inside = c > 0;
        }
        const oit_partfile_grid *g = o->grids[nd.grid];
        uint64_t cells = (uint64_t)(nd.hi[0] - nd.lo[0]) * (nd.hi[1] - nd.lo[1]) *
                         (nd.hi[2] - nd.lo[2]);
        if (top + 2 > o->stack_cap)
            return oit_error_set(err, OIT_ERR_FORMAT, "%s: part order: grid %u nests deeper "
                                 "than its subgrid links allow", oit_partfile_name(o->pf), nd.grid);
        if (cells > 1) {
            split(o, &top, &nd, eye, dir);
            continue;
        }
        if (cells == 0)
            continue;
        uint64_t cell = nd.lo[0] + (uint64_t)g->dims[0] * (nd.lo[1] + (uint64_t)g->dims[1] * nd.lo[2]);
        uint32_t sub = o->cells[nd.grid][cell].subgrid;
        /* The reader checked sub > nd.grid, so a chain of subgrids ends. */
        if (sub && sub < o->grid_count)
            push_grid(o, &top, sub, nd.inside);
        else
            emit_cell(&e, nd.grid, cell);
    }
    *count = e.count;
    return OIT_OK;
}
