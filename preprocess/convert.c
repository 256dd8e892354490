/* The conversion pipeline (convert.h). */
#include "preprocess/convert.h"
#include "base/clock.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "oit/mesh.h"
#include "partition/convex.h"
#include "oit/partfile.h"
#include "partfile/write.h"
#include "partition/clip.h"
#include "partition/kd_split.h"
#include "preprocess/bin.h"
#include "preprocess/cell.h"
#include "preprocess/grid_phase.h"
#include "preprocess/progress.h"

#define TRIANGLES_PER_CELL 65536.0
/* The fast scheme's top cells: at least this many, and 8 parts' worth. */
#define FAST_TRIANGLES_PER_CELL 262144.0
#define MAX_TOP_CELLS_PER_AXIS 1024u


/* ---- the top grid ------------------------------------------------------------ */

/* Cubic cells whose edge is a power of two and an origin on a multiple of
 * it: every cell face and every kd midplane below it is an exact float, so
 * clipped geometry and the grid records agree bit for bit. */
/* The fast scheme's origin: a multiple of cell / 2^j, the coarsest that
 * gives fewest cells. A grid aligned to its own cell size always has a face
 * at 0, so a model around the origin is cut in two on every axis however
 * coarse the grid; a face at a multiple of a finer power of two is still an
 * exact float (the same argument as for the cell size). */
static void shift_origin(const float mn[3], const float mx[3], oit_bin_grid *g)
{
    for (int k = 0; k < 3; k++)
        for (int j = 1; j <= 8; j++) {
            double a = g->cell / exp2(j), o = floor(mn[k] / a) * a;
            uint32_t dims = (uint32_t)floor((mx[k] - o) / g->cell) + 1;
            if (dims < g->dims[k]) {
                g->origin[k] = (float)o;
                g->dims[k] = dims;
            }
        }
}

/* Cells of edge `cell` from the face at or below mn, as many as reach mx. */
static void grid_at_cell(const float mn[3], const float mx[3], double cell, oit_bin_grid *g)
{
    g->cell = (float)cell;
    for (int k = 0; k < 3; k++) {
        double o = floor(mn[k] / cell) * cell;
        g->origin[k] = (float)o;
        g->dims[k] = (uint32_t)floor((mx[k] - o) / cell) + 1;
    }
}

static void choose_grid(const float mn[3], const float mx[3], uint64_t triangles, uint32_t want,
                        double per_cell, oit_bin_grid *g)
{
    double ext[3], longest = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = (double)mx[k] - mn[k];
        longest = ext[k] > longest ? ext[k] : longest;
    }
    uint32_t n = want;
    if (!n) {
        double target = ceil(triangles / per_cell);
        for (n = 1; n < MAX_TOP_CELLS_PER_AXIS; n++) {
            double cells = 1;
            for (int k = 0; k < 3; k++)
                cells *= fmax(1.0, ceil(ext[k] / (longest / n)));
            if (cells >= target)
                break;
        }
    }
    grid_at_cell(mn, mx, longest > 0 ? exp2(ceil(log2(longest / n))) : 1.0, g);
}

static uint64_t cell_count(const oit_bin_grid *g)
{
    return (uint64_t)g->dims[0] * g->dims[1] * g->dims[2];
}

/* The fast scheme's grid, when the user gave no --grid: a model whose
 * extent is its power-of-two cell size, or that straddles a face of every
 * shift, still spans two cells an axis (a bounds maximum on a cell face
 * counts in the next cell), more than the `want` cells its triangles need,
 * and every face clips. A twice or four times larger cell that still gives
 * at least `want` has faces that are as exact, and costs the kd below
 * nothing: it splits by triangle counts, not by cell size. */
static void fewest_cells(const float mn[3], const float mx[3], uint64_t want, oit_bin_grid *g)
{
    for (int d = 1; d <= 2; d++) {
        oit_bin_grid c;
        grid_at_cell(mn, mx, (double)g->cell * 2.0, &c);
        shift_origin(mn, mx, &c);
        if (cell_count(&c) < cell_count(g) && cell_count(&c) >= want)
            *g = c;
    }
}

/* ---- passes over the input ------------------------------------------------- */

static oit_status count_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return OIT_OK;
}

static oit_status phase_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    oit_grid_phase_add(user, t, n);
    return OIT_OK;
}

/* The fast scheme's grid: cells of at least per_cell triangles, their faces
 * where they cross fewest triangles (grid_phase.h), which takes one more
 * pass over the input. */
static oit_status fast_grid(const oit_convert_options *o, const oit_mesh_info *info,
                            oit_bin_grid *g, oit_error *err)
{
    double per_cell = fmax(FAST_TRIANGLES_PER_CELL, 8.0 * o->part_triangles);
    choose_grid(info->bounds_min, info->bounds_max, info->triangles, o->grid, per_cell, g);
    shift_origin(info->bounds_min, info->bounds_max, g);
    if (!o->grid)
        fewest_cells(info->bounds_min, info->bounds_max,
                     (uint64_t)ceil((double)info->triangles / per_cell), g);
    oit_grid_phase *ph = malloc(sizeof *ph);
    if (!ph)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", o->input);
    oit_grid_phase_init(ph, g);
    oit_read_desc rd = {.deflection = info->deflection};
    oit_mesh_info again;
    oit_progress pg;
    oit_progress_start(&pg, "grid", 1, o->progress, o->progress_period_s);
    oit_status s = oit_mesh_read(o->input, &rd, phase_sink, ph, &again, err);
    oit_progress_end(&pg);
    if (!s && again.triangles != info->triangles)
        s = oit_error_set(err, OIT_ERR_IO, "%s: changed while it was read (%llu triangles, "
                          "then %llu)", o->input, (unsigned long long)info->triangles,
                          (unsigned long long)again.triangles);
    if (!s)
        oit_grid_phase_apply(ph, info->bounds_min, info->bounds_max, g);
    free(ph);
    return s;
}

typedef struct bin_sink_ctx {
    oit_bins *bins;
    uint64_t seen, degenerate;
    oit_triangle *keep;
    uint32_t *keep_src; /* the kept triangles' source indices */
    oit_progress *progress;
} bin_sink_ctx;

/* A triangle's source index is its position among the triangles the reader
 * delivers (what oit_mesh_load's array index would be), so counted before
 * dropping degenerate ones. */
static oit_status bin_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    bin_sink_ctx *c = user;
    if (c->seen + n > (uint64_t)UINT32_MAX + 1)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "more than 2^32 triangles: their source "
                             "indices would not fit the part file's 32 bits");
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (oit_triangle_is_degenerate(&t[i]))
            c->degenerate++;
        else {
            c->keep_src[m] = (uint32_t)(c->seen + i);
            c->keep[m++] = t[i];
        }
    }
    c->seen += n;
    oit_progress_update(c->progress, c->seen);
    return oit_bins_add(c->bins, c->keep, c->keep_src, m, err);
}

/* ---- parallel cells, written in order ------------------------------------- */

typedef struct cell_out {
    oit_kd_result kd;
    oit_cell_counts counts;
    oit_status status;
    oit_error err;
    int done;
    uint32_t part_base;
} cell_out;

typedef struct cell_run {
    const oit_convert_options *o;
    oit_bin_grid grid;
    oit_bins *bins;
    cell_out *res;
    uint64_t ncells;
    atomic_uint_fast64_t next;
    uint64_t written; /* cells the writer has consumed; workers stay close */
    int stop;
    pthread_mutex_t lock;
    pthread_cond_t cond;
} cell_run;

static void cell_params(const cell_run *r, uint64_t c, oit_cell_params *p)
{
    uint32_t idx[3] = {(uint32_t)(c % r->grid.dims[0]),
                       (uint32_t)(c / r->grid.dims[0] % r->grid.dims[1]),
                       (uint32_t)(c / r->grid.dims[0] / r->grid.dims[1])};
    memset(p, 0, sizeof *p);
    for (int k = 0; k < 3; k++) {
        p->lo[k] = r->grid.origin[k] + (float)idx[k] * r->grid.cell;
        p->hi[k] = r->grid.origin[k] + (float)(idx[k] + 1) * r->grid.cell;
        p->lo_shared[k] = idx[k] > 0;
    }
    p->K = r->o->K;
    p->max_piece_triangles = r->o->max_piece_triangles;
    p->slabs = r->o->slabs;
    p->fast_part_triangles = r->o->scheme == OIT_SCHEME_FAST ? r->o->part_triangles : 0;
}

static void run_cell(cell_run *r, uint64_t c)
{
    cell_out *out = &r->res[c];
    oit_triangle *tris = NULL;
    uint32_t *src = NULL;
    size_t n = 0;
    out->status = oit_bins_read_cell(r->bins, c, &tris, &src, &n, &out->err);
    if (!out->status) {
        oit_cell_params p;
        cell_params(r, c, &p);
        out->status = oit_cell_partition(&p, tris, src, n, &out->kd, &out->counts, &out->err);
    }
    free(tris);
    free(src);
}

static void *cell_worker(void *arg)
{
    cell_run *r = arg;
    for (;;) {
        uint64_t c = atomic_fetch_add(&r->next, 1);
        if (c >= r->ncells)
            break;
        /* Stay within a window of the writer, so finished cells do not pile up. */
        pthread_mutex_lock(&r->lock);
        while (!r->stop && c >= r->written + 4 * (uint64_t)r->o->threads + 4)
            pthread_cond_wait(&r->cond, &r->lock);
        int stop = r->stop;
        pthread_mutex_unlock(&r->lock);
        if (stop)
            break;
        run_cell(r, c);
        pthread_mutex_lock(&r->lock);
        r->res[c].done = 1;
        pthread_cond_broadcast(&r->cond);
        pthread_mutex_unlock(&r->lock);
    }
    return NULL;
}

/* ---- writing parts ---------------------------------------------------------- */

typedef struct part_buf {
    float *pos;
    uint8_t *rgba;
    uint32_t *idx;
    uint32_t *slot; /* hash of vertex -> index + 1 */
    oit_partfile_piece_desc *pieces;
    size_t tri_cap, piece_cap;
} part_buf;

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

static oit_status write_parts(oit_partfile_writer *w, part_buf *b, const oit_kd_result *kd,
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

static oit_status write_grids(oit_partfile_writer *w, const cell_run *r, oit_error *err)
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

/* ---- the pipeline ------------------------------------------------------------ */

static oit_status partition_and_write(cell_run *r, oit_partfile_writer *w, uint32_t attributes,
                                      oit_convert_stats *st, oit_error *err)
{
    uint32_t nt = r->o->threads ? r->o->threads : 1;
    pthread_t *th = calloc(nt, sizeof *th);
    if (!th)
        return oit_error_set(err, OIT_ERR_NOMEM, "threads: out of memory");
    uint32_t started = 0;
    for (; started < nt; started++)
        if (pthread_create(&th[started], NULL, cell_worker, r))
            break;
    oit_status s = started ? OIT_OK
                           : oit_error_set(err, OIT_ERR_IO, "cannot start worker threads");
    part_buf buf = {0};
    oit_progress pg;
    oit_progress_start(&pg, "partition", r->ncells, r->o->progress,
                       r->o->progress_period_s);
    uint32_t part_base = 0;
    for (uint64_t c = 0; c < r->ncells && !s; c++) {
        pthread_mutex_lock(&r->lock);
        while (!r->res[c].done)
            pthread_cond_wait(&r->cond, &r->lock);
        pthread_mutex_unlock(&r->lock);
        cell_out *co = &r->res[c];
        if (co->status) {
            /* The cell's message does not know the file or the cell. */
            s = oit_error_set(err, co->status, "%s: top cell %llu: %s", r->o->input,
                              (unsigned long long)c, co->err.message);
            break;
        }
        co->part_base = part_base;
        part_base += (uint32_t)co->kd.part_count;
        st->pieces += co->kd.piece_count;
        st->pieces_clustered += co->counts.pieces_cell;
        st->wide_parts += co->kd.wide_parts;
        st->clamped_parts += co->kd.clamped_parts;
        st->max_measured = co->kd.max_measured > st->max_measured ? co->kd.max_measured
                                                                  : st->max_measured;
        st->slabs += co->kd.slab_count;
        st->cut_slabs += co->kd.cuts;
        for (size_t q = 0; q < co->kd.part_count; q++)
            if (co->kd.parts[q].layer_bound > st->max_layer_bound)
                st->max_layer_bound = co->kd.parts[q].layer_bound;
        st->triangles_out += co->kd.tri_count;
        st->subgrids += co->kd.node_count / 2;
        st->subgrid_depth = co->kd.depth > st->subgrid_depth ? co->kd.depth : st->subgrid_depth;
        s = write_parts(w, &buf, &co->kd, attributes, err);
        /* Only the tree is needed from here on (for the grids). */
        free(co->kd.tris);
        free(co->kd.src);
        free(co->kd.parts);
        free(co->kd.pieces);
        co->kd.tris = NULL;
        co->kd.src = NULL;
        co->kd.parts = NULL;
        co->kd.pieces = NULL;
        pthread_mutex_lock(&r->lock);
        r->written = c + 1;
        pthread_cond_broadcast(&r->cond);
        pthread_mutex_unlock(&r->lock);
        oit_progress_update(&pg, c + 1);
    }
    pthread_mutex_lock(&r->lock);
    r->stop = s != OIT_OK;
    pthread_cond_broadcast(&r->cond);
    pthread_mutex_unlock(&r->lock);
    for (uint32_t i = 0; i < started; i++)
        pthread_join(th[i], NULL);
    free(th);
    free(buf.pos);
    free(buf.rgba);
    free(buf.idx);
    free(buf.slot);
    free(buf.pieces);
    oit_progress_end(&pg);
    st->parts = part_base;
    return s;
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* deflection: the first pass's (oit_mesh_info), so that a STEP or IGES
 * file is tessellated alike in every pass. */
static oit_status bin_input(const oit_convert_options *o, const oit_bin_grid *grid,
                            uint64_t total, double deflection, oit_bins **bins,
                            bin_sink_ctx *ctx, oit_error *err)
{
    size_t spill_len = strlen(o->output) + 8;
    char *spill = malloc(spill_len);
    if (!spill)
        return oit_error_set(err, OIT_ERR_NOMEM, "out of memory");
    snprintf(spill, spill_len, "%s.spill", o->output);
    oit_status s = oit_bins_create(grid, o->memory, spill, bins, err);
    free(spill);
    if (s)
        return s;
    oit_read_desc rd = {.deflection = deflection};
    ctx->bins = *bins;
    ctx->keep = malloc(65536 * sizeof *ctx->keep);
    ctx->keep_src = malloc(65536 * sizeof *ctx->keep_src);
    if (!ctx->keep || !ctx->keep_src) {
        free(ctx->keep);
        free(ctx->keep_src);
        return oit_error_set(err, OIT_ERR_NOMEM, "out of memory");
    }
    rd.chunk_triangles = 65536;
    oit_progress pg;
    oit_progress_start(&pg, "bin", total, o->progress, o->progress_period_s);
    ctx->progress = &pg;
    s = oit_mesh_read(o->input, &rd, bin_sink, ctx, NULL, err);
    oit_progress_end(&pg);
    free(ctx->keep);
    free(ctx->keep_src);
    return s;
}

static oit_status convert_binned(const oit_convert_options *o, const oit_mesh_info *info,
                                 cell_run *r, oit_convert_stats *st, double *t_write,
                                 oit_error *err)
{
    char options[200];
    /* The guaranteed scheme's options read as before it had a name
     * (tests/preprocess/test_prep_pinned.sh pins its files). */
    if (o->scheme == OIT_SCHEME_FAST)
        snprintf(options, sizeof options, "K=%u scheme=fast part_triangles=%u grid=%ux%ux%u "
                 "cell=%g", o->K, o->part_triangles, r->grid.dims[0], r->grid.dims[1],
                 r->grid.dims[2], r->grid.cell);
    else
        snprintf(options, sizeof options, "K=%u manage=%s grid=%ux%ux%u cell=%g "
                 "max_piece_triangles=%u slabs=%s", o->K, oit_manage_name(o->manage),
                 r->grid.dims[0], r->grid.dims[1], r->grid.dims[2], r->grid.cell,
                 /* the effective cap, so that the default and its value record alike */
                 o->max_piece_triangles ? o->max_piece_triangles : OIT_CONVEX_MAX_PIECE_DEFAULT,
                 oit_slabs_name(o->slabs));
    /* Parts average a few KB: page-aligned blobs would make padding most of
     * the file (80% on a 12M-triangle plant), and the reader gains nothing
     * from pages, reading each part with one pread into its own memory. */
    oit_partfile_writer_desc wd = {.K = o->K, .attributes = info->attributes, .part_align = 64,
                                   .source_name = base_name(o->input), .options = options,
                                   .origin = {info->origin[0], info->origin[1], info->origin[2]},
                                   .measured_bounds = o->scheme == OIT_SCHEME_FAST,
                                   /* Vertices only: triangles keep their
                                      order (docs/part-file.md, "Stored
                                      streams": the vertex-cache order moved
                                      fragments that tie on key and source
                                      index, and so image bits) */
                                   .order = OIT_PARTFILE_ORDER_VERTICES};
    oit_partfile_writer *w = NULL;
    oit_status s = oit_partfile_writer_create(o->output, &wd, &w, err);
    if (s)
        return s;
    s = partition_and_write(r, w, info->attributes, st, err);
    double t0 = oit_time_s();
    if (!s)
        s = write_grids(w, r, err);
    if (!s) {
        oit_partfile_stats ps = {st->triangles_in, st->degenerate_dropped + st->nonfinite_dropped, 0};
        /* Net: clips add triangles; slivers that round to nothing remove some. */
        int64_t kept = (int64_t)st->triangles_in -
                       (int64_t)(st->degenerate_dropped + st->nonfinite_dropped);
        st->split_added = (int64_t)st->triangles_out - kept;
        ps.triangles_split = st->split_added > 0 ? (uint64_t)st->split_added : 0;
        s = oit_partfile_writer_finish(w, &ps, err);
    } else
        oit_partfile_writer_abort(w);
    *t_write = oit_time_s() - t0;
    return s;
}

const char *oit_slabs_name(oit_kd_slabs s)
{
    return s == OIT_KD_SLABS_NONE ? "none" : s == OIT_KD_SLABS_SEPARATING ? "separating" : "all";
}

void oit_convert_options_init(oit_convert_options *o)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    memset(o, 0, sizeof *o);
    o->K = 8;
    o->memory = (size_t)2 << 30;
    o->threads = cores > 0 ? (uint32_t)cores : 1;
}

const char *oit_scheme_name(oit_scheme s)
{
    return s == OIT_SCHEME_FAST ? "fast" : "guaranteed";
}

const char *oit_manage_name(oit_manage m)
{
    return m == OIT_MANAGE_KD_PARTS ? "kd-parts" : m == OIT_MANAGE_KD_FACETS ? "kd-facets" : "grid";
}

/* The kd schemes are the grid scheme with one top cell (and, for facets,
 * pieces of one triangle): the same subdivision then is one kd-tree. */
static oit_status apply_manage(const oit_convert_options *o, oit_convert_options *eff,
                               oit_error *err)
{
    *eff = *o;
    if (o->scheme == OIT_SCHEME_FAST && !o->part_triangles)
        eff->part_triangles = OIT_FAST_PART_TRIANGLES;
    if (o->manage == OIT_MANAGE_GRID)
        return OIT_OK;
    if (o->scheme == OIT_SCHEME_FAST)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: --scheme fast builds its own kd-trees "
                             "in a grid; it cannot take --manage %s", o->input,
                             oit_manage_name(o->manage));
    if (o->grid > 1 || (o->manage == OIT_MANAGE_KD_FACETS && o->max_piece_triangles > 1))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: --manage %s builds one kd-tree over "
                             "%s; it cannot take --grid %u%s", o->input,
                             oit_manage_name(o->manage),
                             o->manage == OIT_MANAGE_KD_FACETS ? "single facets" : "the model",
                             o->grid, o->manage == OIT_MANAGE_KD_FACETS
                                          ? " or --max-piece-triangles above 1" : "");
    eff->grid = 1;
    if (o->manage == OIT_MANAGE_KD_FACETS)
        eff->max_piece_triangles = 1;
    return OIT_OK;
}

/* The conversion itself, with the scheme already applied to the options;
 * st is zeroed by the caller. */
static oit_status convert_with(const oit_convert_options *o, oit_convert_stats *st,
                               oit_error *err)
{
    st->threads = o->threads;
    st->K = o->K;
    double t0 = oit_time_s();
    oit_mesh_info info;
    oit_read_desc rd = {.deflection = o->deflection};
    oit_progress pg;
    oit_progress_start(&pg, "bounds", 1, o->progress, o->progress_period_s);
    oit_status s = oit_mesh_read(o->input, &rd, count_sink, NULL, &info, err);
    oit_progress_end(&pg);
    if (s)
        return s;
    double t1 = oit_time_s();
    st->seconds_bounds = t1 - t0; /* the fast scheme's grid pass included */
    st->nonfinite_dropped = info.nonfinite_dropped;
    st->deflection = info.deflection;
    st->triangles_in = info.triangles + info.nonfinite_dropped;
    cell_run r = {.o = o};
    if (info.triangles && o->scheme == OIT_SCHEME_FAST) {
        /* The top grid's faces cut blindly, where the kd below picks planes
         * that cross few triangles: fewer, larger cells placed where they
         * cross fewest clip less. */
        if ((s = fast_grid(o, &info, &r.grid, err)))
            return s;
        t1 = oit_time_s();
        st->seconds_bounds = t1 - t0;
    } else if (info.triangles)
        choose_grid(info.bounds_min, info.bounds_max, info.triangles, o->grid,
                    TRIANGLES_PER_CELL, &r.grid);
    else
        r.grid = (oit_bin_grid){{0, 0, 0}, 1.0f, {1, 1, 1}};
    r.ncells = (uint64_t)r.grid.dims[0] * r.grid.dims[1] * r.grid.dims[2];
    memcpy(st->grid_dims, r.grid.dims, sizeof st->grid_dims);
    st->cells = r.ncells;
    bin_sink_ctx bctx = {0};
    s = bin_input(o, &r.grid, info.triangles, info.deflection, &r.bins, &bctx, err);
    st->degenerate_dropped = bctx.degenerate;
    if (!s && bctx.degenerate == info.triangles) /* the reader's test is coarser than ours */
        s = oit_error_set(err, OIT_ERR_FORMAT, "%s: all %llu triangles are degenerate (no "
                          "plane): nothing to convert", o->input,
                          (unsigned long long)info.triangles);
    double t2 = oit_time_s();
    st->seconds_bin = t2 - t1;
    double t_write = 0;
    if (!s) {
        st->spilled_bytes = oit_bins_spilled_bytes(r.bins);
        r.res = calloc(r.ncells, sizeof *r.res);
        if (!r.res)
            s = oit_error_set(err, OIT_ERR_NOMEM, "out of memory");
    }
    if (!s) {
        pthread_mutex_init(&r.lock, NULL);
        pthread_cond_init(&r.cond, NULL);
        s = convert_binned(o, &info, &r, st, &t_write, err);
        pthread_mutex_destroy(&r.lock);
        pthread_cond_destroy(&r.cond);
    }
    if (r.res)
        for (uint64_t c = 0; c < r.ncells; c++)
            oit_kd_result_free(&r.res[c].kd);
    free(r.res);
    oit_bins_destroy(r.bins);
    st->cells += st->subgrids * 2;
    st->seconds_partition = oit_time_s() - t2 - t_write;
    st->seconds_write = t_write;
    st->seconds_total = oit_time_s() - t0;
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) == 0)
        st->peak_rss_bytes = (uint64_t)ru.ru_maxrss * 1024;
    if (s && s != OIT_ERR_NOMEM && !strstr(err->message, o->input) &&
        !strstr(err->message, o->output))
        oit_error_prefix(err, o->input);
    return s;
}

oit_status oit_convert(const oit_convert_options *o, oit_convert_stats *st, oit_error *err)
{
    oit_convert_options eff;
    memset(st, 0, sizeof *st);
    oit_status s = apply_manage(o, &eff, err);
    return s ? s : convert_with(&eff, st, err);
}
