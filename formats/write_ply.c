/* Streaming binary PLY writer (contract in ply_writer.h).
 *
 * The header is written last, into a slot reserved at open: its size is that
 * of a header with 20-digit counts, and a padding comment absorbs the
 * difference, so vertices can stream to the final file immediately while
 * faces wait in a side file that close appends. Encoding is explicit byte by
 * byte so the output is little-endian on any host. */
#include "formats/ply_writer.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { WBUF_BYTES = 1 << 20, MAX_COMMENT = 256, MAX_HEADER = 1024 };

typedef struct wfile {
    FILE *f;
    char *path;
    uint8_t *buf;
    size_t len;
    uint64_t bytes; /* flushed to f */
} wfile;

struct oit_ply_writer {
    oit_ply_writer_desc desc;
    char *final_path;
    char *comment;
    wfile main, faces;
    size_t header_bytes;
    uint64_t vertices, face_count;
    int failed; /* a write failed: close must not publish the file */
};

static char *str_concat(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    char *s = malloc(na + nb + 1);
    if (s) {
        memcpy(s, a, na);
        memcpy(s + na, b, nb + 1);
    }
    return s;
}

static oit_status wfile_open(wfile *wf, const char *path, oit_error *err)
{
    wf->path = str_concat(path, "");
    wf->buf = malloc(WBUF_BYTES);
    if (!wf->path || !wf->buf)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate write buffer", path);
    wf->f = fopen(path, "w+b");
    if (!wf->f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    return OIT_OK;
}

static oit_status wfile_flush(wfile *wf, oit_error *err)
{
    if (wf->len && fwrite(wf->buf, 1, wf->len, wf->f) != wf->len)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed at byte %llu: %s",
                             wf->path, (unsigned long long)wf->bytes,
                             strerror(errno));
    wf->bytes += wf->len;
    wf->len = 0;
    return OIT_OK;
}

/* Makes room for n bytes (n <= WBUF_BYTES) and returns where to put them. */
static uint8_t *wfile_reserve(wfile *wf, size_t n, oit_error *err)
{
    if (wf->len + n > WBUF_BYTES && wfile_flush(wf, err))
        return NULL;
    uint8_t *p = wf->buf + wf->len;
    wf->len += n;
    return p;
}

/* Closes and optionally removes; returns the first error. */
static oit_status wfile_close(wfile *wf, int remove_it, oit_error *err)
{
    oit_status s = OIT_OK;
    if (wf->f && fclose(wf->f) != 0)
        s = oit_error_set(err, OIT_ERR_IO, "%s: close failed: %s", wf->path, strerror(errno));
    if (wf->path && remove_it)
        remove(wf->path);
    free(wf->path);
    free(wf->buf);
    memset(wf, 0, sizeof *wf);
    return s;
}

static uint8_t *put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
    return p + 4;
}

static uint8_t *put_f32(uint8_t *p, float f)
{
    uint32_t v;
    memcpy(&v, &f, 4);
    return put_u32(p, v);
}

static uint8_t *put_f64(uint8_t *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, 8);
    p = put_u32(p, (uint32_t)v);
    return put_u32(p, (uint32_t)(v >> 32));
}

/* The header for the given counts, padded to exactly `size` bytes when size
 * is nonzero; returns its length (0 when it does not fit). */
static size_t format_header(const oit_ply_writer *w, uint64_t nv, uint64_t nf,
                            size_t size, char *out)
{
    static const char *rgba = "property uchar red\nproperty uchar green\n"
                              "property uchar blue\nproperty uchar alpha\n";
    const char *pos = w->desc.vertex_double ? "double" : "float";
    char head[MAX_HEADER], tail[MAX_HEADER];
    int nh = snprintf(head, sizeof head, "ply\nformat binary_little_endian 1.0\n%s%s%s",
                      w->comment ? "comment " : "", w->comment ? w->comment : "",
                      w->comment ? "\n" : "");
    int nt = snprintf(tail, sizeof tail,
                      "element vertex %llu\nproperty %s x\nproperty %s y\n"
                      "property %s z\n%selement face %llu\n"
                      "property list uchar int vertex_indices\n%send_header\n",
                      (unsigned long long)nv, pos, pos, pos, w->desc.vertex_rgba ? rgba : "",
                      (unsigned long long)nf, w->desc.face_rgba ? rgba : "");
    static const char pad_open[] = "comment pad";
    size_t fixed = (size_t)nh + (size_t)nt + sizeof pad_open; /* + newline */
    size_t total = size ? size : fixed;
    if (nh < 0 || nt < 0 || fixed > total || total > MAX_HEADER)
        return 0;
    size_t dots = total - fixed;
    char *p = out;
    memcpy(p, head, (size_t)nh), p += nh;
    memcpy(p, pad_open, sizeof pad_open - 1), p += sizeof pad_open - 1;
    memset(p, '.', dots), p += dots;
    *p++ = '\n';
    memcpy(p, tail, (size_t)nt), p += nt;
    return (size_t)(p - out);
}

static oit_status check_comment(const char *c, const char *path, oit_error *err)
{
    if (!c)
        return OIT_OK;
    if (strlen(c) > MAX_COMMENT || strpbrk(c, "\r\n"))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: header comment must be one line of at most %d characters",
                             path, MAX_COMMENT);
    return OIT_OK;
}

oit_status oit_ply_writer_open(const oit_ply_writer_desc *desc,
                               oit_ply_writer **out, oit_error *err)
{
    *out = NULL;
    if (!desc || !desc->path || !desc->path[0])
        return oit_error_set(err, OIT_ERR_ARGUMENT, "ply writer: no output path");
    oit_status s = check_comment(desc->comment, desc->path, err);
    if (s)
        return s;
    oit_ply_writer *w = calloc(1, sizeof *w);
    if (!w)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate writer", desc->path);
    w->desc = *desc;
    w->final_path = str_concat(desc->path, "");
    w->comment = desc->comment ? str_concat(desc->comment, "") : NULL;
    char *tmp = str_concat(desc->path, ".tmp");
    char *ftmp = str_concat(desc->path, ".faces.tmp");
    w->desc.path = w->final_path;
    w->desc.comment = w->comment;
    if (!w->final_path || !tmp || !ftmp || (desc->comment && !w->comment))
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate writer", desc->path);
    if (!s)
        s = wfile_open(&w->main, tmp, err);
    if (!s)
        s = wfile_open(&w->faces, ftmp, err);
    free(tmp);
    free(ftmp);
    if (!s) {
        char hdr[MAX_HEADER];
        /* Reserve room for the largest counts a uint64 can print. */
        w->header_bytes = format_header(w, UINT64_MAX, UINT64_MAX, 0, hdr);
        memset(wfile_reserve(&w->main, w->header_bytes, err), 0, w->header_bytes);
    }
    if (s) {
        oit_ply_writer_abort(w);
        return s;
    }
    *out = w;
    return OIT_OK;
}

static oit_status fail(oit_ply_writer *w, oit_status s)
{
    w->failed = 1;
    return s;
}

oit_status oit_ply_writer_add_vertices(oit_ply_writer *w, const float *xyz,
                                       const uint8_t *rgba, size_t count,
                                       uint32_t *first, oit_error *err)
{
    if (first)
        *first = (uint32_t)w->vertices;
    if (count > OIT_PLY_WRITER_MAX_VERTICES - w->vertices)
        return fail(w, oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                     "%s: more than %llu vertices do not fit PLY int indices",
                                     w->final_path, (unsigned long long)OIT_PLY_WRITER_MAX_VERTICES));
    if (w->desc.vertex_rgba && !rgba && count)
        return fail(w, oit_error_set(err, OIT_ERR_ARGUMENT, "%s: vertex colours missing",
                                     w->final_path));
    size_t stride = (w->desc.vertex_double ? 24 : 12) + (w->desc.vertex_rgba ? 4 : 0);
    for (size_t i = 0; i < count; i++) {
        uint8_t *p = wfile_reserve(&w->main, stride, err);
        if (!p)
            return fail(w, err ? err->status : OIT_ERR_IO);
        for (int k = 0; k < 3; k++)
            p = w->desc.vertex_double ? put_f64(p, w->desc.offset[k] + (double)xyz[3 * i + k])
                                      : put_f32(p, xyz[3 * i + k]);
        if (w->desc.vertex_rgba)
            memcpy(p, rgba + 4 * i, 4);
    }
    w->vertices += count;
    return OIT_OK;
}

oit_status oit_ply_writer_add_faces(oit_ply_writer *w, const uint32_t *idx,
                                    const uint8_t *rgba, size_t count,
                                    oit_error *err)
{
    if (w->desc.face_rgba && !rgba && count)
        return fail(w, oit_error_set(err, OIT_ERR_ARGUMENT, "%s: face colours missing",
                                     w->final_path));
    size_t stride = w->desc.face_rgba ? 17 : 13;
    for (size_t i = 0; i < count; i++) {
        const uint32_t *t = idx + 3 * i;
        if (t[0] >= w->vertices || t[1] >= w->vertices || t[2] >= w->vertices)
            return fail(w, oit_error_set(err, OIT_ERR_ARGUMENT,
                                         "%s: face %llu: vertex index out of range (%u %u %u, %llu vertices added)",
                                         w->final_path, (unsigned long long)(w->face_count + i),
                                         t[0], t[1], t[2], (unsigned long long)w->vertices));
        uint8_t *p = wfile_reserve(&w->faces, stride, err);
        if (!p)
            return fail(w, err ? err->status : OIT_ERR_IO);
        *p++ = 3;
        p = put_u32(p, t[0]);
        p = put_u32(p, t[1]);
        p = put_u32(p, t[2]);
        if (w->desc.face_rgba)
            memcpy(p, rgba + 4 * i, 4);
    }
    w->face_count += count;
    return OIT_OK;
}

oit_ply_writer_stats oit_ply_writer_counts(const oit_ply_writer *w)
{
    oit_ply_writer_stats st = {w->vertices, w->face_count,
                               w->main.bytes + w->main.len + w->faces.bytes + w->faces.len};
    return st;
}

/* Appends the face side file to the main file through the main buffer. */
static oit_status append_faces(oit_ply_writer *w, oit_error *err)
{
    oit_status s = wfile_flush(&w->faces, err);
    if (s)
        return s;
    if (fflush(w->faces.f) != 0 || fseek(w->faces.f, 0, SEEK_SET) != 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot rewind: %s", w->faces.path,
                             strerror(errno));
    for (;;) {
        s = wfile_flush(&w->main, err);
        if (s)
            return s;
        size_t n = fread(w->main.buf, 1, WBUF_BYTES, w->faces.f);
        w->main.len = n;
        if (n < WBUF_BYTES)
            break;
    }
    if (ferror(w->faces.f))
        return oit_error_set(err, OIT_ERR_IO, "%s: read back failed: %s", w->faces.path,
                             strerror(errno));
    return wfile_flush(&w->main, err);
}

static oit_status write_header(oit_ply_writer *w, oit_error *err)
{
    char hdr[MAX_HEADER];
    size_t n = format_header(w, w->vertices, w->face_count, w->header_bytes, hdr);
    if (n != w->header_bytes)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: header does not fit its slot",
                             w->main.path);
    if (fseek(w->main.f, 0, SEEK_SET) != 0 || fwrite(hdr, 1, n, w->main.f) != n ||
        fflush(w->main.f) != 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write header: %s", w->main.path,
                             strerror(errno));
    return OIT_OK;
}

oit_status oit_ply_writer_close(oit_ply_writer *w, oit_ply_writer_stats *stats,
                                oit_error *err)
{
    if (w->failed) {
        oit_error_set(err, OIT_ERR_IO, "%s: not written: an earlier write failed",
                      w->final_path);
        oit_ply_writer_abort(w);
        return OIT_ERR_IO;
    }
    oit_status s = append_faces(w, err);
    if (!s)
        s = write_header(w, err);
    uint64_t bytes = w->main.bytes;
    oit_status sc = wfile_close(&w->faces, 1, err);
    s = s ? s : sc;
    char *tmp = str_concat(w->main.path, "");
    sc = wfile_close(&w->main, s != OIT_OK, err);
    s = s ? s : sc;
    if (!s && !tmp)
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", w->final_path);
    if (!s && rename(tmp, w->final_path) != 0) {
        s = oit_error_set(err, OIT_ERR_IO, "%s: cannot rename from %s: %s",
                          w->final_path, tmp, strerror(errno));
        remove(tmp);
    }
    if (!s && stats) {
        stats->vertices = w->vertices;
        stats->faces = w->face_count;
        stats->bytes = bytes;
    }
    free(tmp);
    free(w->final_path);
    free(w->comment);
    free(w);
    return s;
}

void oit_ply_writer_abort(oit_ply_writer *w)
{
    if (!w)
        return;
    wfile_close(&w->main, 1, NULL);
    wfile_close(&w->faces, 1, NULL);
    free(w->final_path);
    free(w->comment);
    free(w);
}
