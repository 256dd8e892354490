/* meshoptimizer's attribute and index sequence bitstreams, decoded
 * (meshopt_decode.h; the layout is EXT_meshopt_compression, Appendix A). */
#include "partfile/meshopt_decode.h"

#include <stdint.h>
#include <string.h>

#define VERTEX_HEADER    0xa0u
#define VERTEX_VERSION   0u /* the newest vertex codec version read */
#define SEQUENCE_HEADER  0xd0u
#define SEQUENCE_VERSION 1u    /* versions 0 and 1 write the same sequence */
#define GROUP            16u   /* deltas share one 2-bit mode per group of 16 */
#define BLOCK_BYTES      8192u /* a block's vertices fill at most this ... */
#define BLOCK_MAX        256u  /* ... and number at most this */
#define TAIL_MIN         32u   /* the tail holds the baseline vertex, padded to this */
/* The most a group can take: 8 bytes of 4-bit deltas and 16 escapes.
 * meshopt insists on this much before each group whatever its mode, so a
 * stream cut short fails at the same group in both decoders, and no group
 * needs a bounds check of its own. */
#define GROUP_READ_MAX 24u
/* The sequence's 4 reserved tail bytes let a varint (at most 5 bytes) that
 * starts before them be read without a check. */
#define SEQUENCE_TAIL 4u

static size_t block_vertices(size_t stride)
{
    size_t n = (BLOCK_BYTES / stride) & ~(size_t)(GROUP - 1);
    return n < BLOCK_MAX ? n : BLOCK_MAX;
}

/* Deltas are unpacked LANES byte positions side by side (out[i * LANES] for
 * vertex i), so that one 64-bit word then carries 8 bytes of a vertex through
 * the delta sum, or a 32-bit word the last 4 of a stride that is 4 mod 8. */
#define LANES 8u

/* 2-bit and 4-bit deltas ('bits') are packed first-delta-in-the-high-bits;
 * an all-ones field (the sentinel) takes the next escape byte instead.
 * Branch-free, as sentinels are as unpredictable as the data. Inlined with
 * a constant 'bits', each width gets its own loop. */
static inline const unsigned char *unpack_bits(const unsigned char *in, unsigned char *out,
                                               unsigned bits)
{
    const unsigned per_byte = 8 / bits, sentinel = (1u << bits) - 1;
    const unsigned char *escape = in + GROUP * bits / 8;
    for (unsigned i = 0; i < GROUP; i++) {
        unsigned v = (in[i / per_byte] >> (8 - bits - bits * (i % per_byte))) & sentinel;
        out[i * LANES] = v == sentinel ? *escape : (unsigned char)v;
        escape += v == sentinel;
    }
    return escape;
}

/* One group of 16 zigzagged byte deltas; the caller has checked that
 * GROUP_READ_MAX bytes are readable at `in`. */
static const unsigned char *unpack_group(const unsigned char *in, unsigned mode, unsigned char *out)
{
    switch (mode) {
    case 0:
        for (unsigned i = 0; i < GROUP; i++)
            out[i * LANES] = 0;
        return in;
    case 1:
        return unpack_bits(in, out, 2);
    case 2:
        return unpack_bits(in, out, 4);
    default:
        for (unsigned i = 0; i < GROUP; i++)
            out[i * LANES] = in[i];
        return in + GROUP;
    }
}

/* The zigzagged deltas of one byte position across a block (groups * 16 of
 * them, the last group padded): the groups' 2-bit modes, then the groups. */
static const unsigned char *unpack_deltas(const unsigned char *p, const unsigned char *end,
                                          size_t groups, unsigned char *out)
{
    size_t mode_bytes = (groups + 3) / 4;
    if ((size_t)(end - p) < mode_bytes)
        return NULL;
    const unsigned char *modes = p;
    p += mode_bytes;
    for (size_t g = 0; g < groups; g++) {
        if ((size_t)(end - p) < GROUP_READ_MAX)
            return NULL;
        p = unpack_group(p, (modes[g / 4] >> (2 * (g % 4))) & 3u, out + g * GROUP * LANES);
    }
    return p;
}

/* Bytewise arithmetic in a word, no carry between bytes: unzigzag,
 * (z >> 1) ^ -(z & 1), and addition modulo 256. */
#define LOW7 0x7f7f7f7f7f7f7f7fu
#define HIGH 0x8080808080808080u
#define ONES 0x0101010101010101u

static uint64_t unzigzag_bytes(uint64_t z)
{
    return ((z >> 1) & LOW7) ^ ((z & ONES) * 0xffu);
}

static uint64_t add_bytes(uint64_t a, uint64_t b)
{
    return ((a & LOW7) + (b & LOW7)) ^ ((a ^ b) & HIGH);
}

/* Sums the deltas of 'width' byte positions (8, or the 4 of lanes 0-3)
 * down the block, from the vertex before it (`last`, which then becomes the
 * block's last vertex). The bytes of a narrower width sit in the same bytes
 * of the words in and out, and the arithmetic is bytewise, so the bytes
 * beyond it stay 0 whatever the byte order. Inlined with a constant
 * 'width', each width gets its own loop. */
static inline void add_deltas(const unsigned char *deltas, size_t count, unsigned char *out,
                              size_t stride, unsigned char *last, size_t width)
{
    uint64_t v = 0, z = 0;
    memcpy(&v, last, width);
    for (size_t i = 0; i < count; i++, out += stride) {
        memcpy(&z, deltas + i * LANES, width);
        v = add_bytes(v, unzigzag_bytes(z));
        memcpy(out, &v, width);
    }
    memcpy(last, &v, width);
}

/* A block is stored byte position by byte position (deinterleaved), each
 * byte a wrapping delta to the same byte of the vertex before; `last` is
 * that vertex, carried across blocks. */
static const unsigned char *decode_block(const unsigned char *p, const unsigned char *end,
                                         unsigned char *dst, size_t count, size_t stride,
                                         unsigned char *last)
{
    unsigned char deltas[BLOCK_MAX * LANES];
    size_t groups = (count + GROUP - 1) / GROUP;
    for (size_t k = 0; k < stride; k += LANES) {
        size_t lanes = stride - k < LANES ? stride - k : LANES;
        for (size_t lane = 0; lane < lanes; lane++) {
            p = unpack_deltas(p, end, groups, deltas + lane);
            if (!p)
                return NULL;
        }
        if (lanes == LANES)
            add_deltas(deltas, count, dst + k, stride, last + k, 8);
        else
            add_deltas(deltas, count, dst + k, stride, last + k, 4);
    }
    return p;
}

int oit_meshopt_decode_vertices(void *dst, size_t count, size_t stride, const unsigned char *src,
                                size_t bytes)
{
    if (stride < 4 || stride > BLOCK_MAX || stride % 4 || count > SIZE_MAX / stride)
        return OIT_MESHOPT_EARG;
    /* The size before the header, in meshopt's order, so that even the
     * error codes agree. */
    if (bytes < 1 + stride)
        return OIT_MESHOPT_ETRUNC;
    if ((src[0] & 0xf0u) != VERTEX_HEADER || (src[0] & 0x0fu) > VERTEX_VERSION)
        return OIT_MESHOPT_EHEADER;
    /* The vertex the first one is a delta to: the stream's last `stride`
     * bytes (the tail, zero-padded in front up to TAIL_MIN). */
    const unsigned char *end = src + bytes;
    unsigned char last[BLOCK_MAX];
    memcpy(last, end - stride, stride);
    const unsigned char *p = src + 1;
    size_t per_block = block_vertices(stride);
    unsigned char *out = dst;
    for (size_t done = 0; done < count;) {
        size_t n = count - done < per_block ? count - done : per_block;
        p = decode_block(p, end, out + done * stride, n, stride, last);
        if (!p)
            return OIT_MESHOPT_ETRUNC;
        done += n;
    }
    size_t tail = stride < TAIL_MIN ? TAIL_MIN : stride;
    return (size_t)(end - p) == tail ? 0 : OIT_MESHOPT_ETRAIL;
}

/* An unsigned LEB128 of at most 5 bytes: like meshopt, the fifth byte ends
 * it whatever its top bit says, and bits past 32 are dropped. */
static uint32_t read_varint(const unsigned char **at)
{
    const unsigned char *p = *at;
    uint32_t v = 0;
    for (unsigned i = 0; i < 5; i++) {
        unsigned char b = *p++;
        v |= (uint32_t)(b & 0x7fu) << (7 * i);
        if (b < 0x80u)
            break;
    }
    *at = p;
    return v;
}

static void store_index(void *dst, size_t i, size_t index_size, uint32_t index)
{
    unsigned char *out = (unsigned char *)dst + i * index_size;
    if (index_size == 2)
        memcpy(out, &(uint16_t){(uint16_t)index}, 2);
    else
        memcpy(out, &index, 4);
}

int oit_meshopt_decode_index_sequence(void *dst, size_t count, size_t index_size,
                                      const unsigned char *src, size_t bytes)
{
    if (index_size != 2 && index_size != 4)
        return OIT_MESHOPT_EARG;
    /* Header, at least a byte an index, tail. */
    if (bytes < 1 + SEQUENCE_TAIL || count > bytes - 1 - SEQUENCE_TAIL)
        return OIT_MESHOPT_ETRUNC;
    if ((src[0] & 0xf0u) != SEQUENCE_HEADER || (src[0] & 0x0fu) > SEQUENCE_VERSION)
        return OIT_MESHOPT_EHEADER;
    const unsigned char *p = src + 1;
    const unsigned char *data_end = src + bytes - SEQUENCE_TAIL;
    /* Two baselines, so that two interleaved runs (strips, line lists) each
     * stay small deltas: bit 0 picks one, the rest is a zigzagged delta. */
    uint32_t base[2] = {0, 0};
    for (size_t i = 0; i < count; i++) {
        if (p >= data_end)
            return OIT_MESHOPT_ETRUNC;
        uint32_t v = read_varint(&p);
        uint32_t *b = &base[v & 1u];
        v >>= 1;
        *b += (v >> 1) ^ (0u - (v & 1u));
        store_index(dst, i, index_size, *b);
    }
    return p == data_end ? 0 : OIT_MESHOPT_ETRAIL;
}
