/* Machinery shared by the streaming mesh readers (PLY, OBJ, OFF, STL).
 *
 * - oit_rd_budget: every buffer a reader holds (input buffer, triangle chunk,
 *   vertex table, polygon scratch) is charged against desc->memory_budget, so
 *   a file that needs more fails with OIT_ERR_NOMEM instead of exhausting the
 *   machine. Tables grow as data actually arrives: no allocation is sized by a
 *   count read from a file.
 * - oit_rd_stream: a large buffered reader over a FILE* that hands out
 *   NUL-terminated lines or tokens (text formats) or raw byte runs (binary
 *   formats), and knows the line number / byte offset for error messages.
 * - oit_rd_emitter: collects triangles into chunks of desc->chunk_triangles,
 *   drops triangles with a NaN/inf coordinate (counted in
 *   info->nonfinite_dropped), keeps oit_mesh_info up to date and calls the
 *   sink.
 *
 * Each reader also has a FILE* entry (oit_read_*_stream) so that fuzz targets
 * can feed it bytes from memory through fmemopen.
 */
#ifndef OIT_READERS_INTERNAL_H
#define OIT_READERS_INTERNAL_H

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "oit/mesh.h"

#define OIT_RD_DEFAULT_CHUNK ((size_t)65536)
#define OIT_RD_DEFAULT_BUDGET ((size_t)2 << 30)

typedef struct oit_rd_budget {
    size_t limit;
    size_t used;
} oit_rd_budget;

/* Grows *p (capacity *cap elements of elem bytes) to hold at least need
 * elements, doubling while the budget allows. On failure *p is unchanged and
 * err says "<name>: <what> needs N bytes, over the memory budget of B". */
oit_status oit_rd_grow(oit_rd_budget *b, void **p, size_t *cap, size_t elem, size_t need,
                       const char *name, const char *what, oit_error *err);
/* Returns the bytes of a buffer obtained with oit_rd_grow and frees it. */
void oit_rd_release(oit_rd_budget *b, void **p, size_t *cap, size_t elem);

typedef struct oit_rd_stream {
    FILE *f;
    const char *name;
    oit_rd_budget *budget;
    oit_error *err;
    char *buf;
    size_t cap;        /* allocated bytes; one spare byte for a final NUL */
    size_t pos, end;   /* unread bytes are buf[pos, end)                  */
    uint64_t base;     /* file offset of buf[0]                           */
    uint64_t line;     /* line number of buf[pos] (1-based)               */
    uint64_t tok_line; /* line of the last line or token handed out       */
    int eof;
    int continuation;  /* OBJ: a line ending in '\' continues             */
    const struct oit_gz *gz; /* set when f inflates a gzip file: read
                                errors then say what zlib found       */
} oit_rd_stream;

oit_status oit_rd_open(oit_rd_stream *s, FILE *f, const char *name, oit_rd_budget *b,
                       oit_error *err);
void oit_rd_close(oit_rd_stream *s);

/* Size of a seekable file (or fmemopen buffer) without moving its position;
 * -1 when the stream cannot seek. */
int64_t oit_rd_file_size(FILE *f);

/* Byte offset of the next unread byte. */
static inline uint64_t oit_rd_offset(const oit_rd_stream *s) { return s->base + s->pos; }

/* Next line, without its '\n' or "\r\n", NUL-terminated and writable until
 * the next call. *got is 0 at end of file. */
oit_status oit_rd_line(oit_rd_stream *s, char **line, int *got);
/* Next whitespace-separated token (across lines), NUL-terminated. */
oit_status oit_rd_token(oit_rd_stream *s, char **tok, int *got);
/* Makes n bytes visible at *p without consuming them; *avail says how many
 * there are (fewer only at end of file). */
oit_status oit_rd_peek(oit_rd_stream *s, size_t n, const unsigned char **p, size_t *avail);
/* Exactly n bytes; end of file first is a "truncated" format error naming
 * the offset and `what`. */
oit_status oit_rd_bytes_refill(oit_rd_stream *s, size_t n, const char *what,
                               const unsigned char **p);
static inline oit_status oit_rd_bytes(oit_rd_stream *s, size_t n, const char *what,
                                      const unsigned char **p)
{
    if (s->end - s->pos >= n) { /* the common case, kept inline */
        *p = (const unsigned char *)s->buf + s->pos;
        s->pos += n;
        return OIT_OK;
    }
    return oit_rd_bytes_refill(s, n, what, p);
}

/* "<name>: line N: ..." with N the line of the last line/token handed out. */
oit_status oit_rd_fail_line(oit_rd_stream *s, oit_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* "<name>: byte offset N: ...". */
oit_status oit_rd_fail_offset(oit_rd_stream *s, uint64_t offset, oit_status st,
                              const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* For the formats with a text and a binary flavour (PLY, legacy VTK): the
 * byte offset reached when binary, else the line. */
oit_status oit_rd_fail_here(oit_rd_stream *s, int binary, oit_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* The start of a text format: skips a UTF-8 byte-order mark (editors on
 * Windows write one) and refuses, naming the offset, a first block that
 * holds bytes no text has (NUL and other C0 controls but tab, CR, LF, FF,
 * VT and ESC), so that binary data given a text extension fails at once
 * instead of "parsing" into nothing. `format` names it ("OBJ"). */
oit_status oit_rd_text_begin(oit_rd_stream *s, const char *format);
/* Skips a UTF-8 byte-order mark at the current position, if there is one. */
oit_status oit_rd_skip_bom(oit_rd_stream *s);

/* A read that delivered no triangle is bad input (exit 3), with the reason:
 * no vertices and no faces, vertices but no faces, faces too small to make a
 * triangle, every triangle non-finite, or every triangle of zero area. */
oit_status oit_rd_require_triangles(const char *name, const oit_mesh_info *info,
                                    oit_error *err);

/* Text number parsing on NUL-terminated buffers. Each skips leading blanks,
 * advances *p past the number and returns 0 when no number is there or when
 * it is not followed by a blank, NUL or (for ints) one of `stops`. */
int oit_rd_float(char **p, float *out);
int oit_rd_double(char **p, double *out);
int oit_rd_int(char **p, int64_t *out, const char *stops);
/* Skips blanks; returns the first non-blank character (NUL at line end). */
static inline char oit_rd_skip_blanks(char **p)
{
    char *c = *p;
    while (*c == ' ' || *c == '\t' || *c == '\r' || *c == '\v' || *c == '\f')
        c++;
    *p = c;
    return *c;
}

/* Next blank-delimited word of a line: sets *w, returns its length (0 at
 * the end of the line) and advances *p past it. */
static inline size_t oit_rd_word(char **p, char **w)
{
    char *c = *p;
    oit_rd_skip_blanks(&c);
    *w = c;
    while (*c && *c != ' ' && *c != '\t' && *c != '\r' && *c != '\v' && *c != '\f')
        c++;
    *p = c;
    return (size_t)(c - *w);
}
static inline int oit_rd_word_eq(const char *w, size_t n, const char *lit)
{
    return strlen(lit) == n && memcmp(w, lit, n) == 0;
}
/* ASCII-only case folding: STL writers differ in case ("FACET", "facet"). */
static inline int oit_rd_word_eq_nocase(const char *w, size_t n, const char *lit)
{
    if (strlen(lit) != n) return 0;
    for (size_t i = 0; i < n; i++) {
        char a = w[i];
        if (a >= 'A' && a <= 'Z') a = (char)(a - 'A' + 'a');
        if (a != lit[i]) return 0;
    }
    return 1;
}

/* Little/big-endian scalars from unaligned bytes. */
static inline uint32_t oit_rd_u32(const unsigned char *b, int big_endian)
{
    return big_endian ? (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3]
                      : (uint32_t)b[3] << 24 | (uint32_t)b[2] << 16 | (uint32_t)b[1] << 8 | b[0];
}
static inline float oit_rd_f32(const unsigned char *b, int big_endian)
{
    uint32_t u = oit_rd_u32(b, big_endian);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Colour component to 8 bits: a float in 0..1, or an integer in 0..255. */
static inline uint8_t oit_rd_unit_to_u8(double v)
{
    if (!(v > 0.0)) return 0;
    if (v >= 1.0) return 255;
    return (uint8_t)(v * 255.0 + 0.5);
}
static inline uint8_t oit_rd_clamp_u8(double v)
{
    if (!(v > 0.0)) return 0;
    if (v >= 255.0) return 255;
    return (uint8_t)(v + 0.5);
}

/* A growable vertex table, the only structure indexed at random. */
typedef struct oit_rd_vtable {
    oit_vertex *v;
    size_t count, cap;
} oit_rd_vtable;

static inline oit_status oit_rd_vtable_push(oit_rd_vtable *t, oit_rd_budget *b,
                                            const oit_vertex *v, const char *name,
                                            oit_error *err)
{
    if (t->count == t->cap) {
        oit_status s = oit_rd_grow(b, (void **)&t->v, &t->cap, sizeof *t->v, t->count + 1,
                                   name, "vertex table", err);
        if (s != OIT_OK) return s;
    }
    t->v[t->count++] = *v;
    return OIT_OK;
}

typedef struct oit_rd_emitter {
    oit_triangle *tris;
    size_t count, cap; /* cap: triangles per chunk                  */
    size_t alloc;      /* allocated triangles (>= cap), for budget  */
    oit_rd_budget *budget;
    oit_triangle_sink sink;
    void *user;
    oit_mesh_info *info;
    oit_error *err;
} oit_rd_emitter;

oit_status oit_rd_emitter_init(oit_rd_emitter *e, const oit_read_desc *desc, oit_rd_budget *b,
                               oit_triangle_sink sink, void *user, oit_mesh_info *info,
                               const char *name, oit_error *err);
/* Delivers the partial chunk; call once at the end of a successful read. */
oit_status oit_rd_flush(oit_rd_emitter *e);
void oit_rd_emitter_free(oit_rd_emitter *e);

static inline oit_status oit_rd_emit(oit_rd_emitter *e, const oit_vertex *a, const oit_vertex *b,
                                     const oit_vertex *c)
{
    oit_triangle *t = &e->tris[e->count];
    t->v[0] = *a;
    t->v[1] = *b;
    t->v[2] = *c;
    if (!oit_triangle_is_finite(t)) {
        e->info->nonfinite_dropped++;
        return OIT_OK;
    }
    if (++e->count == e->cap)
        return oit_rd_flush(e);
    return OIT_OK;
}

/* What every reader holds: budget, input, output. Must not be moved once
 * opened (info may point into it). */
typedef struct oit_rd_ctx {
    oit_rd_budget budget;
    oit_rd_stream in;
    oit_rd_emitter out;
    oit_mesh_info *info; /* the caller's, or local_info when it passed NULL */
    oit_mesh_info local_info;
    const char *name;
    oit_error *err;
    int origin_set; /* info->origin picked from the first vertex */
    FILE *gz_file;  /* the inflating stream over the caller's FILE*, or NULL */
    struct oit_gz *gz;
    char gz_name[4096]; /* name + " (gzip)" for messages, unless it ends in .gz */
} oit_rd_ctx;

/* A position as read (double) to the float the reader delivers, relative to
 * the origin the first call picks (oit_mesh_origin_pick). */
static inline void oit_rd_position(oit_rd_ctx *c, const double in[3], float out[3])
{
    if (!c->origin_set) {
        oit_mesh_origin_pick(in, c->info->origin);
        c->origin_set = 1;
    }
    oit_mesh_position(c->info->origin, in, out);
}

/* Opens the context over f; a gzip file is inflated as it is read (the
 * readers see the inflated bytes: c->in.f is then not f). */
oit_status oit_rd_ctx_open(oit_rd_ctx *c, FILE *f, const char *name, const oit_read_desc *desc,
                           oit_triangle_sink sink, void *user, oit_mesh_info *info,
                           oit_error *err);
/* Flushes the last chunk when st is OIT_OK, frees everything, returns the
 * final status. */
oit_status oit_rd_ctx_close(oit_rd_ctx *c, oit_status st);
/* A whole read of f by parse, between oit_rd_ctx_open and oit_rd_ctx_close:
 * the FILE* entry of a reader whose parse needs the context alone. */
oit_status oit_rd_ctx_run(FILE *f, const char *name, const oit_read_desc *desc,
                          oit_triangle_sink sink, void *user, oit_mesh_info *info,
                          oit_error *err, oit_status (*parse)(oit_rd_ctx *c));

/* A reader's FILE* entry; `name` is used in messages only. For OBJ, dir is
 * the folder where mtllib files are looked up (NULL: material libraries are
 * skipped, e.g. when reading from memory). The other readers ignore dir. */
typedef oit_status oit_rd_file_fn(FILE *f, const char *name, const char *dir,
                                  const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                                  oit_mesh_info *info, oit_error *err);

/* Opens path for binary reading, runs fn(f, path, folder of path, ...) and
 * closes it; a file that cannot be opened is OIT_ERR_IO naming it. */
oit_status oit_rd_with_file(const char *path, oit_rd_file_fn *fn, const oit_read_desc *desc,
                            oit_triangle_sink sink, void *user, oit_mesh_info *info,
                            oit_error *err);

oit_rd_file_fn oit_read_ply_stream;
oit_rd_file_fn oit_read_obj_stream;
/* oit_read_obj_stream whose every mtllib statement reads mtl, from its
 * start, instead of a file: the MTL parser fed from memory (fuzz targets).
 * mtl_name names it in messages; mtl must be seekable (fmemopen). */
oit_status oit_read_obj_stream_mtl(FILE *f, const char *name, FILE *mtl, const char *mtl_name,
                                   const oit_read_desc *desc, oit_triangle_sink sink,
                                   void *user, oit_mesh_info *info, oit_error *err);
oit_rd_file_fn oit_read_off_stream;
oit_rd_file_fn oit_read_stl_stream;

#endif
