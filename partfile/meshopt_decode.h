/* Decoders for two of meshoptimizer's bitstreams, written in plain C from
 * the Khronos glTF extension specification EXT_meshopt_compression
 * (Appendix A, "Bitstream"), so that reading a part file needs neither
 * libmeshoptimizer nor the C++ runtime it drags in. Only decoding lives
 * here: the part file writer still encodes with libmeshoptimizer.
 *
 *   oit_meshopt_decode_vertices        mode 0, "attributes": what
 *                                      meshopt_encodeVertexBuffer writes,
 *                                      vertex codec version 0 (header 0xa0),
 *                                      the only version the encoder of
 *                                      libmeshoptimizer 0.18 produces
 *   oit_meshopt_decode_index_sequence  mode 2, "indices": what
 *                                      meshopt_encodeIndexSequence writes
 *                                      (header 0xd0 or 0xd1; the two index
 *                                      codec versions share this bitstream)
 *
 * Each produces, for every stream the encoder writes, the same bytes as
 * meshopt_decodeVertexBuffer / meshopt_decodeIndexSequence of libmeshoptimizer
 * 0.18 (tests/partfile/test_meshopt_decode.c checks that against the library). Other
 * codec versions are refused, not guessed at.
 *
 * Safety: for any input whatsoever (a part file is untrusted) they read only
 * src[0, bytes) and write only dst[0, count * stride) resp.
 * dst[0, count * index_size), keep no state between calls and never abort.
 * A malformed stream may still decode "successfully" into garbage, as with
 * libmeshoptimizer; callers check what they get.
 *
 * Both return 0, or a negative OIT_MESHOPT_E* code; the first three mean
 * what meshopt's -1, -2 and -3 mean, and callers need only tell 0 from
 * non-zero. dst need not be aligned.
 */
#ifndef OIT_PARTFILE_MESHOPT_DECODE_H
#define OIT_PARTFILE_MESHOPT_DECODE_H

#include <stddef.h>

enum {
    OIT_MESHOPT_EHEADER = -1, /* not this codec's header byte, or a later version */
    OIT_MESHOPT_ETRUNC = -2,  /* malformed: the stream ends before `count` items */
    OIT_MESHOPT_ETRAIL = -3,  /* the items end, but not exactly at the stream's tail */
    OIT_MESHOPT_EARG = -4,    /* stride not a multiple of 4 in [4, 256], index_size not
                                 2 or 4, or count * stride overflows */
};

/* Decodes `count` vertices of `stride` bytes from the `bytes`-byte stream at
 * src into dst (count * stride bytes). */
int oit_meshopt_decode_vertices(void *dst, size_t count, size_t stride, const unsigned char *src,
                                size_t bytes);

/* Decodes `count` indices of `index_size` (2 or 4) bytes, native byte order,
 * from the `bytes`-byte stream at src into dst (count * index_size bytes). */
int oit_meshopt_decode_index_sequence(void *dst, size_t count, size_t index_size,
                                      const unsigned char *src, size_t bytes);

#endif
