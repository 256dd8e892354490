/* Wavefront scheduling (schedule.h): Kahn's algorithm over the overlap
 * constraints, with a heap keyed by nearest depth. */
#include "view/stream/schedule.h"

#include <stdlib.h>
#include <string.h>

enum { BIN = 32 };
#define NONE UINT32_MAX

struct oit_scheduler {
    uint32_t max;
    uint32_t *indeg, *seen, *out_first, *cursor, *heap;
    uint32_t *edges;
    size_t edge_cap;
    uint32_t *last; /* per bin: the latest part that touched it */
    size_t bin_cap;
};

void oit_scheduler_destroy(oit_scheduler *s)
{
    if (!s)
        return;
    free(s->indeg);
    free(s->seen);
    free(s->out_first);
    free(s->cursor);
    free(s->heap);
    free(s->edges);
    free(s->last);
    free(s);
}

oit_status oit_scheduler_create(uint32_t max_parts, oit_scheduler **out, oit_error *err)
{
    oit_scheduler *s = calloc(1, sizeof *s);
    size_t n = (size_t)max_parts + 1;
    if (s) {
        s->max = max_parts;
        s->indeg = malloc(n * sizeof *s->indeg);
        s->seen = malloc(n * sizeof *s->seen);
        s->out_first = malloc((n + 1) * sizeof *s->out_first);
        s->cursor = malloc(n * sizeof *s->cursor);
        s->heap = malloc(n * sizeof *s->heap);
    }
    if (!s || !s->indeg || !s->seen || !s->out_first || !s->cursor || !s->heap) {
        oit_scheduler_destroy(s);
        *out = NULL;
        return oit_error_set(err, OIT_ERR_NOMEM, "scheduling: cannot allocate for %u parts",
                             max_parts);
    }
    *out = s;
    return OIT_OK;
}

typedef struct bin_span {
    int x0, x1, y0, y1, nx;
} bin_span;

static int clamp(int v, int hi)
{
    return v < 0 ? 0 : v > hi ? hi : v;
}

static bin_span span_of(const int r[4], int nx, int ny)
{
    return (bin_span){clamp(r[0] / BIN, nx - 1), clamp((r[2] - 1) / BIN, nx - 1),
                      clamp(r[1] / BIN, ny - 1), clamp((r[3] - 1) / BIN, ny - 1), nx};
}

/* One walk over every part's bins in input order. With fill == 0 it counts
 * each part's distinct predecessors (indeg) and successors (out_first[i+1]);
 * with fill == 1 it writes the successors into edges. */
static void link_parts(oit_scheduler *s, uint32_t n, const int (*rects)[4], int nx, int ny,
                       int fill)
{
    for (size_t b = 0; b < (size_t)nx * ny; b++)
        s->last[b] = NONE;
    for (uint32_t i = 0; i < n; i++)
        s->seen[i] = NONE;
    for (uint32_t j = 0; j < n; j++) {
        bin_span sp = span_of(rects[j], nx, ny);
        for (int y = sp.y0; y <= sp.y1; y++)
            for (int x = sp.x0; x <= sp.x1; x++) {
                uint32_t *l = &s->last[(size_t)y * nx + x], i = *l;
                *l = j;
                if (i == NONE || s->seen[i] == j)
                    continue;
                s->seen[i] = j;
                if (fill)
                    s->edges[s->cursor[i]++] = j;
                else {
                    s->indeg[j]++;
                    s->out_first[i + 1]++;
                }
            }
    }
}

static int before(const float *near, uint32_t a, uint32_t b)
{
    return near[a] < near[b] || (near[a] == near[b] && a < b);
}

static void heap_push(uint32_t *h, uint32_t *count, const float *near, uint32_t v)
{
    uint32_t k = (*count)++;
    while (k > 0 && before(near, v, h[(k - 1) / 2])) {
        h[k] = h[(k - 1) / 2];
        k = (k - 1) / 2;
    }
    h[k] = v;
}

static uint32_t heap_pop(uint32_t *h, uint32_t *count, const float *near)
{
    uint32_t top = h[0], v = h[--*count], k = 0;
    for (;;) {
        uint32_t c = 2 * k + 1;
        if (c >= *count)
            break;
        if (c + 1 < *count && before(near, h[c + 1], h[c]))
            c++;
        if (!before(near, h[c], v))
            break;
        h[k] = h[c];
        k = c;
    }
    if (*count)
        h[k] = v;
    return top;
}

static oit_status fit(oit_scheduler *s, size_t bins, size_t edges, oit_error *err)
{
    if (bins > s->bin_cap) {
        uint32_t *l = realloc(s->last, bins * sizeof *l);
        if (!l)
            return oit_error_set(err, OIT_ERR_NOMEM, "scheduling: cannot allocate %zu bins",
                                 bins);
        s->last = l;
        s->bin_cap = bins;
    }
    if (edges > s->edge_cap) {
        uint32_t *e = realloc(s->edges, edges * sizeof *e);
        if (!e)
            return oit_error_set(err, OIT_ERR_NOMEM, "scheduling: cannot allocate %zu "
                                 "constraints", edges);
        s->edges = e;
        s->edge_cap = edges;
    }
    return OIT_OK;
}

static oit_status build_graph(oit_scheduler *s, uint32_t n, const int (*rects)[4], int width,
                              int height, oit_error *err)
{
    if (width <= 0 || height <= 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "scheduling: screen %dx%d", width, height);
    if (n > s->max)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "scheduling: %u parts, more than the %u "
                             "it was made for", n, s->max);
    int nx = (width + BIN - 1) / BIN, ny = (height + BIN - 1) / BIN;
    size_t bins = (size_t)nx * ny;
    oit_status st = fit(s, bins, 0, err);
    if (st != OIT_OK)
        return st;
    memset(s->indeg, 0, (size_t)n * sizeof *s->indeg);
    memset(s->out_first, 0, ((size_t)n + 1) * sizeof *s->out_first);
    link_parts(s, n, rects, nx, ny, 0);
    for (uint32_t i = 0; i < n; i++)
        s->out_first[i + 1] += s->out_first[i];
    if ((st = fit(s, bins, s->out_first[n], err)) != OIT_OK)
        return st;
    memcpy(s->cursor, s->out_first, (size_t)n * sizeof *s->cursor);
    link_parts(s, n, rects, nx, ny, 1);
    return OIT_OK;
}

/* Emits part i and makes available the parts that waited only on it. */
static void emit(oit_scheduler *s, const float *near, uint32_t i, uint32_t *perm,
                 uint32_t *emitted, uint32_t *avail)
{
    if (perm)
        perm[*emitted] = i;
    (*emitted)++;
    for (uint32_t e = s->out_first[i]; e < s->out_first[i + 1]; e++)
        if (--s->indeg[s->edges[e]] == 0)
            heap_push(s->heap, avail, near, s->edges[e]);
}

oit_status oit_schedule_run(oit_scheduler *s, uint32_t n, const int (*rects)[4],
                            const float *near, int width, int height,
                            const oit_schedule_packer *packer, uint32_t *perm, oit_error *err)
{
    oit_status st = build_graph(s, n, rects, width, height, err);
    if (st != OIT_OK)
        return st;
    uint32_t avail = 0, emitted = 0, deferred = 0;
    for (uint32_t i = 0; i < n; i++)
        if (s->indeg[i] == 0)
            heap_push(s->heap, &avail, near, i);
    while (avail) {
        if (packer)
            packer->open(packer->ctx);
        uint32_t misses = 0;
        /* Fill the pack from the front of the wave; a part that does not fit
         * waits (in cursor[], free by now) for the next pack. After a run of
         * misses the pack is closed: the wave has moved on to where the pack
         * is full, and scanning further would cost more than a new pack. */
        while (avail && misses < OIT_SCHEDULE_MISSES) {
            uint32_t i = heap_pop(s->heap, &avail, near);
            if (!packer || packer->join(packer->ctx, i)) {
                emit(s, near, i, perm, &emitted, &avail);
                misses = 0;
            } else {
                s->cursor[deferred++] = i;
                misses++;
            }
        }
        for (uint32_t k = 0; k < deferred; k++)
            heap_push(s->heap, &avail, near, s->cursor[k]);
        deferred = 0;
    }
    /* Every edge points forward in the input, so the graph has no cycle and
     * everything is emitted; a shortfall means a broken rectangle. */
    if (emitted != n)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "scheduling: %u of %u parts emitted",
                             emitted, n);
    return OIT_OK;
}
