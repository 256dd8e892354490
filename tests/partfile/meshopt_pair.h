/* The two meshopt decoders of one codec side by side: libmeshoptimizer's
 * (the oracle: its encoder writes the streams) and ours
 * (partfile/meshopt_decode.h), so that test_meshopt_decode and
 * fuzz_meshopt_decode run the vertex and the index codec through one
 * comparison. */
#ifndef OIT_TESTS_PARTFILE_MESHOPT_PAIR_H
#define OIT_TESTS_PARTFILE_MESHOPT_PAIR_H

#include "partfile/meshopt_decode.h"

#include <meshoptimizer.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Both libraries' decoders take (dst, count, element size, src, bytes). */
typedef int (*meshopt_decode_fn)(void *dst, size_t count, size_t size, const unsigned char *src,
                                 size_t bytes);

typedef struct meshopt_pair {
    const char *what;      /* "vertices" or "indices", for messages */
    const char *size_name; /* what the element size is called */
    meshopt_decode_fn theirs, ours;
} meshopt_pair;

static const meshopt_pair MESHOPT_VERTICES = {"vertices", "stride", meshopt_decodeVertexBuffer,
                                              oit_meshopt_decode_vertices};
static const meshopt_pair MESHOPT_INDICES = {"indices", "size", meshopt_decodeIndexSequence,
                                             oit_meshopt_decode_index_sequence};

/* Decodes count elements of size bytes from src with both, into buffers of
 * the output's exact size (so ASan sees any write past it); their results
 * in *theirs and *ours. Returns 1 when both succeeded with different
 * output bytes. */
static inline int meshopt_pair_run(const meshopt_pair *p, const unsigned char *src, size_t bytes,
                                   size_t count, size_t size, int *theirs, int *ours)
{
    size_t n = count * size;
    unsigned char *a = malloc(n ? n : 1), *b = malloc(n ? n : 1);
    if (!a || !b) {
        fprintf(stderr, "out of memory (%zu bytes)\n", n);
        abort();
    }
    *theirs = p->theirs(a, count, size, src, bytes);
    *ours = p->ours(b, count, size, src, bytes);
    int differ = *theirs == 0 && *ours == 0 && n && memcmp(a, b, n) != 0;
    free(a);
    free(b);
    return differ;
}

#endif
