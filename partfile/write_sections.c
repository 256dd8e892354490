/* What finish writes after the part data (write_internal.h:
 * pf_write_sections): the management sections, each with its checksum and
 * padding, then the header and table at offset 0. Apart from write.c as the
 * file's layout, which docs/part-file.md specifies, not the writer's life. */
#include "oit/partfile.h"

#include "partfile/checksum.h"
#include "partfile/layout.h"
#include "partfile/write.h"
#include "partfile/write_internal.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

typedef struct section_out {
    pf_section *entry;
    uint32_t crc;
} section_out;

static oit_status put(oit_partfile_writer *w, section_out *so, const void *p, size_t n,
                      oit_error *err)
{
    so->crc = oit_crc32c(so->crc, p, n);
    so->entry->size += n;
    return pf_write_bytes(w, p, n, err);
}

static oit_status begin_section(oit_partfile_writer *w, pf_section *table, uint32_t type,
                                section_out *so, oit_error *err)
{
    oit_status s = pf_pad_to(w, PF_SECTION_ALIGN, NULL, err);
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
    oit_status s = pf_pad_to(w, PF_SECTION_ALIGN, &so->crc, err);
    so->entry->size += w->pos - start;
    so->entry->crc = so->crc;
    return s;
}

static oit_status write_meta(oit_partfile_writer *w, pf_section *table,
                             const oit_partfile_stats *st, oit_error *err)
{
    pf_meta m;
    memset(&m, 0, sizeof m);
    pf_bounds_reset(m.bounds_min, m.bounds_max);
    const oit_partfile_part *parts = w->parts.data;
    for (size_t i = 0; i < w->parts.count; i++) {
        pf_bounds_add(m.bounds_min, m.bounds_max, parts[i].bounds_min);
        pf_bounds_add(m.bounds_min, m.bounds_max, parts[i].bounds_max);
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
    oit_status s = pf_write_bytes(w, &h, sizeof h, err);
    if (!s)
        s = pf_write_bytes(w, table, PF_SECTION_COUNT * sizeof *table, err);
    return s;
}

oit_status pf_write_sections(oit_partfile_writer *w, const oit_partfile_stats *st, oit_error *err)
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
