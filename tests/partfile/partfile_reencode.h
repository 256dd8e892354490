/* Test helper: a part file with one part's stored streams re-encoded after
 * an edit of its decoded values (version 5 stores parts encoded, so an
 * out-of-range index or source index must go through the codecs to reach
 * the reader's checks). Later parts and sections shift by a multiple of
 * part_align when the new streams are longer; every checksum is resealed.
 */
#ifndef OIT_TESTS_PARTFILE_REENCODE_H
#define OIT_TESTS_PARTFILE_REENCODE_H

#include "partfile/codec.h"
#include "tests/partfile/partfile_reseal.h"

#include <stdlib.h>

/* A part's decoded values, widened to u32 indices. */
typedef struct decoded_part {
    uint8_t *vertices;
    uint32_t *indices, *sources;
} decoded_part;

static inline void decoded_part_free(decoded_part *d)
{
    free(d->vertices);
    free(d->indices);
    free(d->sources);
}

static inline oit_partfile_part read_part_record(const uint8_t *b, uint32_t part)
{
    pf_section ps;
    memcpy(&ps, b + PF_HEADER_BYTES + (PF_SEC_PARTS - 1) * PF_ENTRY_BYTES, sizeof ps);
    oit_partfile_part p;
    memcpy(&p, b + ps.offset + (size_t)part * sizeof p, sizeof p);
    return p;
}

/* 0 when the part's streams decode. */
static inline int decode_part(const uint8_t *b, uint32_t part, decoded_part *d)
{
    oit_partfile_part p = read_part_record(b, part);
    uint32_t stride = pf_vertex_stride(p.attributes);
    const uint8_t *in = b + p.data_offset;
    d->vertices = malloc((size_t)p.vertex_count * stride);
    d->indices = malloc((size_t)p.index_count * 4);
    d->sources = malloc((size_t)p.index_count / 3 * 4);
    uint16_t *narrow = malloc((size_t)p.index_count * 2);
    int rc = !d->vertices || !d->indices || !d->sources || !narrow ||
             pf_decode_vertices(d->vertices, p.vertex_count, stride, in,
                                (size_t)p.stored_vertex_bytes) ||
             pf_decode_indices(p.index_bits == 16 ? (void *)narrow : (void *)d->indices,
                               p.index_count, p.index_bits, in + p.stored_vertex_bytes,
                               (size_t)p.stored_index_bytes) ||
             pf_decode_sources(d->sources, p.index_count / 3,
                               in + p.stored_vertex_bytes + p.stored_index_bytes,
                               (size_t)p.stored_source_bytes);
    for (uint64_t i = 0; !rc && p.index_bits == 16 && i < p.index_count; i++)
        d->indices[i] = narrow[i];
    free(narrow);
    return rc;
}

/* The file src (size bytes) with part `part`'s streams replaced by the
 * encoding of d: a new buffer (free it), its size in *out_size; NULL when
 * out of memory. */
static inline uint8_t *reencode_part(const uint8_t *src, size_t size, uint32_t part,
                                     const decoded_part *d, size_t *out_size)
{
    pf_header h;
    memcpy(&h, src, sizeof h);
    oit_partfile_part p = read_part_record(src, part);
    uint32_t stride = pf_vertex_stride(p.attributes);
    size_t cap = pf_encode_bound(p.vertex_count, stride, p.index_count);
    uint8_t *enc = malloc(cap);
    pf_codec_sizes z;
    if (!enc || pf_encode_part(d->vertices, p.vertex_count, stride, d->indices, p.index_count,
                               d->sources, enc, cap, &z)) {
        free(enc);
        return NULL;
    }
    uint64_t off = p.data_offset, old = p.stored_bytes;
    uint64_t nw = z.vertex_bytes + z.index_bytes + z.source_bytes;
    uint64_t delta = nw > old ? pf_align_up(nw - old, h.part_align) : 0;
    size_t n = size + (size_t)delta;
    uint8_t *b = calloc(1, n);
    if (!b) {
        free(enc);
        return NULL;
    }
    memcpy(b, src, (size_t)off);
    memcpy(b + off, enc, (size_t)nw);
    memcpy(b + off + old + delta, src + off + old, size - (size_t)(off + old));
    free(enc);
    /* Sections and blobs after the part move by delta. */
    for (uint32_t t = 0; t < PF_SECTION_COUNT; t++) {
        pf_section s;
        uint8_t *e = b + PF_HEADER_BYTES + t * PF_ENTRY_BYTES;
        memcpy(&s, e, sizeof s);
        if (s.offset > off)
            s.offset += delta;
        memcpy(e, &s, sizeof s);
    }
    pf_section ps, ds;
    memcpy(&ps, b + PF_HEADER_BYTES + (PF_SEC_PARTS - 1) * PF_ENTRY_BYTES, sizeof ps);
    for (uint64_t j = 0; j < h.part_count; j++) {
        oit_partfile_part q;
        memcpy(&q, b + ps.offset + j * sizeof q, sizeof q);
        if (j > part)
            q.data_offset += delta;
        if (j == part) {
            q.stored_vertex_bytes = z.vertex_bytes;
            q.stored_index_bytes = z.index_bytes;
            q.stored_source_bytes = z.source_bytes;
            q.stored_bytes = nw;
        }
        memcpy(b + ps.offset + j * sizeof q, &q, sizeof q);
    }
    oit_partfile_part last = read_part_record(b, (uint32_t)(h.part_count - 1));
    uint8_t *de = b + PF_HEADER_BYTES + (PF_SEC_PART_DATA - 1) * PF_ENTRY_BYTES;
    memcpy(&ds, de, sizeof ds);
    ds.size = last.data_offset + last.stored_bytes - ds.offset;
    memcpy(de, &ds, sizeof ds);
    h.file_bytes = n;
    memcpy(b, &h, sizeof h);
    reseal_part(b, n, part);
    reseal(b, n);
    *out_size = n;
    return b;
}

#endif
