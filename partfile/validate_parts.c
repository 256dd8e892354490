/* The PARTS and PIECES sections' checks (validate_internal.h): each part's
 * record, its blob's place in PART_DATA and its pieces, before any blob is
 * read. Apart from validate.c, which runs them in order, as the records of
 * one kind of section. */
#include "partfile/validate_internal.h"

#include <stdint.h>
#include <string.h>

static bool box_inside(const float lo[3], const float hi[3], const float olo[3], const float ohi[3])
{
    for (int k = 0; k < 3; k++)
        if (lo[k] < olo[k] || hi[k] > ohi[k])
            return false;
    return true;
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

oit_status pf_load_parts(oit_partfile *pf, oit_error *err)
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

oit_status pf_check_parts(const oit_partfile *pf, oit_error *err)
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

oit_status pf_check_scene_bounds(const oit_partfile *pf, oit_error *err)
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
