/* Out-of-core binning (bin.h). */
#include "prepare/convert/bin.h"
#include "base/grow.h"
#include "base/minmax.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


typedef struct bin_chunk {
    uint64_t offset; /* of the triangles, after the record header; their
                        source indices follow them */
    uint64_t count;
} bin_chunk;

typedef struct cell_bin {
    oit_triangle *tris;
    uint32_t *src; /* parallel to tris */
    size_t n, cap;
    bin_chunk *chunks;
    size_t nchunks, chunk_cap;
} cell_bin;

struct oit_bins {
    oit_bin_grid grid;
    uint64_t cells;
    cell_bin *bins;
    size_t memory, held;
    char *spill_path;
    int fd;
    uint64_t spill_end;
};

oit_status oit_bins_create(const oit_bin_grid *grid, size_t memory_budget, const char *spill_path,
                           oit_bins **out, oit_error *err)
{
    oit_bins *b = calloc(1, sizeof *b);
    uint64_t cells = (uint64_t)grid->dims[0] * grid->dims[1] * grid->dims[2];
    if (b) {
        b->bins = calloc(cells, sizeof *b->bins);
        b->spill_path = strdup(spill_path);
    }
    if (!b || !b->bins || !b->spill_path) {
        if (b) {
            free(b->bins);
            free(b->spill_path);
        }
        free(b);
        return oit_error_set(err, OIT_ERR_NOMEM, "binning into %llu cells: out of memory",
                             (unsigned long long)cells);
    }
    b->grid = *grid;
    b->cells = cells;
    b->memory = memory_budget;
    b->fd = -1;
    *out = b;
    return OIT_OK;
}

void oit_bin_cell_range(const oit_bin_grid *g, const float mn[3], const float mx[3],
                        uint32_t lo[3], uint32_t hi[3])
{
    for (int k = 0; k < 3; k++) {
        /* Exact: origin and cell are multiples of a power of two. A minimum on
         * a cell face also reaches the cell below (closed boxes). */
        double a = ((double)mn[k] - g->origin[k]) / g->cell;
        double z = ((double)mx[k] - g->origin[k]) / g->cell;
        double l = ceil(a) - 1, h = floor(z);
        l = l < 0 ? 0 : l;
        h = h > g->dims[k] - 1 ? g->dims[k] - 1 : h;
        lo[k] = (uint32_t)l;
        hi[k] = (uint32_t)(h < l ? l : h);
    }
}

/* All n bytes at off, through pwrite (writing) or pread, again after an
 * interruption or a short transfer; -1 on an error or the file's end. */
static int transfer_all(int fd, char *c, size_t n, uint64_t off, int writing)
{
    while (n) {
        ssize_t k = writing ? pwrite(fd, c, n, (off_t)off) : pread(fd, c, n, (off_t)off);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        c += k;
        n -= (size_t)k;
        off += (uint64_t)k;
    }
    return 0;
}

static int write_all(int fd, const void *p, size_t n, uint64_t off)
{
    return transfer_all(fd, (char *)p, n, off, 1);
}

static oit_status spill(oit_bins *b, oit_error *err)
{
    if (b->fd < 0) {
        b->fd = open(b->spill_path, O_RDWR | O_CREAT | O_TRUNC | O_EXCL, 0600);
        if (b->fd < 0)
            return oit_error_set(err, OIT_ERR_IO, "%s: cannot create spill file: %s",
                                 b->spill_path, strerror(errno));
        unlink(b->spill_path);
    }
    for (uint64_t c = 0; c < b->cells; c++) {
        cell_bin *cb = &b->bins[c];
        if (!cb->n)
            continue;
        if (cb->nchunks == cb->chunk_cap) {
            size_t cap = cb->chunk_cap ? 2 * cb->chunk_cap : 4;
            bin_chunk *p = realloc(cb->chunks, cap * sizeof *p);
            if (!p)
                return oit_error_set(err, OIT_ERR_NOMEM, "spill index: out of memory");
            cb->chunks = p;
            cb->chunk_cap = cap;
        }
        uint64_t head[2] = {c, cb->n}, tri_bytes = cb->n * sizeof *cb->tris;
        if (write_all(b->fd, head, sizeof head, b->spill_end) ||
            write_all(b->fd, cb->tris, tri_bytes, b->spill_end + sizeof head) ||
            write_all(b->fd, cb->src, cb->n * sizeof *cb->src,
                      b->spill_end + sizeof head + tri_bytes))
            return oit_error_set(err, OIT_ERR_IO, "%s: spill write failed: %s", b->spill_path,
                                 strerror(errno));
        cb->chunks[cb->nchunks++] = (bin_chunk){b->spill_end + sizeof head, cb->n};
        b->spill_end += sizeof head + cb->n * (sizeof *cb->tris + sizeof *cb->src);
        free(cb->tris);
        free(cb->src);
        cb->tris = NULL;
        cb->src = NULL;
        cb->n = cb->cap = 0;
    }
    b->held = 0;
    return OIT_OK;
}

static oit_status push(oit_bins *b, uint64_t c, const oit_triangle *t, uint32_t src,
                       oit_error *err)
{
    cell_bin *cb = &b->bins[c];
    if (cb->n == cb->cap) {
        size_t cap = cb->cap ? 2 * cb->cap : 64;
        int ok = 1;
        cb->tris = oit_grow(cb->tris, cap, sizeof *cb->tris, &ok);
        cb->src = oit_grow(cb->src, cap, sizeof *cb->src, &ok);
        if (!ok)
            return oit_error_set(err, OIT_ERR_NOMEM, "bin of cell %llu: out of memory",
                                 (unsigned long long)c);
        b->held += (cap - cb->cap) * (sizeof *cb->tris + sizeof *cb->src);
        cb->cap = cap;
    }
    cb->src[cb->n] = src;
    cb->tris[cb->n++] = *t;
    return b->held > b->memory ? spill(b, err) : OIT_OK;
}

oit_status oit_bins_add(oit_bins *b, const oit_triangle *tris, const uint32_t *src, size_t count,
                        oit_error *err)
{
    const oit_bin_grid *g = &b->grid;
    for (size_t i = 0; i < count; i++) {
        const oit_triangle *t = &tris[i];
        float mn[3], mx[3];
        for (int k = 0; k < 3; k++) {
            mn[k] = oit_min_f(oit_min_f(t->v[0].pos[k], t->v[1].pos[k]), t->v[2].pos[k]);
            mx[k] = oit_max_f(oit_max_f(t->v[0].pos[k], t->v[1].pos[k]), t->v[2].pos[k]);
        }
        uint32_t lo[3], hi[3];
        oit_bin_cell_range(g, mn, mx, lo, hi);
        for (uint32_t z = lo[2]; z <= hi[2]; z++)
            for (uint32_t y = lo[1]; y <= hi[1]; y++)
                for (uint32_t x = lo[0]; x <= hi[0]; x++) {
                    oit_status s =
                        push(b, x + (uint64_t)g->dims[0] * (y + (uint64_t)g->dims[1] * z), t,
                             src[i], err);
                    if (s)
                        return s;
                }
    }
    return OIT_OK;
}

static int read_all(int fd, void *p, size_t n, uint64_t off)
{
    return transfer_all(fd, p, n, off, 0);
}

oit_status oit_bins_read_cell(oit_bins *b, uint64_t cell, oit_triangle **tris, uint32_t **src,
                              size_t *count, oit_error *err)
{
    cell_bin *cb = &b->bins[cell];
    size_t n = cb->n;
    for (size_t i = 0; i < cb->nchunks; i++)
        n += cb->chunks[i].count;
    *tris = NULL;
    *src = NULL;
    *count = n;
    if (!n)
        return OIT_OK;
    oit_triangle *t = malloc(n * sizeof *t);
    uint32_t *q = t ? malloc(n * sizeof *q) : NULL;
    if (!q) {
        free(t);
        return oit_error_set(err, OIT_ERR_NOMEM, "cell %llu: %zu triangles: out of memory",
                             (unsigned long long)cell, n);
    }
    size_t at = 0;
    for (size_t i = 0; i < cb->nchunks; i++) {
        uint64_t k = cb->chunks[i].count, off = cb->chunks[i].offset;
        if (read_all(b->fd, t + at, k * sizeof *t, off) ||
            read_all(b->fd, q + at, k * sizeof *q, off + k * sizeof *t)) {
            free(t);
            free(q);
            return oit_error_set(err, OIT_ERR_IO, "%s: spill read failed: %s", b->spill_path,
                                 strerror(errno));
        }
        at += k;
    }
    if (cb->n) {
        memcpy(t + at, cb->tris, cb->n * sizeof *t);
        memcpy(q + at, cb->src, cb->n * sizeof *q);
    }
    /* Each cell is read once: its memory goes back as the partition goes
     * on, instead of all bins staying to the end. */
    free(cb->tris);
    free(cb->src);
    cb->tris = NULL;
    cb->src = NULL;
    cb->n = cb->cap = 0;
    *tris = t;
    *src = q;
    return OIT_OK;
}

uint64_t oit_bins_spilled_bytes(const oit_bins *b)
{
    return b->spill_end;
}

void oit_bins_destroy(oit_bins *b)
{
    if (!b)
        return;
    for (uint64_t c = 0; c < b->cells; c++) {
        free(b->bins[c].tris);
        free(b->bins[c].src);
        free(b->bins[c].chunks);
    }
    free(b->bins);
    if (b->fd >= 0)
        close(b->fd);
    free(b->spill_path);
    free(b);
}
