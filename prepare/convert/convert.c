/* The conversion pipeline (convert.h). This file holds the passes over the
 * input (bounds, the fast scheme's grid phase, binning), the pipeline's
 * order and the options; the top grid is chosen in convert_grid.c, cells
 * are partitioned in convert_cells.c and written in convert_write.c
 * (convert_internal.h). */
#include "prepare/convert/convert.h"
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
#include "prepare/partition/clip.h"
#include "prepare/partition/convex.h"
#include "prepare/convert/convert_internal.h"
#include "prepare/convert/grid_phase.h"
#include "prepare/convert/progress.h"

#define TRIANGLES_PER_CELL 65536.0
/* The fast scheme's top cells: at least this many, and 8 parts' worth. */
#define FAST_TRIANGLES_PER_CELL 262144.0

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
    oit_convert_choose_grid(info->bounds_min, info->bounds_max, info->triangles, o->grid,
                            per_cell, g);
    oit_convert_shift_origin(info->bounds_min, info->bounds_max, g);
    if (!o->grid)
        oit_convert_fewest_cells(info->bounds_min, info->bounds_max,
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

/* ---- the pipeline ------------------------------------------------------------ */

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
     * (tests/prepare/convert/test_prep_pinned.sh pins its files). */
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
    s = oit_convert_partition_and_write(r, w, info->attributes, st, err);
    double t0 = oit_time_s();
    if (!s)
        s = oit_convert_write_grids(w, r, err);
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
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oit_convert_options.scheme = fast "
                             "builds its own kd-trees in a grid; it cannot take "
                             "oit_convert_options.manage = %s", o->input,
                             oit_manage_name(o->manage));
    if (o->grid > 1 || (o->manage == OIT_MANAGE_KD_FACETS && o->max_piece_triangles > 1))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oit_convert_options.manage = %s builds "
                             "one kd-tree over %s; it cannot take oit_convert_options.grid = "
                             "%u%s", o->input, oit_manage_name(o->manage),
                             o->manage == OIT_MANAGE_KD_FACETS ? "single facets" : "the model",
                             o->grid, o->manage == OIT_MANAGE_KD_FACETS
                                          ? " or oit_convert_options.max_piece_triangles above 1"
                                          : "");
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
        oit_convert_choose_grid(info.bounds_min, info.bounds_max, info.triangles, o->grid,
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
