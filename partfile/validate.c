/* The part file's checks (handle.h): nothing in the file is trusted.
 *
 * Open checks the header, the section table, every checksum and every
 * record and cross-reference, in that order, so a later check may rely on
 * the earlier ones (e.g. a part's blob range is known to lie inside
 * PART_DATA before its bytes are read). Management sections are copied into
 * aligned host arrays, which also keeps later changes to the file from
 * reaching validated records; part streams are decoded into the caller's
 * buffer (version 5, partfile/codec.h) and every decoded value is checked
 * before a part is first handed out.
 * Sizes are compared by division or after bounding each count by the section
 * size, so no product or sum below can wrap.
 */
/* Dependencies point down: read.c uses this file and part_blob.c; this file
 * uses part_blob.c (each part's blob at open) and handle.c, never read.c. */
/* madvise (pf_drop_checked) is not POSIX. */
#define _DEFAULT_SOURCE
#include "partfile/handle.h"
#include "partfile/validate_internal.h"

#include "oit/mesh.h"

#include "partfile/checksum.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

static bool box_inside(const float lo[3], const float hi[3], const float olo[3], const float ohi[3])
{
    for (int k = 0; k < 3; k++)
        if (lo[k] < olo[k] || hi[k] > ohi[k])
            return false;
    return true;
}

/* ---- header, table, checksums ------------------------------------------ */

static oit_status check_header(oit_partfile *pf, oit_error *err)
{
    if (pf->size == 0)
        return pf_bad(pf, err, "empty file, not a part file");
    if (pf->size < PF_HEADER_BYTES)
        return pf_bad(pf, err, "file is %zu bytes, shorter than the %u-byte header", pf->size,
                      PF_HEADER_BYTES);
    memcpy(&pf->hdr, pf->base, sizeof pf->hdr);
    const pf_header *h = &pf->hdr;
    if (memcmp(h->magic, PF_MAGIC, sizeof h->magic) != 0)
        return pf_bad(pf, err, "not a part file (no OITPART magic)");
    if (h->version >= 1 && h->version < 4)
        return pf_bad(pf, err, "part file version %u has no source triangle indices, which this "
                      "build needs (it reads version %u): convert the model again with oitprep",
                      h->version, OIT_PARTFILE_VERSION);
    if (h->version == 4)
        return pf_bad(pf, err, "part file version 4 stores its parts unencoded, this build reads "
                      "version %u (encoded parts): convert the model again with oitprep",
                      OIT_PARTFILE_VERSION);
    if (h->version != OIT_PARTFILE_VERSION)
        return pf_bad(pf, err, "part file version %u, this build reads version %u", h->version,
                      OIT_PARTFILE_VERSION);
    uint32_t known = OIT_PARTFILE_FLAG_MEASURED_BOUNDS;
    if ((h->flags & ~known) || h->reserved || h->header_bytes != PF_HEADER_BYTES ||
        h->section_count != PF_SECTION_COUNT)
        return pf_bad(pf, err, "header: flags 0x%x, header size %u, %u sections: expected flags "
                      "within 0x%x, %u, %u", h->flags, h->header_bytes, h->section_count, known,
                      PF_HEADER_BYTES, PF_SECTION_COUNT);
    if (h->K < 2 || h->K > PF_K_MAX || h->K % 2)
        return pf_bad(pf, err, "header: K %u is not an even number in 2..%u", h->K, PF_K_MAX);
    if (h->part_align < PF_ALIGN_MIN || h->part_align > PF_ALIGN_MAX ||
        (h->part_align & (h->part_align - 1)))
        return pf_bad(pf, err, "header: part alignment %u is not a power of two in %u..%u",
                      h->part_align, PF_ALIGN_MIN, PF_ALIGN_MAX);
    if (h->file_bytes != pf->size)
        return pf_bad(pf, err, "file is %zu bytes, its header says %llu (truncated or appended to)",
                      pf->size, (unsigned long long)h->file_bytes);
    if (pf->size < PF_TABLE_END)
        return pf_bad(pf, err, "file is %zu bytes, shorter than header and section table (%u)",
                      pf->size, PF_TABLE_END);
    memcpy(pf->sec, pf->base + PF_HEADER_BYTES, sizeof pf->sec);
    uint32_t crc = oit_crc32c(oit_crc32c(0, pf->base, offsetof(pf_header, table_crc)),
                              pf->base + PF_HEADER_BYTES, sizeof pf->sec);
    if (crc != h->table_crc)
        return pf_bad(pf, err, "header: checksum 0x%08x, stored 0x%08x (corrupt header or table)",
                      crc, h->table_crc);
    return OIT_OK;
}

static oit_status check_entry(const oit_partfile *pf, uint32_t i, oit_error *err)
{
    const pf_section *s = &pf->sec[i];
    if (s->type != i + 1 || s->flags || s->reserved)
        return pf_bad(pf, err, "section table: entry %u: type %u flags 0x%x: expected type %u "
                      "(%s), no flags", i, s->type, s->flags, i + 1, pf_section_name(i + 1));
    uint64_t align = s->type == PF_SEC_PART_DATA ? pf->hdr.part_align : PF_SECTION_ALIGN;
    const char *name = pf_section_name(s->type);
    if (s->offset % align)
        return pf_bad(pf, err, "section %s: offset %llu is not a multiple of %llu", name,
                      (unsigned long long)s->offset, (unsigned long long)align);
    if (s->offset < PF_TABLE_END || s->offset > pf->size || s->size > pf->size - s->offset)
        return pf_bad(pf, err, "section %s: bytes %llu..+%llu lie outside the file's data "
                      "(%u..%zu)", name, (unsigned long long)s->offset,
                      (unsigned long long)s->size, PF_TABLE_END, pf->size);
    return OIT_OK;
}

static oit_status check_table(const oit_partfile *pf, oit_error *err)
{
    for (uint32_t i = 0; i < PF_SECTION_COUNT; i++) {
        oit_status s = check_entry(pf, i, err);
        if (s)
            return s;
    }
    for (uint32_t i = 0; i < PF_SECTION_COUNT; i++)
        for (uint32_t j = i + 1; j < PF_SECTION_COUNT; j++) {
            const pf_section *a = &pf->sec[i], *b = &pf->sec[j];
            if (a->size && b->size && a->offset < b->offset + b->size &&
                b->offset < a->offset + a->size)
                return pf_bad(pf, err, "sections %s and %s overlap", pf_section_name(a->type),
                              pf_section_name(b->type));
        }
    return OIT_OK;
}

/* Bytes of mapped part data checked between drops (pf_drop_checked). */
#define PF_DROP_CHUNK ((size_t)64 << 20)

/* A mapped file's pages that were read only to be checked are dropped from
 * the process once checked: validating a file of many GB must not hold it
 * resident (oitprep's peak RSS would be the file). They stay in the page
 * cache and fault back in when read. Harmless beyond the range: the mapping
 * is private and read-only, so a dropped page is only ever re-read. */
void pf_drop_checked(const oit_partfile *pf, const uint8_t *from, size_t n)
{
    long page = sysconf(_SC_PAGESIZE);
    if (!pf->map || n == 0 || page <= 0)
        return;
    uintptr_t a = (uintptr_t)from / (uintptr_t)page * (uintptr_t)page;
    uintptr_t b = (uintptr_t)(from + n);
    madvise((void *)a, b - a, MADV_DONTNEED);
}

static uint32_t data_checksum(const oit_partfile *pf, const uint8_t *p, uint64_t n)
{
    uint32_t crc = 0;
    for (uint64_t at = 0; at < n; at += PF_DROP_CHUNK) {
        size_t k = n - at < PF_DROP_CHUNK ? (size_t)(n - at) : PF_DROP_CHUNK;
        crc = oit_crc32c(crc, p + at, k);
        pf_drop_checked(pf, p + at, k);
    }
    return crc;
}

static oit_status check_checksums(const oit_partfile *pf, bool with_data, oit_error *err)
{
    for (uint32_t t = 1; t <= PF_SECTION_COUNT; t++) {
        if (t == PF_SEC_PART_DATA && !with_data)
            continue; /* each part's own checksum covers it when it is validated */
        uint32_t crc = t == PF_SEC_PART_DATA
                           ? data_checksum(pf, pf_sec_data(pf, t), pf_sec_size(pf, t))
                           : oit_crc32c(0, pf_sec_data(pf, t), pf_sec_size(pf, t));
        if (crc != pf->sec[t - 1].crc)
            return pf_bad(pf, err, "section %s: checksum 0x%08x, stored 0x%08x (corrupt)",
                          pf_section_name(t), crc, pf->sec[t - 1].crc);
    }
    return OIT_OK;
}

/* ---- META --------------------------------------------------------------- */

static char *copy_string(const uint8_t *p, uint32_t n)
{
    char *s = malloc((size_t)n + 1);
    if (s) {
        memcpy(s, p, n);
        s[n] = 0;
    }
    return s;
}

static oit_status load_meta(oit_partfile *pf, oit_error *err)
{
    uint64_t size = pf_sec_size(pf, PF_SEC_META);
    if (size < sizeof pf->meta)
        return pf_bad(pf, err, "section META: %llu bytes, shorter than its %zu-byte record",
                      (unsigned long long)size, sizeof pf->meta);
    memcpy(&pf->meta, pf_sec_data(pf, PF_SEC_META), sizeof pf->meta);
    const pf_meta *m = &pf->meta;
    uint64_t head = sizeof *m + sizeof pf->origin;
    if (size != head + (uint64_t)m->source_name_bytes + m->options_bytes)
        return pf_bad(pf, err, "section META: %llu bytes, its record says %llu",
                      (unsigned long long)size,
                      (unsigned long long)(head + (uint64_t)m->source_name_bytes +
                                           m->options_bytes));
    if (m->reserved || (m->attributes & ~(uint32_t)(OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE)))
        return pf_bad(pf, err, "section META: unknown attribute bits 0x%x", m->attributes);
    if (!pf_box_ok(m->bounds_min, m->bounds_max))
        return pf_bad(pf, err, "section META: scene bounds are not finite or min > max");
    memcpy(pf->origin, pf_sec_data(pf, PF_SEC_META) + sizeof *m, head - sizeof *m);
    for (int k = 0; k < 3; k++)
        if (!isfinite(pf->origin[k]))
            return pf_bad(pf, err, "section META: origin is not finite");
    const uint8_t *text = pf_sec_data(pf, PF_SEC_META) + head;
    pf->source_name = copy_string(text, m->source_name_bytes);
    pf->options = copy_string(text + m->source_name_bytes, m->options_bytes);
    if (!pf->source_name || !pf->options)
        return pf_nomem(pf, err);
    if (strlen(pf->source_name) != m->source_name_bytes ||
        strlen(pf->options) != m->options_bytes)
        return pf_bad(pf, err, "section META: source name or options contain a NUL byte");
    return OIT_OK;
}

/* ---- PARTS and PIECES ----------------------------------------------------- */

static oit_status load_records(oit_partfile *pf, uint32_t type, size_t record, void **out,
                               uint64_t *count, oit_error *err)
{
    uint64_t size = pf_sec_size(pf, type);
    if (size % record)
        return pf_bad(pf, err, "section %s: %llu bytes is not a whole number of %zu-byte records",
                      pf_section_name(type), (unsigned long long)size, record);
    *count = size / record;
    *out = pf_copy_out(pf_sec_data(pf, type), *count, record);
    return *out ? OIT_OK : pf_nomem(pf, err);
}

static oit_status load_parts(oit_partfile *pf, oit_error *err)
{
    uint64_t n = 0;
    oit_status s = load_records(pf, PF_SEC_PARTS, sizeof(oit_partfile_part), (void **)&pf->parts,
                                &n, err);
    if (s)
        return s;
    if (n != pf->hdr.part_count)
        return pf_bad(pf, err, "section PARTS: holds %llu records, the header claims %llu parts",
                      (unsigned long long)n, (unsigned long long)pf->hdr.part_count);
    if (n > UINT32_MAX - 1)
        return pf_bad(pf, err, "section PARTS: %llu parts, at most %u allowed",
                      (unsigned long long)n, UINT32_MAX - 1);
    return load_records(pf, PF_SEC_PIECES, sizeof(oit_partfile_piece), (void **)&pf->pieces,
                        &pf->piece_count, err);
}

/* Fields that do not depend on the PART_DATA layout. */
static oit_status check_part_fields(const oit_partfile *pf, uint32_t i, oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    /* Measured bounds are not sums over pieces: only the file's limit holds. */
    uint32_t max_layers = 2 * p->piece_count < OIT_PARTFILE_MAX_LAYERS &&
                                  !(pf->hdr.flags & OIT_PARTFILE_FLAG_MEASURED_BOUNDS)
                              ? 2 * p->piece_count
                              : OIT_PARTFILE_MAX_LAYERS;
    if (p->reserved || !pf_box_ok(p->bounds_min, p->bounds_max))
        return pf_bad(pf, err, "section PARTS: record %u: bounds not finite or min > max", i);
    if (p->attributes & ~pf->meta.attributes)
        return pf_bad(pf, err, "section PARTS: record %u: attributes 0x%x, the file has 0x%x", i,
                      p->attributes, pf->meta.attributes);
    if (!p->piece_count || p->layer_bound < 1 || p->layer_bound > max_layers)
        return pf_bad(pf, err, "section PARTS: record %u: layer bound %u with %u pieces, K %u", i,
                      p->layer_bound, p->piece_count, pf->hdr.K);
    if (!p->vertex_count || !p->index_count || p->index_count % 3)
        return pf_bad(pf, err, "section PARTS: record %u: %u vertices, %llu indices", i,
                      p->vertex_count, (unsigned long long)p->index_count);
    if (p->index_bits != 32 && (p->index_bits != 16 || p->vertex_count > PF_INDEX16_MAX_VERTICES))
        return pf_bad(pf, err, "section PARTS: record %u: %u-bit indices for %u vertices", i,
                      p->index_bits, p->vertex_count);
    return OIT_OK;
}

/* The stored streams tile the stored bytes, and the decoded blob is at most
 * PF_DECODE_RATIO times their size: no codec packs more than 64 decoded
 * bytes into one stored byte, so a record cannot make the reader allocate
 * far more than the file holds. */
#define PF_DECODE_RATIO 128u
static oit_status check_part_streams(const oit_partfile *pf, uint32_t i, oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint64_t v = p->stored_vertex_bytes, x = p->stored_index_bytes, s = p->stored_source_bytes;
    if (v > p->stored_bytes || x > p->stored_bytes - v || s != p->stored_bytes - v - x ||
        !v || !x || !s || p->data_bytes / PF_DECODE_RATIO > p->stored_bytes)
        return pf_bad(pf, err, "section PARTS: record %u: stored streams %llu + %llu + %llu "
                      "bytes do not tile %llu stored bytes for a %llu-byte part", i,
                      (unsigned long long)v, (unsigned long long)x, (unsigned long long)s,
                      (unsigned long long)p->stored_bytes, (unsigned long long)p->data_bytes);
    return OIT_OK;
}

/* The blob's layout, and that it lies in PART_DATA after the previous one. */
static oit_status check_part_blob(const oit_partfile *pf, uint32_t i, uint64_t prev_end,
                                  oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    const pf_section *d = &pf->sec[PF_SEC_PART_DATA - 1];
    uint64_t vbytes = (uint64_t)p->vertex_count * pf_vertex_stride(p->attributes);
    if (p->vertex_offset != 0 || p->vertex_bytes != vbytes ||
        p->index_offset != pf_align_up(vbytes, 4))
        return pf_bad(pf, err, "section PARTS: record %u: vertex bytes %llu at %llu, indices at "
                      "%llu: expected %llu at 0, indices at %llu", i,
                      (unsigned long long)p->vertex_bytes, (unsigned long long)p->vertex_offset,
                      (unsigned long long)p->index_offset, (unsigned long long)vbytes,
                      (unsigned long long)pf_align_up(vbytes, 4));
    /* index_count <= size (the index codec stores at least a byte an index)
     * bounds every product below. */
    if (p->index_count > d->size || p->index_bytes != p->index_count * (p->index_bits / 8) ||
        p->data_bytes != oit_partfile_source_offset(p) + p->index_count / 3 * 4)
        return pf_bad(pf, err, "section PARTS: record %u: %llu indices do not fit %llu index "
                      "bytes and %llu source indices in a %llu-byte blob", i,
                      (unsigned long long)p->index_count, (unsigned long long)p->index_bytes,
                      (unsigned long long)(p->index_count / 3), (unsigned long long)p->data_bytes);
    if (p->data_offset % pf->hdr.part_align || p->data_offset < prev_end ||
        p->data_offset > d->offset + d->size ||
        p->stored_bytes > d->offset + d->size - p->data_offset)
        return pf_bad(pf, err, "section PARTS: record %u: blob %llu..+%llu is unaligned, out of "
                      "order or outside PART_DATA", i, (unsigned long long)p->data_offset,
                      (unsigned long long)p->stored_bytes);
    return check_part_streams(pf, i, err);
}

static oit_status check_pieces_of(const oit_partfile *pf, uint32_t i, oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint64_t tri = 0;
    for (uint32_t k = 0; k < p->piece_count; k++) {
        uint64_t j = (uint64_t)p->piece_first + k;
        const oit_partfile_piece *pc = &pf->pieces[j];
        if (pc->part != i || pc->triangle_first != tri || !pc->triangle_count ||
            pc->triangle_count > p->index_count / 3 - tri)
            return pf_bad(pf, err, "section PIECES: record %llu: part %u triangles %llu..+%llu, "
                          "expected part %u from triangle %llu within %llu", (unsigned long long)j,
                          pc->part, (unsigned long long)pc->triangle_first,
                          (unsigned long long)pc->triangle_count, i, (unsigned long long)tri,
                          (unsigned long long)(p->index_count / 3));
        if (!pc->plane_count || pc->plane_count > pc->triangle_count ||
            !pf_box_ok(pc->bounds_min, pc->bounds_max) ||
            !box_inside(pc->bounds_min, pc->bounds_max, p->bounds_min, p->bounds_max))
            return pf_bad(pf, err, "section PIECES: record %llu: %u planes for %llu triangles, or "
                          "bounds outside part %u", (unsigned long long)j, pc->plane_count,
                          (unsigned long long)pc->triangle_count, i);
        tri += pc->triangle_count;
    }
    if (tri != p->index_count / 3)
        return pf_bad(pf, err, "section PIECES: part %u: pieces cover %llu of %llu triangles", i,
                      (unsigned long long)tri, (unsigned long long)(p->index_count / 3));
    return OIT_OK;
}

static oit_status check_parts(const oit_partfile *pf, oit_error *err)
{
    uint64_t pieces = 0, triangles = 0, prev_end = 0;
    uint32_t n = (uint32_t)pf->hdr.part_count;
    for (uint32_t i = 0; i < n; i++) {
        const oit_partfile_part *p = &pf->parts[i];
        oit_status s = check_part_fields(pf, i, err);
        if (!s && (p->piece_first != pieces || p->piece_count > pf->piece_count - pieces))
            s = pf_bad(pf, err, "section PARTS: record %u: pieces %u..+%u, expected from %llu "
                       "within %llu", i, p->piece_first, p->piece_count,
                       (unsigned long long)pieces, (unsigned long long)pf->piece_count);
        if (!s)
            s = check_part_blob(pf, i, prev_end, err);
        if (!s)
            s = check_pieces_of(pf, i, err);
        if (s)
            return s;
        pieces += p->piece_count;
        triangles += p->index_count / 3;
        prev_end = p->data_offset + p->stored_bytes;
    }
    if (pieces != pf->piece_count)
        return pf_bad(pf, err, "section PIECES: %llu records, the parts own %llu",
                      (unsigned long long)pf->piece_count, (unsigned long long)pieces);
    if (triangles != pf->hdr.triangle_count)
        return pf_bad(pf, err, "header: %llu triangles, the parts hold %llu",
                      (unsigned long long)pf->hdr.triangle_count, (unsigned long long)triangles);
    return OIT_OK;
}

static oit_status check_scene_bounds(const oit_partfile *pf, oit_error *err)
{
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (uint32_t i = 0; i < pf->hdr.part_count; i++)
        for (int k = 0; k < 3; k++) {
            const oit_partfile_part *p = &pf->parts[i];
            lo[k] = i == 0 || p->bounds_min[k] < lo[k] ? p->bounds_min[k] : lo[k];
            hi[k] = i == 0 || p->bounds_max[k] > hi[k] ? p->bounds_max[k] : hi[k];
        }
    if (memcmp(lo, pf->meta.bounds_min, sizeof lo) || memcmp(hi, pf->meta.bounds_max, sizeof hi))
        return pf_bad(pf, err, "section META: scene bounds differ from the union of part bounds");
    return OIT_OK;
}

/* ---- GRID and SUBGRIDS -------------------------------------------------------- */

static oit_status check_grid(const oit_partfile *pf, uint32_t g, uint64_t cell_first,
                             oit_error *err)
{
    const oit_partfile_grid *gr = &pf->grids[g];
    const char *sec = g ? "SUBGRIDS" : "GRID";
    uint64_t xy = (uint64_t)gr->dims[0] * gr->dims[1];
    if (!gr->dims[0] || !gr->dims[1] || !gr->dims[2] || xy > UINT64_MAX / gr->dims[2] ||
        xy * gr->dims[2] != gr->cell_count || gr->cell_first != cell_first)
        return pf_bad(pf, err, "section %s: grid %u: %ux%ux%u dims, %llu cells from %llu", sec, g,
                      gr->dims[0], gr->dims[1], gr->dims[2], (unsigned long long)gr->cell_count,
                      (unsigned long long)gr->cell_first);
    if (!pf_finite3(gr->origin) || !pf_finite3(gr->cell_size) || !(gr->cell_size[0] > 0) ||
        !(gr->cell_size[1] > 0) || !(gr->cell_size[2] > 0))
        return pf_bad(pf, err, "section %s: grid %u: origin or cell size not finite or <= 0", sec,
                      g);
    if (g == 0 && (gr->depth || gr->parent_grid != OIT_PARTFILE_NONE ||
                   gr->parent_cell != OIT_PARTFILE_NONE))
        return pf_bad(pf, err, "section GRID: the top grid has depth %u, parent %u", gr->depth,
                      gr->parent_grid);
    if (g > 0 && (gr->parent_grid >= g ||
                  gr->parent_cell >= pf->grids[gr->parent_grid].cell_count ||
                  gr->depth != pf->grids[gr->parent_grid].depth + 1))
        return pf_bad(pf, err, "section SUBGRIDS: record %u: parent grid %u cell %u depth %u: the "
                      "parent must be an earlier grid, one level up", g - 1, gr->parent_grid,
                      gr->parent_cell, gr->depth);
    return OIT_OK;
}

static oit_status check_cell_list(const oit_partfile *pf, const char *sec, uint64_t c,
                                  const uint32_t *list, uint64_t list_first,
                                  const oit_partfile_cell *cell, oit_error *err)
{
    if (cell->reserved || cell->list_first != list_first)
        return pf_bad(pf, err, "section %s: cell %llu: list from %llu, expected %llu", sec,
                      (unsigned long long)c, (unsigned long long)cell->list_first,
                      (unsigned long long)list_first);
    for (uint32_t k = 0; k < cell->list_count; k++) {
        uint32_t part = list[cell->list_first + k];
        if (part >= pf->hdr.part_count || (k && part <= list[cell->list_first + k - 1]))
            return pf_bad(pf, err, "section %s: cell %llu: part %u is missing or out of order "
                          "(%llu parts)", sec, (unsigned long long)c, part,
                          (unsigned long long)pf->hdr.part_count);
    }
    return OIT_OK;
}

typedef struct grid_block {
    pf_grid_block head;
    const uint8_t *grids, *cells, *list;
} grid_block;

static oit_status parse_block(const oit_partfile *pf, uint32_t type, grid_block *b,
                              oit_error *err)
{
    const char *sec = pf_section_name(type);
    uint64_t size = pf_sec_size(pf, type);
    const uint8_t *p = pf_sec_data(pf, type);
    if (size < sizeof b->head)
        return pf_bad(pf, err, "section %s: %llu bytes, shorter than its head", sec,
                      (unsigned long long)size);
    memcpy(&b->head, p, sizeof b->head);
    const pf_grid_block *h = &b->head;
    /* Bounding each count by the size keeps the byte total below 2^64. */
    if (h->reserved || h->grid_count > size / sizeof(oit_partfile_grid) ||
        h->cell_count > size / sizeof(oit_partfile_cell) || h->list_count > size / 4 ||
        size != pf_grid_block_bytes(h->grid_count, h->cell_count, h->list_count) ||
        (type == PF_SEC_GRID && h->grid_count != 1))
        return pf_bad(pf, err, "section %s: %llu bytes cannot hold the %u grids, %llu cells and "
                      "%llu list entries its head claims", sec, (unsigned long long)size,
                      h->grid_count, (unsigned long long)h->cell_count,
                      (unsigned long long)h->list_count);
    b->grids = p + sizeof *h;
    b->cells = b->grids + h->grid_count * sizeof(oit_partfile_grid);
    b->list = b->cells + h->cell_count * sizeof(oit_partfile_cell);
    return OIT_OK;
}

/* Appends a block to the unified grid, cell and list arrays. */
static oit_status append_block(oit_partfile *pf, const grid_block *b, oit_error *err)
{
    const pf_grid_block *h = &b->head;
    uint64_t grids = (uint64_t)pf->grid_count + h->grid_count;
    if (grids > UINT32_MAX)
        return pf_bad(pf, err, "section SUBGRIDS: too many grids");
    void *g = realloc(pf->grids, grids * sizeof *pf->grids);
    if (g)
        pf->grids = g;
    void *c = realloc(pf->cells, (pf->cell_count + h->cell_count + 1) * sizeof *pf->cells);
    if (c)
        pf->cells = c;
    void *l = realloc(pf->lists, (pf->list_count + h->list_count + 1) * sizeof *pf->lists);
    if (l)
        pf->lists = l;
    if (!g || !c || !l)
        return pf_nomem(pf, err);
    memcpy(pf->grids + pf->grid_count, b->grids, h->grid_count * sizeof *pf->grids);
    memcpy(pf->cells + pf->cell_count, b->cells, h->cell_count * sizeof *pf->cells);
    memcpy(pf->lists + pf->list_count, b->list, h->list_count * sizeof *pf->lists);
    return OIT_OK;
}

/* Checks the block just appended, then shifts its offsets to unified ones. */
static oit_status check_block(oit_partfile *pf, uint32_t type, const pf_grid_block *h,
                              oit_error *err)
{
    const char *sec = pf_section_name(type);
    uint32_t g0 = pf->grid_count;
    uint64_t cells = 0, list = 0;
    for (uint32_t g = g0; g < g0 + h->grid_count; g++) {
        oit_status s = check_grid(pf, g, cells, err);
        if (s)
            return s;
        cells += pf->grids[g].cell_count;
        if (cells > h->cell_count)
            break;
    }
    if (cells != h->cell_count)
        return pf_bad(pf, err, "section %s: grids own %llu cells, the head says %llu", sec,
                      (unsigned long long)cells, (unsigned long long)h->cell_count);
    oit_partfile_cell *cell = pf->cells + pf->cell_count;
    const uint32_t *lst = pf->lists + pf->list_count;
    for (uint64_t c = 0; c < h->cell_count; c++) {
        if (cell[c].list_count > h->list_count - list)
            return pf_bad(pf, err, "section %s: cell %llu: list runs past the %llu entries", sec,
                          (unsigned long long)c, (unsigned long long)h->list_count);
        oit_status s = check_cell_list(pf, sec, c, lst, list, &cell[c], err);
        if (s)
            return s;
        list += cell[c].list_count;
    }
    if (list != h->list_count)
        return pf_bad(pf, err, "section %s: cells use %llu of %llu list entries", sec,
                      (unsigned long long)list, (unsigned long long)h->list_count);
    for (uint32_t g = g0; g < g0 + h->grid_count; g++)
        pf->grids[g].cell_first += pf->cell_count;
    for (uint64_t c = 0; c < h->cell_count; c++)
        cell[c].list_first += pf->list_count;
    pf->grid_count += h->grid_count;
    pf->cell_count += h->cell_count;
    pf->list_count += h->list_count;
    return OIT_OK;
}

static oit_status load_grids(oit_partfile *pf, oit_error *err)
{
    static const uint32_t types[2] = {PF_SEC_GRID, PF_SEC_SUBGRIDS};
    for (int i = 0; i < 2; i++) {
        grid_block b;
        oit_status s = parse_block(pf, types[i], &b, err);
        if (!s)
            s = append_block(pf, &b, err);
        if (!s)
            s = check_block(pf, types[i], &b.head, err);
        if (s)
            return s;
    }
    return OIT_OK;
}

/* ---- SLABS ------------------------------------------------------------------ */

static oit_status load_slabs(oit_partfile *pf, oit_error *err)
{
    uint64_t size = pf_sec_size(pf, PF_SEC_SLABS);
    const uint8_t *p = pf_sec_data(pf, PF_SEC_SLABS);
    pf_slab_block h;
    if (size < sizeof h)
        return pf_bad(pf, err, "section SLABS: %llu bytes, shorter than its head",
                      (unsigned long long)size);
    memcpy(&h, p, sizeof h);
    if (h.reserved || h.slab_count > size / sizeof(oit_partfile_slab) || h.list_count > size / 4 ||
        size != pf_slab_block_bytes(h.slab_count, h.list_count))
        return pf_bad(pf, err, "section SLABS: %llu bytes cannot hold the %u slabs and %llu list "
                      "entries its head claims", (unsigned long long)size, h.slab_count,
                      (unsigned long long)h.list_count);
    pf->slab_count = h.slab_count;
    pf->slab_list_count = h.list_count;
    pf->slabs = pf_copy_out(p + sizeof h, h.slab_count, sizeof *pf->slabs);
    pf->slab_list = pf_copy_out(p + sizeof h + h.slab_count * sizeof *pf->slabs, h.list_count,
                                sizeof *pf->slab_list);
    return pf->slabs && pf->slab_list ? OIT_OK : pf_nomem(pf, err);
}

static bool cell_has_part(const oit_partfile *pf, const oit_partfile_cell *cell, uint32_t part)
{
    const uint32_t *l = pf->lists + cell->list_first;
    uint32_t lo = 0, hi = cell->list_count;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (l[mid] < part)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < cell->list_count && l[lo] == part;
}

static oit_status check_slab(const oit_partfile *pf, uint32_t i, uint64_t list_first,
                             oit_error *err)
{
    const oit_partfile_slab *s = &pf->slabs[i];
    float len2 = s->normal[0] * s->normal[0] + s->normal[1] * s->normal[1] +
                 s->normal[2] * s->normal[2];
    /* A cutting plane keeps its integer normal (partfile.h). */
    if (!pf_finite3(s->normal) || !(len2 > 0) || !isfinite(len2))
        return pf_bad(pf, err, "section SLABS: record %u: normal (%g %g %g) zero or not finite", i,
                      s->normal[0], s->normal[1], s->normal[2]);
    if (!isfinite(s->d0) || !isfinite(s->d1) || s->d0 > s->d1)
        return pf_bad(pf, err, "section SLABS: record %u: planes d0 %g > d1 %g or not finite", i,
                      s->d0, s->d1);
    if (s->grid >= pf->grid_count || s->cell >= pf->grids[s->grid].cell_count)
        return pf_bad(pf, err, "section SLABS: record %u: grid %u cell %u does not exist", i,
                      s->grid, s->cell);
    const oit_partfile_cell *cell = &pf->cells[pf->grids[s->grid].cell_first + s->cell];
    if (cell->slab != i + 1)
        return pf_bad(pf, err, "section SLABS: record %u: its cell names slab %u", i, cell->slab);
    if (s->inside_first != list_first || s->inside_count > pf->slab_list_count - list_first)
        return pf_bad(pf, err, "section SLABS: record %u: list %llu..+%u, expected from %llu "
                      "within %llu", i, (unsigned long long)s->inside_first, s->inside_count,
                      (unsigned long long)list_first, (unsigned long long)pf->slab_list_count);
    if (s->part_below == s->part_above || !cell_has_part(pf, cell, s->part_below) ||
        !cell_has_part(pf, cell, s->part_above))
        return pf_bad(pf, err, "section SLABS: record %u: parts %u and %u are not two parts of its "
                      "cell", i, s->part_below, s->part_above);
    for (uint32_t k = 0; k < s->inside_count; k++) {
        uint32_t p = pf->slab_list[list_first + k];
        if ((k && p <= pf->slab_list[list_first + k - 1]) || p == s->part_below ||
            p == s->part_above || !cell_has_part(pf, cell, p))
            return pf_bad(pf, err, "section SLABS: record %u: inside part %u is out of order, "
                          "repeated or not in its cell", i, p);
    }
    return OIT_OK;
}

static oit_status check_slabs(const oit_partfile *pf, oit_error *err)
{
    uint64_t list = 0;
    for (uint32_t i = 0; i < pf->slab_count; i++) {
        oit_status s = check_slab(pf, i, list, err);
        if (s)
            return s;
        list += pf->slabs[i].inside_count;
    }
    if (list != pf->slab_list_count)
        return pf_bad(pf, err, "section SLABS: slabs use %llu of %llu list entries",
                      (unsigned long long)list, (unsigned long long)pf->slab_list_count);
    return OIT_OK;
}

/* ---- links between grids, cells, slabs and parts ------------------------------ */

static void cell_box(const oit_partfile_grid *g, uint64_t cell, double lo[3], double hi[3])
{
    uint64_t idx[3] = {cell % g->dims[0], cell / g->dims[0] % g->dims[1],
                       cell / g->dims[0] / g->dims[1]};
    for (int k = 0; k < 3; k++) {
        lo[k] = g->origin[k] + (double)idx[k] * g->cell_size[k];
        hi[k] = lo[k] + g->cell_size[k];
    }
}

/* A subgrid covers the region its parent cell stands for: the cell's box
 * within its own grid's region (to rounding). It may reach beyond it, so a
 * two-cell subgrid can put its one boundary anywhere inside. region holds 6
 * doubles per grid, filled in grid order (parents come first). */
static bool subgrid_fits(const oit_partfile *pf, uint32_t sg, double *region)
{
    const oit_partfile_grid *sub = &pf->grids[sg];
    const oit_partfile_grid *parent = &pf->grids[sub->parent_grid];
    double lo[3], hi[3], *r = &region[6 * sg], *pr = &region[6 * sub->parent_grid];
    cell_box(parent, sub->parent_cell, lo, hi);
    for (int k = 0; k < 3; k++) {
        r[k] = lo[k] > pr[k] ? lo[k] : pr[k];
        r[3 + k] = hi[k] < pr[3 + k] ? hi[k] : pr[3 + k];
        /* Float origins and sizes: deep cells are only a few ulps wide. */
        double mag = fabs(lo[k]) > fabs(hi[k]) ? fabs(lo[k]) : fabs(hi[k]);
        double tol = 1e-4 * (hi[k] - lo[k]) + 8.0 * FLT_EPSILON * mag;
        double slo = sub->origin[k], shi = slo + (double)sub->dims[k] * sub->cell_size[k];
        if (!(r[k] < r[3 + k]) || slo > r[k] + tol || shi < r[3 + k] - tol)
            return false;
    }
    return true;
}

static oit_status check_cell_links(const oit_partfile *pf, uint32_t g, uint64_t c,
                                   double *region, oit_error *err)
{
    const oit_partfile_cell *cell = &pf->cells[pf->grids[g].cell_first + c];
    uint32_t sg = cell->subgrid;
    if (sg && (sg >= pf->grid_count || pf->grids[sg].parent_grid != g ||
               pf->grids[sg].parent_cell != c || !subgrid_fits(pf, sg, region)))
        return pf_bad(pf, err, "section %s: grid %u cell %llu: subgrid %u does not refine this "
                      "cell", g ? "SUBGRIDS" : "GRID", g, (unsigned long long)c, sg);
    if (cell->slab > pf->slab_count)
        return pf_bad(pf, err, "section %s: grid %u cell %llu: slab %u of %u does not exist",
                      g ? "SUBGRIDS" : "GRID", g, (unsigned long long)c, cell->slab - 1,
                      pf->slab_count);
    return OIT_OK;
}

static oit_status check_links(const oit_partfile *pf, oit_error *err)
{
    if (!pf->grid_count)
        return OIT_OK;
    double *region = malloc(6 * sizeof *region * pf->grid_count);
    if (!region)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: grid regions: out of memory", pf->name);
    const oit_partfile_grid *top = &pf->grids[0];
    for (int k = 0; k < 3; k++) {
        region[k] = top->origin[k];
        region[3 + k] = top->origin[k] + (double)top->dims[k] * top->cell_size[k];
    }
    for (uint32_t g = 0; g < pf->grid_count; g++)
        for (uint64_t c = 0; c < pf->grids[g].cell_count; c++) {
            oit_status s = check_cell_links(pf, g, c, region, err);
            if (s) {
                free(region);
                return s;
            }
        }
    free(region);
    for (uint32_t g = 1; g < pf->grid_count; g++) {
        const oit_partfile_grid *gr = &pf->grids[g];
        const oit_partfile_grid *parent = &pf->grids[gr->parent_grid];
        if (pf->cells[parent->cell_first + gr->parent_cell].subgrid != g)
            return pf_bad(pf, err, "section SUBGRIDS: record %u: its parent cell does not name it",
                          g - 1);
    }
    return OIT_OK;
}

/* A part in no cell would never be ordered, so never drawn. */
static oit_status check_coverage(const oit_partfile *pf, oit_error *err)
{
    uint32_t n = (uint32_t)pf->hdr.part_count;
    unsigned char *seen = calloc(n ? n : 1, 1);
    if (!seen)
        return pf_nomem(pf, err);
    for (uint64_t i = 0; i < pf->list_count; i++)
        seen[pf->lists[i]] = 1;
    uint32_t missing = n;
    for (uint32_t i = 0; i < n && missing == n; i++)
        if (!seen[i])
            missing = i;
    free(seen);
    if (missing != n)
        return pf_bad(pf, err, "section PARTS: record %u: the part is in no grid cell", missing);
    return OIT_OK;
}

oit_status pf_validate_all(oit_partfile *pf, bool deferred, oit_error *err)
{
    oit_status s = check_header(pf, err);
    if (!s)
        s = check_table(pf, err);
    if (!s)
        s = check_checksums(pf, !deferred, err);
    if (!s)
        s = load_meta(pf, err);
    if (!s)
        s = load_parts(pf, err);
    if (!s)
        s = check_parts(pf, err);
    if (!s)
        s = check_scene_bounds(pf, err);
    if (!s)
        s = load_grids(pf, err);
    if (!s)
        s = load_slabs(pf, err);
    if (!s)
        s = check_slabs(pf, err);
    if (!s)
        s = check_links(pf, err);
    if (!s)
        s = check_coverage(pf, err);
    const uint8_t *checked = s ? NULL : pf_sec_data(pf, PF_SEC_PART_DATA);
    oit_partfile_buffer buf = {0};
    for (uint32_t i = 0; !s && !deferred && i < pf->hdr.part_count; i++) {
        s = pf_validate_blob(pf, i, &buf, err);
        const uint8_t *end = pf->base + pf->parts[i].data_offset + pf->parts[i].stored_bytes;
        if (end - checked >= (ptrdiff_t)PF_DROP_CHUNK || i + 1 == pf->hdr.part_count) {
            pf_drop_checked(pf, checked, (size_t)(end - checked));
            checked = end;
        }
    }
    oit_partfile_buffer_free(&buf);
    return s;
}
