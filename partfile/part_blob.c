/* One part's blob (handle.h: pf_decode_blob, pf_validate_blob): its stored
 * streams decoded into the caller's buffer, every decoded value checked, and
 * that buffer's growth and release. Apart from validate.c because open's
 * checks and a part's first load (read.c) both use it: with the buffer here,
 * validate.c never reaches back into read.c. */
#include "partfile/handle.h"

#include "base/minmax.h"
#include "partfile/checksum.h"
#include "partfile/codec.h"
#include "partfile/validate_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint32_t index_at(const uint8_t *idx, uint32_t bits, uint64_t i)
{
    if (bits == 16) {
        uint16_t v;
        memcpy(&v, idx + i * 2, 2);
        return v;
    }
    uint32_t v;
    memcpy(&v, idx + i * 4, 4);
    return v;
}

static void vertex_at(const uint8_t *blob, uint32_t stride, uint32_t v, float out[3])
{
    memcpy(out, blob + (size_t)v * stride, 12);
}

/* Bounds are stored exactly (min/max of the data), so compare for equality. */
static oit_status check_vertices(const oit_partfile *pf, uint32_t i, const uint8_t *blob,
                                 oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint32_t stride = pf_vertex_stride(p->attributes);
    float lo[3], hi[3], v[3];
    vertex_at(blob, stride, 0, lo);
    memcpy(hi, lo, sizeof hi);
    for (uint32_t j = 0; j < p->vertex_count; j++) {
        vertex_at(blob, stride, j, v);
        if (!pf_finite3(v))
            return pf_bad(pf, err, "section PART_DATA: part %u: vertex %u is not finite", i, j);
        for (int k = 0; k < 3; k++) {
            lo[k] = oit_min_f(lo[k], v[k]);
            hi[k] = oit_max_f(hi[k], v[k]);
        }
    }
    if (memcmp(lo, p->bounds_min, sizeof lo) || memcmp(hi, p->bounds_max, sizeof hi))
        return pf_bad(pf, err, "section PART_DATA: part %u: vertices span (%g %g %g)..(%g %g %g), "
                      "the record says (%g %g %g)..(%g %g %g)", i, lo[0], lo[1], lo[2], hi[0],
                      hi[1], hi[2], p->bounds_min[0], p->bounds_min[1], p->bounds_min[2],
                      p->bounds_max[0], p->bounds_max[1], p->bounds_max[2]);
    return OIT_OK;
}

static oit_status check_indices(const oit_partfile *pf, uint32_t i, const uint8_t *blob,
                                oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    const uint8_t *idx = blob + p->index_offset;
    for (uint64_t j = 0; j < p->index_count; j++) {
        uint32_t v = index_at(idx, p->index_bits, j);
        if (v >= p->vertex_count)
            return pf_bad(pf, err, "section PART_DATA: part %u: triangle %llu: index %u >= %u "
                          "vertices", i, (unsigned long long)(j / 3), v, p->vertex_count);
    }
    return OIT_OK;
}

/* Every source index names a triangle the source delivered; the pad
 * before them is zero. */
static oit_status check_sources(const oit_partfile *pf, uint32_t i, const uint8_t *blob,
                                oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint64_t at = oit_partfile_source_offset(p);
    for (uint64_t j = p->index_offset + p->index_bytes; j < at; j++)
        if (blob[j])
            return pf_bad(pf, err, "section PART_DATA: part %u: non-zero pad before the source "
                          "indices", i);
    for (uint64_t t = 0; t < p->index_count / 3; t++) {
        uint32_t v;
        memcpy(&v, blob + at + t * 4, sizeof v);
        if (v >= pf->meta.triangles_in)
            return pf_bad(pf, err, "section PART_DATA: part %u: triangle %llu: source index %u "
                          ">= %llu source triangles", i, (unsigned long long)t, v,
                          (unsigned long long)pf->meta.triangles_in);
    }
    return OIT_OK;
}

/* Runs after check_indices: every index is in range. */
static oit_status check_piece_bounds(const oit_partfile *pf, uint32_t i, const uint8_t *blob,
                                     oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint32_t stride = pf_vertex_stride(p->attributes);
    const uint8_t *idx = blob + p->index_offset;
    for (uint32_t k = 0; k < p->piece_count; k++) {
        const oit_partfile_piece *pc = &pf->pieces[p->piece_first + k];
        float lo[3], hi[3], v[3];
        uint64_t first = pc->triangle_first * 3, end = first + pc->triangle_count * 3;
        vertex_at(blob, stride, index_at(idx, p->index_bits, first), lo);
        memcpy(hi, lo, sizeof hi);
        for (uint64_t j = first; j < end; j++) {
            vertex_at(blob, stride, index_at(idx, p->index_bits, j), v);
            for (int c = 0; c < 3; c++) {
                lo[c] = oit_min_f(lo[c], v[c]);
                hi[c] = oit_max_f(hi[c], v[c]);
            }
        }
        if (memcmp(lo, pc->bounds_min, sizeof lo) || memcmp(hi, pc->bounds_max, sizeof hi))
            return pf_bad(pf, err, "section PIECES: record %u: bounds differ from its triangles' "
                          "(part %u)", p->piece_first + k, i);
    }
    return OIT_OK;
}

static oit_status buffer_reserve(const oit_partfile *pf, oit_partfile_buffer *buf,
                                 uint64_t bytes, oit_error *err)
{
    if (bytes <= buf->capacity)
        return OIT_OK;
    if (bytes > SIZE_MAX)
        return pf_nomem(pf, err);
    void *p = realloc(buf->data, (size_t)bytes);
    if (!p)
        return pf_nomem(pf, err);
    buf->data = p;
    buf->capacity = (size_t)bytes;
    return OIT_OK;
}

/* Decodes part i's stored streams into the version 4 blob layout in buf
 * (pads zero); checks nothing but the codecs' own framing. */
oit_status pf_decode_blob(const oit_partfile *pf, uint32_t i, oit_partfile_buffer *buf,
                          oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    oit_status s = buffer_reserve(pf, buf, p->data_bytes, err);
    if (s)
        return s;
    uint8_t *blob = buf->data;
    const uint8_t *in = pf->base + p->data_offset;
    uint64_t src_at = oit_partfile_source_offset(p);
    memset(blob + p->vertex_bytes, 0, (size_t)(p->index_offset - p->vertex_bytes));
    memset(blob + p->index_offset + p->index_bytes, 0,
           (size_t)(src_at - p->index_offset - p->index_bytes));
    const char *what = NULL;
    if (pf_decode_vertices(blob, p->vertex_count, pf_vertex_stride(p->attributes), in,
                           (size_t)p->stored_vertex_bytes))
        what = "vertex";
    else if (pf_decode_indices(blob + p->index_offset, p->index_count, p->index_bits,
                               in + p->stored_vertex_bytes, (size_t)p->stored_index_bytes))
        what = "index";
    else if (pf_decode_sources((uint32_t *)(void *)(blob + src_at), p->index_count / 3,
                               in + p->stored_vertex_bytes + p->stored_index_bytes,
                               (size_t)p->stored_source_bytes))
        what = "source index";
    if (what)
        return pf_bad(pf, err, "section PART_DATA: part %u: the %s stream does not decode to the "
                      "record's counts (corrupt)", i, what);
    return OIT_OK;
}

/* Checksum of the stored bytes, decode into buf, then every decoded value. */
oit_status pf_validate_blob(const oit_partfile *pf, uint32_t i, oit_partfile_buffer *buf,
                            oit_error *err)
{
    const oit_partfile_part *p = &pf->parts[i];
    uint32_t crc = oit_crc32c(0, pf->base + p->data_offset, p->stored_bytes);
    if (crc != p->data_crc)
        return pf_bad(pf, err, "section PART_DATA: part %u: checksum 0x%08x, stored 0x%08x "
                      "(corrupt)", i, crc, p->data_crc);
    oit_status s = pf_decode_blob(pf, i, buf, err);
    if (s)
        return s;
    const uint8_t *blob = buf->data;
    s = check_vertices(pf, i, blob, err);
    if (!s)
        s = check_indices(pf, i, blob, err);
    if (!s)
        s = check_piece_bounds(pf, i, blob, err);
    if (!s)
        s = check_sources(pf, i, blob, err);
    return s;
}

void oit_partfile_buffer_free(oit_partfile_buffer *buf)
{
    if (!buf)
        return;
    free(buf->data);
    *buf = (oit_partfile_buffer){0};
}
