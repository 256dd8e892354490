/* The per-part stream codecs of part file version 5 (docs/part-file.md,
 * "PART_DATA"). A part is stored as three encoded streams back to back:
 *
 *   vertices        meshopt_encodeVertexBuffer over the stride-12/16
 *                   vertices: lossless, every float keeps its bits
 *   indices         meshopt_encodeIndexSequence: lossless and in order (the
 *                   triangle codec meshopt_encodeIndexBuffer may rotate a
 *                   triangle's vertices, and the tie rule's plane is
 *                   computed from vertex 0, docs/ties.md)
 *   source indices  one LEB128 varint a triangle of zigzag(s[t] - s[t-1] - 1)
 *                   with s[-1] = -1, so an ascending run costs a zero byte
 *                   a triangle
 *
 * and decoded into the version 4 blob layout (vertices, pad to 4, indices of
 * index_bits, pad to 4, u32 source indices), which is what every reader of
 * a part view sees. The encoders (encode.c) use libmeshoptimizer;
 * the decoders (partfile_codec.c) use our own meshopt_decode.h, so that
 * reading needs no C++ runtime. The decoders never read or write outside
 * the buffers they are given; they may yield garbage for hostile input, so
 * the part file reader checks what they produce.
 */
#ifndef OIT_PARTFILE_CODEC_H
#define OIT_PARTFILE_CODEC_H

#include <stddef.h>
#include <stdint.h>

/* Encoded stream sizes of one part. */
typedef struct pf_codec_sizes {
    uint64_t vertex_bytes, index_bytes, source_bytes;
} pf_codec_sizes;

/* The most bytes pf_encode_part can write for such a part. */
size_t pf_encode_bound(uint32_t vertex_count, uint32_t stride, uint64_t index_count);

/* Encodes the streams into out (cap bytes, at least pf_encode_bound).
 * Returns 0, or -1 when cap is too small. */
int pf_encode_part(const uint8_t *vertices, uint32_t vertex_count, uint32_t stride,
                   const uint32_t *indices, uint64_t index_count, const uint32_t *sources,
                   uint8_t *out, size_t cap, pf_codec_sizes *sizes);

/* Each returns 0, or -1 when the stream is malformed or is not exactly
 * `bytes` long for `count` items. */
int pf_decode_vertices(void *dst, uint32_t count, uint32_t stride, const uint8_t *src,
                       size_t bytes);
int pf_decode_indices(void *dst, uint64_t count, uint32_t index_bits, const uint8_t *src,
                      size_t bytes);
int pf_decode_sources(uint32_t *dst, uint64_t count, const uint8_t *src, size_t bytes);

#endif
