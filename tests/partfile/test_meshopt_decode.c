/* partfile/meshopt_decode.c against libmeshoptimizer, whose encoder is the
 * oracle: streams of many strides (fixed ones and random multiples of 4 up
 * to 256, past the first block, whose size depends on the stride),
 * counts and kinds of data (so that every
 * byte-group mode and the escape bytes occur, which the test counts) are
 * encoded with meshopt_encodeVertexBuffer / meshopt_encodeIndexSequence and
 * decoded by both decoders.
 *
 * What is asserted, for every stream below:
 *   - both decoders succeed or both fail;
 *   - when both succeed, their outputs are byte-identical;
 *   - for streams the encoder wrote, both succeed.
 * That includes the hostile ones: every truncation of a few streams, single-
 * byte corruptions (where both decoders may well accept garbage: the two
 * garbages must still be equal), random bytes behind a valid header, every
 * header byte, and wrong counts. Every input is copied into a buffer of its
 * exact size and every output buffer is allocated at its exact size, so an
 * ASan build (OIT_SANITIZE) also proves that ours never reads or writes
 * outside them. meshopt's own error codes (-1, -2, -3) are compared too but
 * only counted: callers tell only 0 from non-zero.
 *
 * Also prints the decode speed of both on a large buffer (not asserted: the
 * machines are shared).
 *
 * usage: test_meshopt_decode [--write-corpus DIR]
 * --write-corpus writes the fuzz seeds (fuzz_meshopt_decode.c's layout) to
 * DIR and exits.
 */
#include "partfile/meshopt_decode.h"
#include "tests/partfile/meshopt_pair.h"

#include "base/clock.h"

#include <meshoptimizer.h>

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- bookkeeping ------------------------------------------------------------ */

typedef struct tally {
    unsigned long vertex_streams, index_streams; /* encoder-written, compared */
    unsigned long hostile;                       /* damaged or random, compared */
    unsigned long both_accept_hostile;           /* ... that both decoded "fine" */
    unsigned long code_differs;                  /* both failed, different codes */
    unsigned long modes[4], escapes;             /* in the encoded vertex streams */
    unsigned long failures;
} tally;

static void fail(tally *t, const char *fmt, ...)
{
    if (t->failures++ >= 30)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("FAIL ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) {
        fprintf(stderr, "out of memory (%zu bytes)\n", n);
        exit(2);
    }
    return p;
}

static unsigned char *dup_bytes(const unsigned char *s, size_t n)
{
    unsigned char *d = xmalloc(n);
    if (n)
        memcpy(d, s, n);
    return d;
}

/* splitmix64: a fixed seed, state held by the caller. */
typedef struct rng {
    uint64_t s;
} rng;

static uint64_t rng_next(rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static uint32_t rng_below(rng *r, uint32_t n)
{
    return (uint32_t)(rng_next(r) % n);
}

/* ---- comparing the two decoders --------------------------------------------- */

/* Compares both decoders on one input (copied to an exact-size buffer);
 * returns the common result, or 1 when they disagree. */
static int compare_pair(tally *t, const meshopt_pair *p, const char *name, const unsigned char *enc,
                        size_t bytes, size_t count, size_t size)
{
    unsigned char *src = dup_bytes(enc, bytes);
    int ra, rb;
    int differ = meshopt_pair_run(p, src, bytes, count, size, &ra, &rb);
    int rc = ra == 0 ? rb : ra;
    if ((ra == 0) != (rb == 0)) {
        fail(t, "%s: %s count %zu %s %zu bytes %zu: meshopt %d, ours %d", name, p->what, count,
             p->size_name, size, bytes, ra, rb);
        rc = 1;
    } else if (differ) {
        fail(t, "%s: %s count %zu %s %zu: outputs differ", name, p->what, count, p->size_name,
             size);
        rc = 1;
    } else if (ra != rb) {
        t->code_differs++;
    }
    free(src);
    return rc;
}

static int compare_vertices(tally *t, const char *name, const unsigned char *enc, size_t bytes,
                            size_t count, size_t stride)
{
    return compare_pair(t, &MESHOPT_VERTICES, name, enc, bytes, count, stride);
}

static int compare_indices(tally *t, const char *name, const unsigned char *enc, size_t bytes,
                           size_t count, size_t index_size)
{
    return compare_pair(t, &MESHOPT_INDICES, name, enc, bytes, count, index_size);
}

/* ---- hostile variants of one stream ----------------------------------------- */

/* A stream's decoder, for the damage loops to be shared by both codecs. */
typedef int (*compare_fn)(tally *, const char *, const unsigned char *, size_t, size_t, size_t);

static void hostile(tally *t, compare_fn cmp, const char *name, const unsigned char *enc,
                    size_t bytes, size_t count, size_t width)
{
    size_t runs = 0, accepted = 0;
    /* Every truncation, and the stream with a byte too many. */
    unsigned char *buf = xmalloc(bytes + 1);
    memcpy(buf, enc, bytes);
    buf[bytes] = 0;
    for (size_t len = 0; len <= bytes + 1; len++, runs++)
        if (len != bytes)
            accepted += cmp(t, name, buf, len, count, width) == 0;
    /* Single-byte corruptions: every byte of small streams, a sample of big. */
    static const unsigned char flips[] = {0x01, 0x02, 0x10, 0x80, 0xff};
    size_t step = bytes / 1500 + 1;
    for (size_t at = 0; at < bytes; at += step) {
        for (size_t f = 0; f < sizeof flips; f++, runs++) {
            buf[at] ^= flips[f];
            accepted += cmp(t, name, buf, bytes, count, width) == 0;
            buf[at] ^= flips[f];
        }
    }
    /* Wrong counts: one less, one and 17 more. */
    for (size_t c = count ? count - 1 : 0; c <= count + 17; c += c < count + 1 ? 2 : 16, runs++)
        accepted += cmp(t, name, buf, bytes, c, width) == 0;
    free(buf);
    t->hostile += runs;
    t->both_accept_hostile += accepted;
}

/* A stream the library's encoder wrote (bytes 0: it failed) must be taken
 * alike by both decoders; with damage, so must its hostile variants.
 * Returns cmp's result for the stream itself (0: both decoded it). */
static int check_encoded(tally *t, compare_fn cmp, const char *name, const unsigned char *enc,
                         size_t bytes, size_t count, size_t width, int damage)
{
    if (!bytes)
        fail(t, "%s: the encoder failed", name);
    int rc = cmp(t, name, enc, bytes, count, width);
    if (rc != 0)
        fail(t, "%s: an encoder-written stream is refused", name);
    if (damage)
        hostile(t, cmp, name, enc, bytes, count, width);
    return rc;
}

/* ---- vertex data ------------------------------------------------------------ */

enum vpattern { V_RANDOM, V_ZERO, V_CONST, V_SMOOTH, V_MIXED, V_INTS, V_SPIKES, V_COUNT };
static const char *const vpattern_name[V_COUNT] = {"random", "zero", "const", "smooth",
                                                   "mixed",  "ints", "spikes"};

/* A wrapping byte delta of a group's kind: 0 none, 1 fits 2 bits, 2 fits 4
 * bits, 3 anything; kinds 1 and 2 now and then overflow into an escape. */
static unsigned char kind_delta(rng *r, unsigned kind)
{
    static const int range[4] = {0, 1, 7, 127};
    int span = range[kind];
    if (kind && kind < 3 && rng_below(r, 8) == 0)
        span = 127;
    return span ? (unsigned char)((int)rng_below(r, 2u * span + 1) - span) : 0;
}

static void fill_mixed(rng *r, unsigned char *v, size_t count, size_t stride)
{
    unsigned kind[256]; /* per byte position, drawn anew each group of 16 */
    for (size_t i = 0; i < count; i++) {
        for (size_t k = 0; k < stride; k++) {
            if (i % 16 == 0)
                kind[k] = rng_below(r, 4);
            unsigned char prev = i ? v[(i - 1) * stride + k] : (unsigned char)rng_next(r);
            v[i * stride + k] = (unsigned char)(prev + kind_delta(r, kind[k]));
        }
    }
}

static void fill_vertices(rng *r, enum vpattern p, unsigned char *v, size_t count, size_t stride)
{
    size_t n = count * stride;
    switch (p) {
    case V_RANDOM:
        for (size_t i = 0; i < n; i++)
            v[i] = (unsigned char)rng_next(r);
        break;
    case V_ZERO:
        memset(v, 0, n);
        break;
    case V_CONST:
        for (size_t i = 0; i < n; i++)
            v[i] = i < stride ? (unsigned char)rng_next(r) : v[i - stride];
        break;
    case V_SMOOTH:
        for (size_t i = 0; i < n / 4; i++) {
            size_t vert = i / (stride / 4), c = i % (stride / 4);
            float f = (float)(sin(vert * 0.001 + c) * 100.0 + c * 0.5);
            memcpy(v + 4 * i, &f, 4);
        }
        break;
    case V_MIXED:
        fill_mixed(r, v, count, stride);
        break;
    case V_INTS:
        for (size_t i = 0; i < n / 4; i++) {
            uint32_t x = (uint32_t)(i / (stride / 4)) * (uint32_t)(1 + 977 * (i % (stride / 4)));
            memcpy(v + 4 * i, &x, 4);
        }
        break;
    default: /* V_SPIKES: constant, with an odd random byte (escapes) */
        fill_vertices(r, V_CONST, v, count, stride);
        for (size_t i = stride; i < n; i++)
            if (rng_below(r, 40) == 0)
                v[i] = (unsigned char)rng_next(r);
        break;
    }
}

/* Counts the group modes and escapes of an encoder-written stream (the walk
 * of the decoder, without its checks): evidence that the data above covers
 * every path of the bitstream. */
static void count_modes(tally *t, const unsigned char *s, size_t count, size_t stride)
{
    size_t per_block = (8192 / stride) & ~(size_t)15;
    per_block = per_block < 256 ? per_block : 256;
    const unsigned char *p = s + 1;
    for (size_t done = 0; done < count; done += per_block) {
        size_t n = count - done < per_block ? count - done : per_block, groups = (n + 15) / 16;
        for (size_t k = 0; k < stride; k++) {
            const unsigned char *modes = p;
            p += (groups + 3) / 4;
            for (size_t g = 0; g < groups; g++) {
                unsigned mode = (modes[g / 4] >> (2 * (g % 4))) & 3u, bits = mode * 2;
                t->modes[mode]++;
                if (mode == 0 || mode == 3) {
                    p += mode == 3 ? 16 : 0;
                    continue;
                }
                size_t sentinels = 0;
                for (unsigned i = 0; i < 16; i++)
                    sentinels += ((p[i * bits / 8] >> (8 - bits - i * bits % 8)) &
                                  ((1u << bits) - 1)) == (1u << bits) - 1;
                t->escapes += sentinels;
                p += 2 * bits + sentinels;
            }
        }
    }
}

static unsigned char *encode_vertices(const unsigned char *v, size_t count, size_t stride,
                                      size_t *bytes)
{
    size_t cap = meshopt_encodeVertexBufferBound(count, stride);
    unsigned char *enc = xmalloc(cap);
    *bytes = meshopt_encodeVertexBuffer(enc, cap, v, count, stride);
    return enc;
}

static void vertex_case(tally *t, rng *r, enum vpattern p, size_t count, size_t stride, int damage)
{
    char name[96];
    snprintf(name, sizeof name, "vertices %s x%zu stride %zu", vpattern_name[p], count, stride);
    unsigned char *v = xmalloc(count * stride);
    fill_vertices(r, p, v, count, stride);
    size_t bytes;
    unsigned char *enc = encode_vertices(v, count, stride, &bytes);
    count_modes(t, enc, count, stride);
    unsigned char *out = xmalloc(count * stride);
    if (check_encoded(t, compare_vertices, name, enc, bytes, count, stride, damage) == 0 &&
        (oit_meshopt_decode_vertices(out, count, stride, enc, bytes) ||
         (count && memcmp(out, v, count * stride))))
        fail(t, "%s: does not round-trip", name);
    t->vertex_streams++;
    free(out);
    free(enc);
    free(v);
}

/* Strides whose block (8192 / stride vertices, rounded down to whole groups
 * of 16, at most 256) is not a power of two: 40 takes 192 vertices, 48 160,
 * 100 80 and a last lane group of 4 bytes; below 32 bytes and at powers of
 * two every rounding gives 256 or 8192 / stride alike. */
static void vertex_cases(tally *t, rng *r)
{
    static const size_t strides[] = {4, 8, 12, 16, 20, 32, 40, 48, 64, 100, 256};
    static const size_t counts[] = {0, 1, 2, 15, 16, 17, 31, 255, 256, 257, 1000, 5003};
    for (size_t s = 0; s < sizeof strides / sizeof *strides; s++)
        for (size_t c = 0; c < sizeof counts / sizeof *counts; c++)
            for (int p = 0; p < V_COUNT; p++) {
                /* damage a few: every truncation is quadratic in the size
                 * (of 257 vertices, only at the strides damaged before 40
                 * and 48 came: those add seconds) */
                size_t n = counts[c];
                int long_257 = n == 257 && (strides[s] == 40 || strides[s] == 48);
                int damage = strides[s] <= 64 && (n == 1 || n == 17 || (n == 257 && !long_257)) &&
                             (p == V_MIXED || p == V_SMOOTH || (p == V_ZERO && n == 17));
                vertex_case(t, r, (enum vpattern)p, counts[c], strides[s], damage);
            }
    /* A stream big enough that blocks differ in their modes. */
    vertex_case(t, r, V_MIXED, 20000, 12, 0);
}

/* The property over every stride the codec takes (4..256, a multiple of 4)
 * with more vertices than one block holds, so that the second block starts
 * where the block size says: random counts past a block or two, random
 * data of every pattern. */
static void random_stride_cases(tally *t, rng *r)
{
    for (int i = 0; i < 160; i++) {
        size_t stride = 4 * (1 + rng_below(r, 64));
        size_t block = (8192 / stride) & ~(size_t)15;
        block = block < 256 ? block : 256;
        size_t count = block + 1 + rng_below(r, (uint32_t)(2 * block + 300));
        enum vpattern p = (enum vpattern)rng_below(r, V_COUNT);
        vertex_case(t, r, p, count, stride, 0);
    }
}

/* ---- index data ------------------------------------------------------------- */

enum ipattern { I_RANDOM, I_MONOTONE, I_STEPS, I_STRIP, I_JUMPS, I_MAX, I_GRID, I_COUNT };
static const char *const ipattern_name[I_COUNT] = {"random", "monotone", "steps", "strip",
                                                   "jumps",  "max",      "grid"};

static uint32_t index_at(rng *r, enum ipattern p, size_t i, uint32_t prev, uint32_t max)
{
    switch (p) {
    case I_RANDOM:
        return (uint32_t)rng_next(r) & max;
    case I_MONOTONE:
        return (uint32_t)i & max;
    case I_STEPS:
        return (prev + rng_below(r, 300)) & max;
    case I_STRIP: /* two interleaved runs: both baselines */
        return (uint32_t)(i % 2 ? i / 2 : max / 2 + i / 2) & max;
    case I_JUMPS:
        return i % 3 == 0 ? 0 : i % 3 == 1 ? max : (uint32_t)rng_next(r) & max;
    case I_MAX:
        return max;
    default: { /* I_GRID: two triangles a quad of a 100-wide grid */
        size_t q = i / 6, x = q % 99, y = q / 99, corner[6] = {0, 1, 100, 1, 101, 100};
        return (uint32_t)(y * 100 + x + corner[i % 6]) & max;
    }
    }
}

static void index_case(tally *t, rng *r, enum ipattern p, size_t count, size_t index_size,
                       int version, int damage)
{
    char name[96];
    snprintf(name, sizeof name, "indices v%d %s x%zu size %zu", version, ipattern_name[p], count,
             index_size);
    uint32_t max = index_size == 2 ? 0xffffu : 0xffffffffu;
    uint32_t *idx = xmalloc(count * 4);
    for (size_t i = 0; i < count; i++)
        idx[i] = index_at(r, p, i, i ? idx[i - 1] : 0, max);
    meshopt_encodeIndexVersion(version);
    size_t cap = meshopt_encodeIndexSequenceBound(count, (size_t)max);
    unsigned char *enc = xmalloc(cap);
    size_t bytes = meshopt_encodeIndexSequence(enc, cap, idx, count);
    check_encoded(t, compare_indices, name, enc, bytes, count, index_size, damage);
    t->index_streams++;
    free(enc);
    free(idx);
}

static void index_cases(tally *t, rng *r)
{
    static const size_t counts[] = {0, 1, 2, 3, 4, 5, 6, 16, 17, 100, 999, 10002};
    for (int version = 0; version <= 1; version++)
        for (size_t size = 2; size <= 4; size += 2)
            for (size_t c = 0; c < sizeof counts / sizeof *counts; c++)
                for (int p = 0; p < I_COUNT; p++)
                    index_case(t, r, (enum ipattern)p, counts[c], size, version,
                               version == 1 && counts[c] == 100);
}

/* ---- random bytes and header bytes ------------------------------------------ */

static void garbage_cases(tally *t, rng *r)
{
    unsigned char buf[2048];
    unsigned long runs = 0, accepted = 0;
    for (int n = 0; n < 20000; n++, runs++) {
        size_t len = 1 + rng_below(r, sizeof buf), count = rng_below(r, n % 2 ? 40 : 700);
        /* sparse bytes reach the zero and 2-bit modes, dense ones the raw one */
        uint32_t density = 1 + rng_below(r, 8);
        for (size_t i = 0; i < len; i++)
            buf[i] = rng_below(r, 8) < density ? (unsigned char)rng_next(r) : 0;
        if (n % 2) {
            buf[0] = (unsigned char)(0xd0 + rng_below(r, 3));
            accepted +=
                compare_indices(t, "random index bytes", buf, len, count, n % 4 == 1 ? 2 : 4) == 0;
        } else {
            buf[0] = (unsigned char)(0xa0 + rng_below(r, 2));
            accepted += compare_vertices(t, "random vertex bytes", buf, len, count,
                                         4 * (1 + rng_below(r, 64))) == 0;
        }
    }
    /* Every header byte before a valid stream of each kind. */
    rng_next(r);
    unsigned char v[16 * 20] = {0}, *venc;
    size_t vbytes;
    venc = encode_vertices(v, 20, 16, &vbytes);
    uint32_t idx[5] = {1, 2, 3, 70000, 0};
    unsigned char ienc[64];
    meshopt_encodeIndexVersion(1);
    size_t ibytes = meshopt_encodeIndexSequence(ienc, sizeof ienc, idx, 5);
    for (unsigned h = 0; h < 256; h++, runs += 2) {
        venc[0] = ienc[0] = (unsigned char)h;
        accepted += compare_vertices(t, "header byte", venc, vbytes, 20, 16) == 0;
        accepted += compare_indices(t, "header byte", ienc, ibytes, 5, 4) == 0;
    }
    free(venc);
    t->hostile += runs;
    t->both_accept_hostile += accepted;
}

/* ---- speed ------------------------------------------------------------------ */

typedef int (*decode_fn)(void *, size_t, size_t, const unsigned char *, size_t);

static double best_seconds(decode_fn f, void *dst, size_t count, size_t width,
                           const unsigned char *src, size_t bytes)
{
    double best = 1e9;
    for (int rep = 0; rep < 11; rep++) {
        double t0 = oit_time_s();
        if (f(dst, count, width, src, bytes))
            return -1;
        double dt = oit_time_s() - t0;
        best = dt < best ? dt : best;
    }
    return best;
}

static void speed(tally *t, rng *r)
{
    size_t nv = 1000000, stride = 16, ni = 3000000, bytes;
    unsigned char *v = xmalloc(nv * stride), *out = xmalloc(nv * stride);
    fill_vertices(r, V_SMOOTH, v, nv, stride);
    unsigned char *enc = encode_vertices(v, nv, stride, &bytes);
    double a = best_seconds(meshopt_decodeVertexBuffer, out, nv, stride, enc, bytes);
    double b = best_seconds(oit_meshopt_decode_vertices, out, nv, stride, enc, bytes);
    if (a < 0 || b < 0 || memcmp(out, v, nv * stride))
        fail(t, "speed: the large vertex buffer does not decode");
    printf("speed: %zu vertices of %zu bytes (%zu encoded): meshopt %.2f ms (%.0f MB/s), "
           "ours %.2f ms (%.0f MB/s), ours/meshopt %.2fx\n",
           nv, stride, bytes, a * 1e3, nv * stride / a * 1e-6, b * 1e3, nv * stride / b * 1e-6,
           b / a);
    free(enc);
    uint32_t *idx = xmalloc(ni * 4);
    for (size_t i = 0; i < ni; i++)
        idx[i] = index_at(r, I_GRID, i, 0, 0xffffffffu);
    size_t cap = meshopt_encodeIndexSequenceBound(ni, 1u << 30);
    enc = xmalloc(cap);
    bytes = meshopt_encodeIndexSequence(enc, cap, idx, ni);
    free(out);
    out = xmalloc(ni * 4);
    a = best_seconds(meshopt_decodeIndexSequence, out, ni, 4, enc, bytes);
    b = best_seconds(oit_meshopt_decode_index_sequence, out, ni, 4, enc, bytes);
    if (a < 0 || b < 0 || memcmp(out, idx, ni * 4))
        fail(t, "speed: the large index sequence does not decode");
    printf("speed: %zu indices (%zu encoded): meshopt %.2f ms, ours %.2f ms, ours/meshopt "
           "%.2fx\n",
           ni, bytes, a * 1e3, b * 1e3, b / a);
    free(idx);
    free(enc);
    free(out);
    free(v);
}

/* ---- fuzz seeds ------------------------------------------------------------- */

/* One seed in fuzz_meshopt_decode.c's layout: the 6-byte parameter header,
 * then the stream. */
static int write_seed(const char *dir, const char *file, const unsigned char param[6],
                      const unsigned char *enc, size_t bytes)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(param, 1, 6, f) == 6 && fwrite(enc, 1, bytes, f) == bytes;
    if (f && fclose(f))
        ok = 0;
    if (!ok)
        fprintf(stderr, "cannot write %s\n", path);
    return ok ? 0 : 1;
}

static int write_corpus(const char *dir, rng *r)
{
    static const struct {
        enum vpattern p;
        size_t count, stride;
    } vs[] = {{V_MIXED, 40, 12}, {V_SMOOTH, 300, 16}, {V_SPIKES, 17, 4}, {V_ZERO, 0, 32}};
    int bad = 0;
    for (size_t s = 0; s < sizeof vs / sizeof *vs; s++) {
        unsigned char *v = xmalloc(vs[s].count * vs[s].stride), param[6] = {0};
        fill_vertices(r, vs[s].p, v, vs[s].count, vs[s].stride);
        size_t bytes;
        unsigned char *enc = encode_vertices(v, vs[s].count, vs[s].stride, &bytes);
        param[0] = (unsigned char)(vs[s].stride / 4 - 1);
        param[1] = (unsigned char)vs[s].count;
        param[2] = (unsigned char)(vs[s].count >> 8);
        char file[64];
        snprintf(file, sizeof file, "vertices_%s_%zu_%zu", vpattern_name[vs[s].p], vs[s].count,
                 vs[s].stride);
        bad |= write_seed(dir, file, param, enc, bytes);
        free(enc);
        free(v);
    }
    static const struct {
        enum ipattern p;
        size_t count, size;
    } is[] = {{I_STRIP, 30, 2}, {I_JUMPS, 12, 4}, {I_GRID, 120, 4}};
    meshopt_encodeIndexVersion(1);
    for (size_t s = 0; s < sizeof is / sizeof *is; s++) {
        uint32_t idx[120];
        unsigned char enc[1024], param[6] = {0};
        for (size_t i = 0; i < is[s].count; i++)
            idx[i] = index_at(r, is[s].p, i, i ? idx[i - 1] : 0,
                              is[s].size == 2 ? 0xffffu : 0xffffffffu);
        size_t bytes = meshopt_encodeIndexSequence(enc, sizeof enc, idx, is[s].count);
        param[3] = is[s].size == 4;
        param[4] = (unsigned char)is[s].count;
        char file[64];
        snprintf(file, sizeof file, "indices_%s_%zu_%zu", ipattern_name[is[s].p], is[s].count,
                 is[s].size);
        bad |= write_seed(dir, file, param, enc, bytes);
    }
    return bad;
}

int main(int argc, char **argv)
{
    rng r = {20240611u};
    if (argc == 3 && !strcmp(argv[1], "--write-corpus"))
        return write_corpus(argv[2], &r);
    if (argc != 1) {
        fprintf(stderr, "usage: test_meshopt_decode [--write-corpus DIR]\n");
        return 2;
    }
    tally t = {0};
    vertex_cases(&t, &r);
    random_stride_cases(&t, &r);
    index_cases(&t, &r);
    garbage_cases(&t, &r);
    printf("compared: %lu encoded vertex streams, %lu encoded index sequences, %lu hostile "
           "inputs (both decoders accepted %lu of them, with equal output)\n",
           t.vertex_streams, t.index_streams, t.hostile, t.both_accept_hostile);
    printf("vertex groups: %lu zero, %lu 2-bit, %lu 4-bit, %lu raw; %lu escape bytes\n", t.modes[0],
           t.modes[1], t.modes[2], t.modes[3], t.escapes);
    printf("failures where the error codes differ (not asserted): %lu\n", t.code_differs);
    for (int m = 0; m < 4; m++)
        if (!t.modes[m])
            fail(&t, "no vertex group of mode %d was encoded: the data misses a path", m);
    if (!t.escapes)
        fail(&t, "no escape byte was encoded: the data misses a path");
    speed(&t, &r);
    if (t.failures)
        fprintf(stderr, "%lu failures\n", t.failures);
    return t.failures != 0;
}
