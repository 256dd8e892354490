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
/* This file holds the header, the section table, the checksums, META and
 * the order of every check (pf_validate_all); the records' checks are in
 * validate_parts.c and validate_grids.c, a part's blob in part_blob.c.
 * Dependencies point down: read.c uses this file and part_blob.c; this file
 * uses those three and handle.c, never read.c. */
/* madvise (pf_drop_checked) is not POSIX. */
#define _DEFAULT_SOURCE
#include "partfile/handle.h"
#include "partfile/validate_internal.h"

#include "oit/mesh.h"

#include "partfile/checksum.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

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
        s = pf_load_parts(pf, err);
    if (!s)
        s = pf_check_parts(pf, err);
    if (!s)
        s = pf_check_scene_bounds(pf, err);
    if (!s)
        s = pf_load_grids(pf, err);
    if (!s)
        s = pf_load_slabs(pf, err);
    if (!s)
        s = pf_check_slabs(pf, err);
    if (!s)
        s = pf_check_links(pf, err);
    if (!s)
        s = pf_check_coverage(pf, err);
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
