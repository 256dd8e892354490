/* libFuzzer target: partfile/meshopt_decode.c over arbitrary bytes, each
 * decoder against libmeshoptimizer's on the same input.
 *
 * Input: 6 parameter bytes, then the stream (given to both decoders):
 *   byte 0      vertex stride = 4 * (1 + byte % 64), so 4..256
 *   bytes 1-2   vertex count, little-endian, low 13 bits (several blocks)
 *   byte 3      bit 0: 4-byte indices, else 2-byte
 *   bytes 4-5   index count, little-endian
 * (tests/partfile/test_meshopt_decode.c --write-corpus writes seeds in this layout.)
 *
 * The stream and the outputs sit in buffers of their exact size, so ASan
 * traps any access outside them; a difference from libmeshoptimizer in
 * success or, when both succeed, in the output bytes traps too.
 */
#include "partfile/meshopt_decode.h"
#include "tests/partfile/meshopt_pair.h"

#include <meshoptimizer.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define REQUIRE(c)                                                                                 \
    do {                                                                                           \
        if (!(c))                                                                                  \
            __builtin_trap();                                                                      \
    } while (0)

/* Traps unless both decoders succeed or both fail, and agree on every
 * output byte when they succeed. */
static void both(const meshopt_pair *p, const unsigned char *src, size_t bytes, size_t count,
                 size_t size)
{
    int ra, rb;
    REQUIRE(!meshopt_pair_run(p, src, bytes, count, size, &ra, &rb));
    REQUIRE((ra == 0) == (rb == 0));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 6)
        return 0;
    size_t stride = 4 * (1 + data[0] % 64u);
    size_t vcount = (data[1] | (size_t)data[2] << 8) & 0x1fffu;
    size_t index_size = data[3] & 1u ? 4 : 2;
    size_t icount = data[4] | (size_t)data[5] << 8;
    size_t bytes = size - 6;
    /* A copy of its own size: libFuzzer's buffer is exact already, but
     * this keeps the promise visible. */
    unsigned char *src = malloc(bytes ? bytes : 1);
    REQUIRE(src);
    memcpy(src, data + 6, bytes);
    both(&MESHOPT_VERTICES, src, bytes, vcount, stride);
    both(&MESHOPT_INDICES, src, bytes, icount, index_size);
    /* Bad arguments are refused, never decoded. */
    REQUIRE(oit_meshopt_decode_vertices(NULL, 1, stride + 2, src, bytes) == OIT_MESHOPT_EARG);
    REQUIRE(oit_meshopt_decode_index_sequence(NULL, 1, 3, src, bytes) == OIT_MESHOPT_EARG);
    free(src);
    return 0;
}
