/* Adding a part (write.h: oit_partfile_writer_add_part): its checks, its
 * record and pieces, and its blob encoded and streamed to the file. Apart
 * from write.c as the one step that touches a part's data; the rest of the
 * writer keeps only records. */
#include "oit/mesh.h"
#include "oit/partfile.h"

#include "partfile/checksum.h"
#include "partfile/codec.h"
#include "partfile/layout.h"
#include "partfile/vertex_order.h"
#include "partfile/write.h"
#include "partfile/write_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
    pf_bounds_reset(r.bounds_min, r.bounds_max);
    for (uint32_t i = 0; i < p->vertex_count; i++)
        pf_bounds_add(r.bounds_min, r.bounds_max, p->positions + (size_t)i * 3);
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
        pf_bounds_reset(pc.bounds_min, pc.bounds_max);
        for (uint64_t t = first * 3; t < (first + pc.triangle_count) * 3; t++)
            pf_bounds_add(pc.bounds_min, pc.bounds_max, p->positions + (size_t)p->indices[t] * 3);
        first += pc.triangle_count;
        oit_status s = pf_vec_push(&w->pieces, &pc, 1, sizeof pc, err);
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
    s = pf_pad_to(w, w->part_align, &w->data_crc, err);
    rec.data_offset = w->pos;
    rec.data_crc = oit_crc32c(0, blob, rec.stored_bytes);
    if (!s)
        s = pf_write_bytes(w, blob, rec.stored_bytes, err);
    if (!s)
        w->data_crc = oit_crc32c(w->data_crc, blob, rec.stored_bytes);
    free(blob);
    if (!s)
        s = add_pieces(w, p, n, err);
    for (uint64_t t = 0; !s && t < p->index_count / 3; t++)
        if (p->sources[t] >= w->sources_end)
            w->sources_end = (uint64_t)p->sources[t] + 1;
    if (!s)
        s = pf_vec_push(&w->parts, &rec, 1, sizeof rec, err);
    pf_ordered_free(&ord);
    if (s)
        return s;
    w->triangles += q.index_count / 3;
    if (index)
        *index = n;
    return OIT_OK;
}
