/* Cells partitioned in parallel and consumed in cell order
 * (convert_internal.h): workers take cells from a counter within a window
 * of the writer, the writer waits for each cell in turn, so the file is
 * byte-identical for any thread count. Apart as the one threaded step. */
#include "prepare/convert/convert_internal.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "prepare/convert/progress.h"

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

oit_status oit_convert_partition_and_write(cell_run *r, oit_partfile_writer *w, uint32_t attributes,
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
        s = oit_convert_write_parts(w, &buf, &co->kd, attributes, err);
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
