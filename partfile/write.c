/* Part file writer (write.h; the format: docs/part-file.md).
 *
 * Part blobs are streamed to "<path>.tmp" as they are added, starting at the
 * first aligned offset after the header and section table; only records stay
 * in memory. finish appends the management sections, then writes the header
 * and table at offset 0, syncs, re-opens the file with the reader (so a
 * converter cannot emit a file that oitstream would refuse) and renames it.
 * Every byte written is computed (padding is zero), so the output depends on
 * nothing but the calls.
 * This file holds the writer's life (create, abort, finish) and its byte
 * output; parts are added in write_part.c, grids and slabs in write_grid.c,
 * and finish's sections are laid out in write_sections.c.
 */
#include "oit/mesh.h"
#include "oit/partfile.h"

#include "partfile/checksum.h"
#include "partfile/layout.h"
#include "partfile/write.h"
#include "partfile/write_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const uint8_t zeros[4096];

oit_status pf_vec_push(vec *v, const void *items, size_t n, size_t size, oit_error *err)
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

oit_status pf_write_bytes(oit_partfile_writer *w, const void *p, size_t n, oit_error *err)
{
    if (n && fwrite(p, 1, n, w->file) != n)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed at byte %llu: %s", w->tmp_path,
                             (unsigned long long)w->pos, strerror(errno));
    w->pos += n;
    return OIT_OK;
}

oit_status pf_pad_to(oit_partfile_writer *w, uint64_t align, uint32_t *crc, oit_error *err)
{
    uint64_t gap = pf_align_up(w->pos, align) - w->pos;
    while (gap > 0) {
        size_t n = gap < sizeof zeros ? (size_t)gap : sizeof zeros;
        oit_status s = pf_write_bytes(w, zeros, n, err);
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
        s = pf_pad_to(w, w->part_align, NULL, err);
    if (s) {
        oit_partfile_writer_abort(w);
        return s;
    }
    w->data_start = w->pos;
    *out = w;
    return OIT_OK;
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
        s = pf_write_sections(w, &st, err);
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
