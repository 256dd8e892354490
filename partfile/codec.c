/* Part stream codecs (partfile_codec.h). */
#include "partfile/codec.h"

#include <meshoptimizer.h>
#include <string.h>

/* The longest LEB128 varint of a zigzag-coded 33-bit delta. */
#define SOURCE_VARINT_MAX 5u

size_t pf_encode_bound(uint32_t vertex_count, uint32_t stride, uint64_t index_count)
{
    return meshopt_encodeVertexBufferBound(vertex_count, stride) +
           meshopt_encodeIndexSequenceBound((size_t)index_count, vertex_count) +
           (size_t)(index_count / 3) * SOURCE_VARINT_MAX;
}

/* zigzag(s[t] - s[t-1] - 1): 0 for the next index, small for near ones. */
static uint64_t source_token(int64_t prev, uint32_t s)
{
    int64_t d = (int64_t)s - prev - 1;
    return ((uint64_t)d << 1) ^ (uint64_t)(d >> 63);
}

static size_t encode_sources(const uint32_t *sources, uint64_t n, uint8_t *out)
{
    size_t at = 0;
    int64_t prev = -1;
    for (uint64_t t = 0; t < n; t++) {
        uint64_t z = source_token(prev, sources[t]);
        do {
            uint8_t byte = (uint8_t)(z & 0x7f);
            z >>= 7;
            out[at++] = byte | (z ? 0x80 : 0);
        } while (z);
        prev = sources[t];
    }
    return at;
}

int pf_encode_part(const uint8_t *vertices, uint32_t vertex_count, uint32_t stride,
                   const uint32_t *indices, uint64_t index_count, const uint32_t *sources,
                   uint8_t *out, size_t cap, pf_codec_sizes *sizes)
{
    if (cap < pf_encode_bound(vertex_count, stride, index_count))
        return -1;
    size_t v = meshopt_encodeVertexBuffer(out, cap, vertices, vertex_count, stride);
    size_t i = v ? meshopt_encodeIndexSequence(out + v, cap - v, indices, (size_t)index_count) : 0;
    if (!v || !i)
        return -1;
    sizes->vertex_bytes = v;
    sizes->index_bytes = i;
    sizes->source_bytes = encode_sources(sources, index_count / 3, out + v + i);
    return 0;
}

int pf_decode_vertices(void *dst, uint32_t count, uint32_t stride, const uint8_t *src,
                       size_t bytes)
{
    return meshopt_decodeVertexBuffer(dst, count, stride, src, bytes) == 0 ? 0 : -1;
}

int pf_decode_indices(void *dst, uint64_t count, uint32_t index_bits, const uint8_t *src,
                      size_t bytes)
{
    if (index_bits != 16 && index_bits != 32)
        return -1;
    return meshopt_decodeIndexSequence(dst, (size_t)count, index_bits / 8, src, bytes) == 0 ? 0
                                                                                            : -1;
}

/* One varint at *at, advancing it; -1 past the end or over 64 bits. */
static int read_varint(const uint8_t *src, size_t bytes, size_t *at, uint64_t *out)
{
    uint64_t z = 0;
    for (unsigned shift = 0; shift < 64; shift += 7) {
        if (*at >= bytes)
            return -1;
        uint8_t b = src[(*at)++];
        z |= (uint64_t)(b & 0x7f) << shift;
        if (!(b & 0x80)) {
            *out = z;
            return 0;
        }
    }
    return -1;
}

int pf_decode_sources(uint32_t *dst, uint64_t count, const uint8_t *src, size_t bytes)
{
    size_t at = 0;
    int64_t prev = -1;
    for (uint64_t t = 0; t < count; t++) {
        uint64_t z;
        if (read_varint(src, bytes, &at, &z) || z > ((uint64_t)1 << 34))
            return -1;
        int64_t d = (int64_t)(z >> 1) ^ -(int64_t)(z & 1);
        int64_t s = prev + 1 + d;
        if (s < 0 || s > (int64_t)UINT32_MAX)
            return -1;
        memcpy(&dst[t], &(uint32_t){(uint32_t)s}, 4);
        prev = s;
    }
    return at == bytes ? 0 : -1;
}
