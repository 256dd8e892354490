/* Part stream decoders (codec.h), with our own meshopt decoders
 * (meshopt_decode.h): no libmeshoptimizer symbol here, so a reader does not
 * drag in the C++ runtime. The encoders are in encode.c. */
#include "partfile/codec.h"

#include "partfile/meshopt_decode.h"

#include <string.h>

int pf_decode_vertices(void *dst, uint32_t count, uint32_t stride, const uint8_t *src,
                       size_t bytes)
{
    return oit_meshopt_decode_vertices(dst, count, stride, src, bytes) == 0 ? 0 : -1;
}

int pf_decode_indices(void *dst, uint64_t count, uint32_t index_bits, const uint8_t *src,
                      size_t bytes)
{
    if ((index_bits != 16 && index_bits != 32) || count > SIZE_MAX / 4)
        return -1;
    return oit_meshopt_decode_index_sequence(dst, (size_t)count, index_bits / 8, src, bytes) == 0
               ? 0
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
