/* Part stream encoders (codec.h): the writer's half, kept apart from
 * the decoders so that reading a part file needs no libmeshoptimizer. */
#include "partfile/codec.h"

#include <meshoptimizer.h>

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
