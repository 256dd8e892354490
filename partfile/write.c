/* Part file writer (write.h; the format: docs/part-file.md).
 *
 * Part blobs are streamed to "<path>.tmp" as they are added, starting at the
 * first aligned offset after the header and section table; only records stay
 * in memory. finish appends the management sections, then writes the header
 * and table at offset 0, syncs, re-opens the file with the reader (so a
 * converter cannot emit a file that oitstream would refuse) and renames it.
 * Every byte written is computed (padding is zero), so the output depends on
 * nothing but the calls.
 */
#include "oit/mesh.h"
#include "oit/partfile.h"

#include "base/minmax.h"
#include "partfile/checksum.h"
#include "partfile/codec.h"
#include "partfile/layout.h"
#include "partfile/vertex_order.h"
#include "partfile/write.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct vec {
    void *data;
    size_t count, capacity;
} vec;

struct oit_partfile_writer {
    char *path, *tmp_path;
    FILE *file;
    uint32_t K, part_align, attributes;
    double origin[3];
    char *source_name, *options;
    bool skip_verify, have_grid, measured_bounds;
    oit_partfile_order order;
    uint64_t pos;        /* bytes written so far            */
    uint64_t data_start; /* PART_DATA offset                */
    uint32_t data_crc;   /* running CRC of PART_DATA        */
    uint64_t triangles;
    uint64_t sources_end; /* 1 + the largest source index written, 0 before */
    vec parts, pieces;
    vec grids;                 /* oit_partfile_grid, 0 = top   */
    vec top_cells, sub_cells;  /* oit_partfile_cell            */
    vec top_list, sub_list;    /* uint32_t                     */
    vec slabs, slab_list;
};

static const uint8_t zeros[4096];

static oit_status vec_push(vec *v, const void *items, size_t n, size_t size, oit_error *err)
{
    if (n > SIZE_MAX / size - v->count)
        return oit_error_set(err, OIT_ERR_NOMEM, "part file writer: array too large");
    if (v->count + n > v->capacity) {
        size_t cap = v->capacity ? v->capacity : 16;
        while (cap < v->count + n)
            cap = cap > SIZE_MAX / 2 / size ? v->count + n : cap * 2;
        void *p = realloc(v->data, cap * size);
        if (!p)
            return oit_error_set(err, OIT_ERR_NOMEM, "part file writer: out of memory");
        v->data = p;
        v->capacity = cap;
    }
    if (n == 0)
        return OIT_OK;
    if (items)
        memcpy((char *)v->data + v->count * size, items, n * size);
    else
        memset((char *)v->data + v->count * size, 0, n * size);
    v->count += n;
    return OIT_OK;
}

static char *dup_string(const char *s)
{
    size_t n = strlen(s ? s : "") + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s ? s : "", n);
    return d;
}

/* The tables, once written: freed before the written file is verified, so
 * that the verifying reader's copies do not come on top of them. */
static void free_tables(oit_partfile_writer *w)
{
    vec *vecs[] = {&w->parts,    &w->pieces,   &w->grids, &w->top_cells, &w->sub_cells,
                   &w->top_list, &w->sub_list, &w->slabs, &w->slab_list};
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++) {
        free(vecs[i]->data);
        *vecs[i] = (vec){0};
    }
}

static void writer_free(oit_partfile_writer *w)
{
    free_tables(w);
    free(w->path);
    free(w->tmp_path);
    free(w->source_name);
    free(w->options);
    free(w);
}

void oit_partfile_writer_abort(oit_partfile_writer *w)
{
    if (!w)
        return;
    if (w->file)
        fclose(w->file);
    remove(w->tmp_path);
    writer_free(w);
}

static oit_status write_bytes(oit_partfile_writer *w, const void *p, size_t n, oit_error *err)
{
    if (n && fwrite(p, 1, n, w->file) != n)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed at byte %llu: %s", w->tmp_path,
                             (unsigned long long)w->pos, strerror(errno));
    w->pos += n;
    return OIT_OK;
}

/* Zero-fills up to the next multiple of align; *crc (if any) covers it. */
static oit_status pad_to(oit_partfile_writer *w, uint64_t align, uint32_t *crc, oit_error *err)
{
    uint64_t gap = pf_align_up(w->pos, align) - w->pos;
    while (gap > 0) {
        size_t n = gap < sizeof zeros ? (size_t)gap : sizeof zeros;
        oit_status s = write_bytes(w, zeros, n, err);
        if (s)
            return s;
        if (crc)
            *crc = oit_crc32c(*crc, zeros, n);
        gap -= n;
    }
    return OIT_OK;
}

static bool is_pow2(uint32_t x) { return x && !(x & (x - 1)); }

oit_status oit_partfile_writer_create(const char *path, const oit_partfile_writer_desc *desc,
                                      oit_partfile_writer **out, oit_error *err)
{
    oit_partfile_writer_desc d = desc ? *desc : (oit_partfile_writer_desc){0};
    *out = NULL;
    d.K = d.K ? d.K : 8;
    d.part_align = d.part_align ? d.part_align : 4096;
    if (d.K < 2 || d.K > PF_K_MAX || d.K % 2)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: K %u is not an even number in 2..%u",
                             path, d.K, PF_K_MAX);
    if (!is_pow2(d.part_align) || d.part_align < PF_ALIGN_MIN || d.part_align > PF_ALIGN_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: part alignment %u is not a power of two in %u..%u", path,
                             d.part_align, PF_ALIGN_MIN, PF_ALIGN_MAX);
    if (d.attributes & ~(uint32_t)(OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: unknown attribute bits 0x%x", path,
                             d.attributes);
    if (!isfinite(d.origin[0]) || !isfinite(d.origin[1]) || !isfinite(d.origin[2]))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: origin is not finite", path);
    oit_partfile_writer *w = calloc(1, sizeof *w);
    if (!w)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", path);
    w->K = d.K;
    w->part_align = d.part_align;
    w->attributes = d.attributes;
    memcpy(w->origin, d.origin, sizeof w->origin);
    w->skip_verify = d.skip_verify;
    w->measured_bounds = d.measured_bounds;
    w->order = d.order;
    w->path = dup_string(path);
    w->tmp_path = malloc(strlen(path) + 5);
    w->source_name = dup_string(d.source_name);
    w->options = dup_string(d.options);
    if (!w->path || !w->tmp_path || !w->source_name || !w->options) {
        writer_free(w);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", path);
    }
    snprintf(w->tmp_path, strlen(path) + 5, "%s.tmp", path);
    w->file = fopen(w->tmp_path, "wb");
    if (!w->file) {
        oit_error_set(err, OIT_ERR_IO, "%s: cannot create: %s", w->tmp_path, strerror(errno));
        writer_free(w);
        return OIT_ERR_IO;
    }
    /* Header and table are written last; reserve them, then align the data. */
    oit_status s = OIT_OK;
    if (fseeko(w->file, PF_TABLE_END, SEEK_SET) != 0)
        s = oit_error_set(err, OIT_ERR_IO, "%s: seek failed: %s", w->tmp_path, strerror(errno));
    w->pos = PF_TABLE_END;
    if (!s)
        s = pad_to(w, w->part_align, NULL, err);
    if (s) {
        oit_partfile_writer_abort(w);
        return s;
    }
    w->data_start = w->pos;
    *out = w;
    return OIT_OK;
}

/* ---- parts ---------------------------------------------------------------- */

static oit_status check_part(const oit_partfile_writer *w, const oit_partfile_part_desc *p,
                             oit_error *err)
{
    uint32_t n = (uint32_t)w->parts.count;
    if (!p->positions || !p->vertex_count || !p->indices || !p->index_count ||
        p->index_count % 3 || !p->sources || !p->pieces || !p->piece_count)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: part %u: needs vertices, a multiple of 3 indices, their "
                             "triangles' source indices and pieces", w->path, n);
    if (p->attributes & ~(uint32_t)(OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part %u: unknown attribute bits 0x%x",
                             w->path, n, p->attributes);
    uint64_t tris = 0;
    for (uint32_t i = 0; i < p->piece_count; i++) {
        if (!p->pieces[i].triangle_count || !p->pieces[i].plane_count)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: part %u: piece %u has no triangles or no planes", w->path,
                                 n, i);
        tris += p->pieces[i].triangle_count;
    }
    if (tris != p->index_count / 3)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: part %u: pieces cover %llu triangles, the part has %llu",
                             w->path, n, (unsigned long long)tris,
                             (unsigned long long)(p->index_count / 3));
    for (uint64_t i = 0; i < p->index_count; i++)
        if (p->indices[i] >= p->vertex_count)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: part %u: index %u >= %u vertices", w->path, n,
                                 p->indices[i], p->vertex_count);
    for (uint64_t i = 0; i < (uint64_t)p->vertex_count * 3; i++)
        if (!isfinite(p->positions[i]))
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: part %u: vertex %llu is not finite", w->path, n,
                                 (unsigned long long)(i / 3));
    return OIT_OK;
}

static void bounds_reset(float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
}

static void bounds_add(float lo[3], float hi[3], const float *p)
{
    for (int k = 0; k < 3; k++) {
        lo[k] = oit_min_f(lo[k], p[k]);
        hi[k] = oit_max_f(hi[k], p[k]);
    }
}

/* Lays out vertices, zero pad to 4, indices, zero pad to 4, source indices:
 * the blob as the reader decodes it. */
static uint8_t *build_blob(const oit_partfile_part_desc *p, oit_partfile_part *rec)
{
    uint32_t stride = pf_vertex_stride(rec->attributes);
    uint8_t *blob = calloc(1, rec->data_bytes ? rec->data_bytes : 1);
    if (!blob)
        return NULL;
    for (uint32_t i = 0; i < p->vertex_count; i++) {
        memcpy(blob + (size_t)i * stride, p->positions + (size_t)i * 3, 12);
        if (rec->attributes)
            memcpy(blob + (size_t)i * stride + 12, p->rgba + (size_t)i * 4, 4);
    }
    uint8_t *idx = blob + rec->index_offset;
    for (uint64_t i = 0; i < p->index_count; i++) {
        if (rec->index_bits == 16) {
            uint16_t v = (uint16_t)p->indices[i];
            memcpy(idx + i * 2, &v, 2);
        } else {
            memcpy(idx + i * 4, &p->indices[i], 4);
        }
    }
    memcpy(blob + oit_partfile_source_offset(rec), p->sources, p->index_count / 3 * 4);
    return blob;
}

/* The part's stored streams (codec.h); sets the record's stored
 * sizes. NULL when out of memory. */
static uint8_t *encode_blob(const oit_partfile_part_desc *p, oit_partfile_part *rec)
{
    uint8_t *blob = build_blob(p, rec);
    uint32_t stride = pf_vertex_stride(rec->attributes);
    size_t cap = pf_encode_bound(p->vertex_count, stride, p->index_count);
    uint8_t *out = blob ? malloc(cap) : NULL;
    pf_codec_sizes z;
    if (out && pf_encode_part(blob, p->vertex_count, stride, p->indices, p->index_count,
                              p->sources, out, cap, &z)) {
        free(out);
        out = NULL;
    }
    free(blob);
    if (!out)
        return NULL;
    rec->stored_vertex_bytes = z.vertex_bytes;
    rec->stored_index_bytes = z.index_bytes;
    rec->stored_source_bytes = z.source_bytes;
    rec->stored_bytes = z.vertex_bytes + z.index_bytes + z.source_bytes;
    return out;
}

static oit_partfile_part part_record(const oit_partfile_writer *w, const oit_partfile_part_desc *p)
{
    oit_partfile_part r;
    memset(&r, 0, sizeof r);
    r.attributes = p->rgba ? (p->attributes ? p->attributes : OIT_ATTR_COLOUR | OIT_ATTR_ALPHA) : 0;
    uint32_t max_layers = p->piece_count > w->K / 2 ? w->K : 2 * p->piece_count;
    r.layer_bound = p->layer_bound ? p->layer_bound : max_layers;
    r.piece_first = (uint32_t)w->pieces.count;
    r.piece_count = p->piece_count;
    r.index_bits = p->vertex_count <= PF_INDEX16_MAX_VERTICES ? 16 : 32;
    r.vertex_count = p->vertex_count;
    r.index_count = p->index_count;
    r.vertex_bytes = (uint64_t)p->vertex_count * pf_vertex_stride(r.attributes);
    r.index_offset = pf_align_up(r.vertex_bytes, 4);
    r.index_bytes = p->index_count * (r.index_bits / 8);
    r.data_bytes = oit_partfile_source_offset(&r) + p->index_count / 3 * 4;
    bounds_reset(r.bounds_min, r.bounds_max);
    for (uint32_t i = 0; i < p->vertex_count; i++)
        bounds_add(r.bounds_min, r.bounds_max, p->positions + (size_t)i * 3);
    return r;
}

static oit_status add_pieces(oit_partfile_writer *w, const oit_partfile_part_desc *p,
                             uint32_t part, oit_error *err)
{
    uint64_t first = 0;
    for (uint32_t i = 0; i < p->piece_count; i++) {
        oit_partfile_piece pc;
        memset(&pc, 0, sizeof pc);
        pc.part = part;
        pc.plane_count = p->pieces[i].plane_count;
        pc.triangle_first = first;
        pc.triangle_count = p->pieces[i].triangle_count;
        bounds_reset(pc.bounds_min, pc.bounds_max);
        for (uint64_t t = first * 3; t < (first + pc.triangle_count) * 3; t++)
            bounds_add(pc.bounds_min, pc.bounds_max, p->positions + (size_t)p->indices[t] * 3);
        first += pc.triangle_count;
        oit_status s = vec_push(&w->pieces, &pc, 1, sizeof pc, err);
        if (s)
            return s;
    }
    return OIT_OK;
}

oit_status oit_partfile_writer_add_part(oit_partfile_writer *w, const oit_partfile_part_desc *p,
                                        uint32_t *index, oit_error *err)
{
    if (w->parts.count >= UINT32_MAX || w->pieces.count + p->piece_count >= UINT32_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: too many parts or pieces", w->path);
    oit_status s = check_part(w, p, err);
    if (s)
        return s;
    uint32_t n = (uint32_t)w->parts.count;
    pf_ordered ord = {0};
    oit_partfile_part_desc q = *p;
    if (w->order != OIT_PARTFILE_ORDER_KEEP) {
        if (pf_cache_order(p, w->order == OIT_PARTFILE_ORDER_CACHE, &ord))
            return oit_error_set(err, OIT_ERR_NOMEM, "%s: part %u: vertex-cache order failed "
                                 "(out of memory, or the optimiser changed a triangle)",
                                 w->path, n);
        q.positions = ord.positions;
        q.rgba = ord.rgba;
        q.indices = ord.indices;
        q.sources = ord.sources;
    }
    p = &q;
    oit_partfile_part rec = part_record(w, p);
    uint8_t *blob = encode_blob(p, &rec);
    if (!blob) {
        pf_ordered_free(&ord);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: part %u: out of memory for %llu bytes",
                             w->path, n, (unsigned long long)rec.data_bytes);
    }
    s = pad_to(w, w->part_align, &w->data_crc, err);
    rec.data_offset = w->pos;
    rec.data_crc = oit_crc32c(0, blob, rec.stored_bytes);
    if (!s)
        s = write_bytes(w, blob, rec.stored_bytes, err);
    if (!s)
        w->data_crc = oit_crc32c(w->data_crc, blob, rec.stored_bytes);
    free(blob);
    if (!s)
        s = add_pieces(w, p, n, err);
    for (uint64_t t = 0; !s && t < p->index_count / 3; t++)
        if (p->sources[t] >= w->sources_end)
            w->sources_end = (uint64_t)p->sources[t] + 1;
    if (!s)
        s = vec_push(&w->parts, &rec, 1, sizeof rec, err);
    pf_ordered_free(&ord);
    if (s)
        return s;
    w->triangles += q.index_count / 3;
    if (index)
        *index = n;
    return OIT_OK;
}

/* ---- grids and slabs ------------------------------------------------------ */

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
    oit_status s = vec_push(cv, NULL, cells, sizeof(oit_partfile_cell), err);
    uint64_t list_first = lv->count;
    for (uint64_t c = 0; !s && c < cells; c++) {
        oit_partfile_cell *cell = (oit_partfile_cell *)cv->data + cell0 + c;
        cell->list_first = list_first;
        cell->list_count = g->cell_counts[c];
        list_first += cell->list_count;
    }
    if (!s)
        s = vec_push(lv, g->cell_parts, list_total, sizeof(uint32_t), err);
    if (!s)
        s = vec_push(&w->grids, &rec, 1, sizeof rec, err);
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
    oit_status s = vec_push(&w->slab_list, sd->inside, sd->inside_count, sizeof(uint32_t), err);
    if (!s)
        s = vec_push(&w->slabs, &rec, 1, sizeof rec, err);
    if (s)
        return s;
    cell->slab = n + 1;
    if (slab)
        *slab = n;
    return OIT_OK;
}

/* ---- finish ----------------------------------------------------------------- */

typedef struct section_out {
    pf_section *entry;
    uint32_t crc;
} section_out;

static oit_status put(oit_partfile_writer *w, section_out *so, const void *p, size_t n,
                      oit_error *err)
{
    so->crc = oit_crc32c(so->crc, p, n);
    so->entry->size += n;
    return write_bytes(w, p, n, err);
}

static oit_status begin_section(oit_partfile_writer *w, pf_section *table, uint32_t type,
                                section_out *so, oit_error *err)
{
    oit_status s = pad_to(w, PF_SECTION_ALIGN, NULL, err);
    so->entry = &table[type - 1];
    so->entry->type = type;
    so->entry->offset = w->pos;
    so->entry->size = 0;
    so->crc = 0;
    return s;
}

static oit_status end_section(oit_partfile_writer *w, section_out *so, oit_error *err)
{
    uint64_t start = w->pos;
    oit_status s = pad_to(w, PF_SECTION_ALIGN, &so->crc, err);
    so->entry->size += w->pos - start;
    so->entry->crc = so->crc;
    return s;
}

static oit_status write_meta(oit_partfile_writer *w, pf_section *table,
                             const oit_partfile_stats *st, oit_error *err)
{
    pf_meta m;
    memset(&m, 0, sizeof m);
    bounds_reset(m.bounds_min, m.bounds_max);
    const oit_partfile_part *parts = w->parts.data;
    for (size_t i = 0; i < w->parts.count; i++) {
        bounds_add(m.bounds_min, m.bounds_max, parts[i].bounds_min);
        bounds_add(m.bounds_min, m.bounds_max, parts[i].bounds_max);
    }
    if (!w->parts.count)
        memset(m.bounds_min, 0, sizeof m.bounds_min * 2);
    m.attributes = w->attributes;
    for (size_t i = 0; i < w->parts.count; i++)
        m.attributes |= parts[i].attributes;
    m.triangles_in = st->triangles_in;
    m.triangles_dropped = st->triangles_dropped;
    m.triangles_split = st->triangles_split;
    m.source_name_bytes = (uint32_t)strlen(w->source_name);
    m.options_bytes = (uint32_t)strlen(w->options);
    section_out so;
    oit_status s = begin_section(w, table, PF_SEC_META, &so, err);
    if (!s)
        s = put(w, &so, &m, sizeof m, err);
    if (!s)
        s = put(w, &so, w->origin, sizeof w->origin, err);
    if (!s)
        s = put(w, &so, w->source_name, m.source_name_bytes, err);
    if (!s)
        s = put(w, &so, w->options, m.options_bytes, err);
    /* META's size is exact (no padding): the strings' lengths define it. */
    so.entry->crc = so.crc;
    return s;
}

/* A piece of a section's bytes. */
typedef struct chunk {
    const void *data;
    size_t bytes;
} chunk;

/* Section 'type' of the n chunks in order (those of 0 bytes add nothing),
 * padded to PF_SECTION_ALIGN. */
static oit_status write_section(oit_partfile_writer *w, pf_section *table, uint32_t type,
                                const chunk *c, int n, oit_error *err)
{
    section_out so;
    oit_status s = begin_section(w, table, type, &so, err);
    for (int i = 0; i < n && !s; i++)
        if (c[i].bytes)
            s = put(w, &so, c[i].data, c[i].bytes, err);
    if (!s)
        s = end_section(w, &so, err);
    return s;
}

static oit_status write_array(oit_partfile_writer *w, pf_section *table, uint32_t type,
                              const vec *v, size_t size, oit_error *err)
{
    return write_section(w, table, type, &(chunk){v->data, v->count * size}, 1, err);
}

static oit_status write_grids(oit_partfile_writer *w, pf_section *table, bool top, oit_error *err)
{
    const oit_partfile_grid *grids = w->grids.data;
    size_t first = top ? 0 : 1, count = top ? 1 : w->grids.count - 1;
    const vec *cells = top ? &w->top_cells : &w->sub_cells;
    const vec *list = top ? &w->top_list : &w->sub_list;
    pf_grid_block b;
    memset(&b, 0, sizeof b);
    b.grid_count = (uint32_t)count;
    b.cell_count = cells->count;
    b.list_count = list->count;
    const chunk c[] = {{&b, sizeof b},
                       {grids + first, count * sizeof *grids},
                       {cells->data, cells->count * sizeof(oit_partfile_cell)},
                       {list->data, list->count * sizeof(uint32_t)}};
    return write_section(w, table, top ? PF_SEC_GRID : PF_SEC_SUBGRIDS, c, 4, err);
}

static oit_status write_slabs(oit_partfile_writer *w, pf_section *table, oit_error *err)
{
    pf_slab_block b;
    memset(&b, 0, sizeof b);
    b.slab_count = (uint32_t)w->slabs.count;
    b.list_count = w->slab_list.count;
    const chunk c[] = {{&b, sizeof b},
                       {w->slabs.data, w->slabs.count * sizeof(oit_partfile_slab)},
                       {w->slab_list.data, w->slab_list.count * sizeof(uint32_t)}};
    return write_section(w, table, PF_SEC_SLABS, c, 3, err);
}

static oit_status write_header(oit_partfile_writer *w, pf_section *table, oit_error *err)
{
    pf_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, PF_MAGIC, sizeof h.magic);
    h.version = OIT_PARTFILE_VERSION;
    h.flags = w->measured_bounds ? OIT_PARTFILE_FLAG_MEASURED_BOUNDS : 0;
    h.header_bytes = PF_HEADER_BYTES;
    h.section_count = PF_SECTION_COUNT;
    h.K = w->K;
    h.part_align = w->part_align;
    h.file_bytes = w->pos;
    h.part_count = w->parts.count;
    h.triangle_count = w->triangles;
    h.table_crc = oit_crc32c(oit_crc32c(0, &h, offsetof(pf_header, table_crc)), table,
                             PF_SECTION_COUNT * sizeof *table);
    if (fseeko(w->file, 0, SEEK_SET) != 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: seek failed: %s", w->tmp_path, strerror(errno));
    w->pos = 0;
    oit_status s = write_bytes(w, &h, sizeof h, err);
    if (!s)
        s = write_bytes(w, table, PF_SECTION_COUNT * sizeof *table, err);
    return s;
}

static oit_status write_all(oit_partfile_writer *w, const oit_partfile_stats *st, oit_error *err)
{
    pf_section table[PF_SECTION_COUNT];
    memset(table, 0, sizeof table);
    table[PF_SEC_PART_DATA - 1] = (pf_section){.type = PF_SEC_PART_DATA,
                                               .offset = w->data_start,
                                               .size = w->pos - w->data_start,
                                               .crc = w->data_crc};
    oit_status s = write_meta(w, table, st, err);
    if (!s)
        s = write_array(w, table, PF_SEC_PARTS, &w->parts, sizeof(oit_partfile_part), err);
    if (!s)
        s = write_array(w, table, PF_SEC_PIECES, &w->pieces, sizeof(oit_partfile_piece), err);
    if (!s)
        s = write_grids(w, table, true, err);
    if (!s)
        s = write_grids(w, table, false, err);
    if (!s)
        s = write_slabs(w, table, err);
    if (!s)
        s = write_header(w, table, err);
    if (!s && (fflush(w->file) != 0 || fsync(fileno(w->file)) != 0))
        s = oit_error_set(err, OIT_ERR_IO, "%s: flush failed: %s", w->tmp_path, strerror(errno));
    return s;
}

/* A file the reader refuses means the caller's structures were inconsistent. */
static oit_status verify(oit_partfile_writer *w, oit_error *err)
{
    oit_partfile *pf = NULL;
    oit_status s = oit_partfile_open(w->tmp_path, NULL, &pf, err);
    oit_partfile_close(pf);
    if (s == OIT_ERR_FORMAT) {
        oit_error_prefix(err, "written file does not validate");
        oit_error_prefix(err, w->path);
        if (err)
            err->status = OIT_ERR_ARGUMENT;
        s = OIT_ERR_ARGUMENT;
    }
    return s;
}

oit_status oit_partfile_writer_finish(oit_partfile_writer *w, const oit_partfile_stats *stats,
                                      oit_error *err)
{
    oit_partfile_stats st = stats ? *stats : (oit_partfile_stats){w->triangles, 0, 0};
    oit_status s = OIT_OK;
    if (!w->have_grid)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "%s: no grid was set", w->path);
    else if (w->sources_end > st.triangles_in)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "%s: source index %llu >= %llu source "
                          "triangles (triangles_in)", w->path,
                          (unsigned long long)(w->sources_end - 1),
                          (unsigned long long)st.triangles_in);
    if (!s)
        s = write_all(w, &st, err);
    if (fclose(w->file) != 0 && !s)
        s = oit_error_set(err, OIT_ERR_IO, "%s: close failed: %s", w->tmp_path, strerror(errno));
    w->file = NULL;
    free_tables(w);
    if (!s && !w->skip_verify)
        s = verify(w, err);
    if (!s && rename(w->tmp_path, w->path) != 0)
        s = oit_error_set(err, OIT_ERR_IO, "%s: cannot rename to %s: %s", w->tmp_path, w->path,
                          strerror(errno));
    if (s)
        remove(w->tmp_path);
    writer_free(w);
    return s;
}
