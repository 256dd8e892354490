/* Buffered input, budgeted allocation, chunked output and number parsing
 * shared by the mesh readers; see readers_internal.h for the contract. */
#include "formats/readers_internal.h"
#include "formats/gzip_input.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* A line or token longer than this is refused even within budget: no mesh
 * format has one, and it bounds the damage of a file without newlines. */
#define RD_MAX_LINE ((size_t)64 << 20)
#define RD_BUFFER ((size_t)1 << 20)

/* ---- budget ----------------------------------------------------------- */

oit_status oit_rd_grow(oit_rd_budget *b, void **p, size_t *cap, size_t elem, size_t need,
                       const char *name, const char *what, oit_error *err)
{
    if (need <= *cap)
        return OIT_OK;
    size_t old_bytes = *cap * elem;
    size_t avail = b->limit - (b->used - old_bytes);
    size_t max_elems = avail / elem;
    if (need > max_elems)
        return oit_error_set(err, OIT_ERR_NOMEM,
                             "%s: %s of %zu entries exceeds the memory budget of %zu bytes "
                             "(%zu bytes held by other buffers)",
                             name, what, need, b->limit, b->used - old_bytes);
    size_t ncap = *cap > 8 ? *cap : 8;
    while (ncap < need)
        ncap = ncap > SIZE_MAX / 2 ? need : ncap * 2;
    if (ncap > max_elems)
        ncap = max_elems; /* still >= need, checked above */
    void *q = realloc(*p, ncap * elem);
    if (!q)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %zu bytes for the %s",
                             name, ncap * elem, what);
    b->used = b->used - old_bytes + ncap * elem;
    *p = q;
    *cap = ncap;
    return OIT_OK;
}

void oit_rd_release(oit_rd_budget *b, void **p, size_t *cap, size_t elem)
{
    free(*p);
    b->used -= *cap * elem;
    *p = NULL;
    *cap = 0;
}

/* ---- input ------------------------------------------------------------ */

int64_t oit_rd_file_size(FILE *f)
{
    off_t here = ftello(f);
    if (here < 0 || fseeko(f, 0, SEEK_END) != 0)
        return -1;
    off_t size = ftello(f);
    if (fseeko(f, here, SEEK_SET) != 0)
        return -1;
    return size < 0 ? -1 : (int64_t)(size - here);
}

oit_status oit_rd_open(oit_rd_stream *s, FILE *f, const char *name, oit_rd_budget *b,
                       oit_error *err)
{
    memset(s, 0, sizeof *s);
    s->f = f;
    s->name = name;
    s->budget = b;
    s->err = err;
    s->line = 1;
    size_t want = RD_BUFFER;
    if (want > b->limit / 4)
        want = b->limit / 4 < 4096 ? 4096 : b->limit / 4;
    int64_t size = oit_rd_file_size(f); /* small files get a small buffer */
    if (size >= 0 && (uint64_t)size + 64 < want)
        want = (size_t)size + 64;
    return oit_rd_grow(b, (void **)&s->buf, &s->cap, 1, want, name, "input buffer", err);
}

void oit_rd_close(oit_rd_stream *s)
{
    if (s->budget)
        oit_rd_release(s->budget, (void **)&s->buf, &s->cap, 1);
}

/* Makes at least `need` unread bytes available unless the file ends first;
 * the buffer grows (within budget and RD_MAX_LINE) when need exceeds it. */
static oit_status rd_fill(oit_rd_stream *s, size_t need)
{
    if (s->end - s->pos >= need)
        return OIT_OK;
    if (s->pos > 0) {
        memmove(s->buf, s->buf + s->pos, s->end - s->pos);
        s->base += s->pos;
        s->end -= s->pos;
        s->pos = 0;
    }
    if (need + 1 > s->cap) {
        if (need > RD_MAX_LINE)
            return oit_rd_fail_offset(s, s->base, OIT_ERR_FORMAT,
                                      "line or token longer than %zu bytes", RD_MAX_LINE);
        oit_status st = oit_rd_grow(s->budget, (void **)&s->buf, &s->cap, 1, need + 1, s->name,
                                    "input buffer", s->err);
        if (st != OIT_OK)
            return st;
    }
    while (!s->eof && s->end < need) {
        size_t n = fread(s->buf + s->end, 1, s->cap - 1 - s->end, s->f);
        if (n == 0) {
            if (ferror(s->f) && s->gz && oit_gz_message(s->gz)[0])
                return oit_error_set(s->err, OIT_ERR_FORMAT, "%s: %s, after %llu inflated bytes",
                                     s->name, oit_gz_message(s->gz),
                                     (unsigned long long)(s->base + s->end));
            if (ferror(s->f))
                return oit_rd_fail_offset(s, s->base + s->end, OIT_ERR_IO, "read error: %s",
                                          strerror(errno));
            s->eof = 1;
        }
        s->end += n;
    }
    return OIT_OK;
}

/* Asks for more bytes after the `have` already scanned; *more is 0 at EOF. */
static oit_status rd_more(oit_rd_stream *s, size_t have, int *more)
{
    size_t need = have < s->cap / 2 ? s->cap - 1 : have * 2;
    size_t before = s->end - s->pos;
    oit_status st = rd_fill(s, need);
    *more = s->end - s->pos > before;
    return st;
}

oit_status oit_rd_line(oit_rd_stream *s, char **line, int *got)
{
    size_t k = 0; /* bytes of the line scanned so far, from pos */
    s->tok_line = s->line;
    for (;;) {
        char *start = s->buf + s->pos;
        char *nl = memchr(start + k, '\n', s->end - s->pos - k);
        if (!nl) {
            int more;
            k = s->end - s->pos;
            oit_status st = rd_more(s, k, &more);
            if (st != OIT_OK)
                return st;
            if (more)
                continue;
            *got = k > 0;
            if (k > 0)
                s->line++; /* an unterminated last line still counts */
            else if (s->tok_line > 1)
                s->tok_line--; /* "file ends" errors name the last line */
            start = s->buf + s->pos;
            start[k] = '\0';
            if (k > 0 && start[k - 1] == '\r')
                start[k - 1] = '\0';
            s->pos = s->end;
            *line = start;
            return OIT_OK;
        }
        size_t i = (size_t)(nl - start);
        size_t j = (i > 0 && start[i - 1] == '\r') ? i - 1 : i;
        s->line++;
        if (s->continuation && j > 0 && start[j - 1] == '\\') {
            for (size_t m = j - 1; m <= i; m++)
                start[m] = ' ';
            k = i + 1;
            continue;
        }
        start[j] = '\0';
        s->pos += i + 1;
        *line = start;
        *got = 1;
        return OIT_OK;
    }
}

static int rd_is_space(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

oit_status oit_rd_token(oit_rd_stream *s, char **tok, int *got)
{
    int more;
    oit_status st;
    for (;;) { /* skip white space, counting lines */
        while (s->pos < s->end && rd_is_space(s->buf[s->pos]))
            s->line += s->buf[s->pos++] == '\n';
        if (s->pos < s->end)
            break;
        if ((st = rd_more(s, 0, &more)) != OIT_OK)
            return st;
        if (!more) {
            *got = 0;
            return OIT_OK;
        }
    }
    s->tok_line = s->line;
    size_t k = 0;
    for (;;) {
        while (s->pos + k < s->end && !rd_is_space(s->buf[s->pos + k]))
            k++;
        if (s->pos + k < s->end)
            break;
        if ((st = rd_more(s, k, &more)) != OIT_OK)
            return st;
        if (!more)
            break;
    }
    char *start = s->buf + s->pos;
    if (s->pos + k < s->end) {
        s->line += start[k] == '\n';
        s->pos += k + 1;
    } else {
        s->pos += k;
    }
    start[k] = '\0';
    *tok = start;
    *got = 1;
    return OIT_OK;
}

oit_status oit_rd_peek(oit_rd_stream *s, size_t n, const unsigned char **p, size_t *avail)
{
    oit_status st = rd_fill(s, n);
    *p = (const unsigned char *)s->buf + s->pos;
    *avail = s->end - s->pos;
    return st;
}

oit_status oit_rd_bytes_refill(oit_rd_stream *s, size_t n, const char *what,
                               const unsigned char **p)
{
    oit_status st = rd_fill(s, n);
    if (st != OIT_OK)
        return st;
    if (s->end - s->pos < n)
        return oit_rd_fail_offset(s, oit_rd_offset(s), OIT_ERR_FORMAT,
                                  "file truncated in %s (%zu bytes needed, %zu left)", what, n,
                                  s->end - s->pos);
    *p = (const unsigned char *)s->buf + s->pos;
    s->pos += n;
    return OIT_OK;
}

static oit_status rd_failv(oit_rd_stream *s, int binary, uint64_t offset, oit_status st,
                           const char *fmt, va_list ap)
{
    char msg[400];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (binary)
        return oit_error_set(s->err, st, "%s: byte offset %" PRIu64 ": %s", s->name, offset, msg);
    return oit_error_set(s->err, st, "%s: line %" PRIu64 ": %s", s->name, s->tok_line, msg);
}

oit_status oit_rd_fail_line(oit_rd_stream *s, oit_status st, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    st = rd_failv(s, 0, 0, st, fmt, ap);
    va_end(ap);
    return st;
}

oit_status oit_rd_fail_offset(oit_rd_stream *s, uint64_t offset, oit_status st,
                              const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    st = rd_failv(s, 1, offset, st, fmt, ap);
    va_end(ap);
    return st;
}

oit_status oit_rd_fail_here(oit_rd_stream *s, int binary, oit_status st, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    st = rd_failv(s, binary, oit_rd_offset(s), st, fmt, ap);
    va_end(ap);
    return st;
}

/* ---- text and content checks ------------------------------------------ */

#define RD_TEXT_PROBE ((size_t)4096)

oit_status oit_rd_skip_bom(oit_rd_stream *s)
{
    const unsigned char *b;
    size_t avail;
    oit_status st = oit_rd_peek(s, 3, &b, &avail);
    if (st == OIT_OK && avail >= 3 && b[0] == 0xef && b[1] == 0xbb && b[2] == 0xbf)
        s->pos += 3;
    return st;
}

static int rd_is_binary_byte(unsigned char c)
{
    return c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v' &&
           c != 0x1b;
}

oit_status oit_rd_text_begin(oit_rd_stream *s, const char *format)
{
    oit_status st = oit_rd_skip_bom(s);
    const unsigned char *b;
    size_t avail;
    if (st == OIT_OK)
        st = oit_rd_peek(s, RD_TEXT_PROBE, &b, &avail);
    if (st != OIT_OK)
        return st;
    for (size_t i = 0; i < avail && i < RD_TEXT_PROBE; i++)
        if (rd_is_binary_byte(b[i]))
            return oit_rd_fail_offset(s, oit_rd_offset(s) + i, OIT_ERR_FORMAT,
                                      "byte 0x%02x: binary data, not a text %s file", b[i],
                                      format);
    return OIT_OK;
}

oit_status oit_rd_require_triangles(const char *name, const oit_mesh_info *info,
                                    oit_error *err)
{
    unsigned long long t = info->triangles, nf = info->nonfinite_dropped;
    unsigned long long v = info->vertices_in, f = info->faces_in;
    if (t > 0 && info->zero_area < t)
        return OIT_OK;
    if (t > 0)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: all %llu triangles are degenerate (zero "
                             "area): nothing to draw", name, t);
    if (nf > 0)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: all %llu triangles have a non-finite "
                             "coordinate (NaN or inf): nothing to draw", name, nf);
    if (f > 0)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: %llu faces but none with three "
                             "vertices: no triangle to draw", name, f);
    if (v > 0)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: %llu vertices but no faces: no triangle "
                             "to draw (a point cloud?)", name, v);
    return oit_error_set(err, OIT_ERR_FORMAT, "%s: no vertices and no faces: no model in this "
                         "file", name);
}

/* ---- numbers ---------------------------------------------------------- */

static int rd_ends_token(char c, const char *stops)
{
    return c == '\0' || rd_is_space(c) || (stops && c != '\0' && strchr(stops, c));
}

int oit_rd_float(char **p, float *out)
{
    oit_rd_skip_blanks(p);
    char *end;
    float v = strtof(*p, &end);
    if (end == *p || !rd_ends_token(*end, NULL))
        return 0;
    *out = v;
    *p = end;
    return 1;
}

int oit_rd_double(char **p, double *out)
{
    oit_rd_skip_blanks(p);
    char *end;
    double v = strtod(*p, &end);
    if (end == *p || !rd_ends_token(*end, NULL))
        return 0;
    *out = v;
    *p = end;
    return 1;
}

int oit_rd_int(char **p, int64_t *out, const char *stops)
{
    oit_rd_skip_blanks(p);
    const char *c = *p;
    int neg = 0;
    if (*c == '-' || *c == '+')
        neg = *c++ == '-';
    if (*c < '0' || *c > '9')
        return 0;
    uint64_t v = 0;
    while (*c >= '0' && *c <= '9') {
        unsigned d = (unsigned)(*c++ - '0');
        if (v > (UINT64_C(1) << 62) / 10) /* far beyond any index or count */
            return 0;
        v = v * 10 + d;
    }
    if (!rd_ends_token(*c, stops))
        return 0;
    *out = neg ? -(int64_t)v : (int64_t)v;
    *p = (char *)c;
    return 1;
}

/* ---- output ----------------------------------------------------------- */

oit_status oit_rd_emitter_init(oit_rd_emitter *e, const oit_read_desc *desc, oit_rd_budget *b,
                               oit_triangle_sink sink, void *user, oit_mesh_info *info,
                               const char *name, oit_error *err)
{
    memset(e, 0, sizeof *e);
    e->budget = b;
    e->sink = sink;
    e->user = user;
    e->info = info;
    e->err = err;
    size_t chunk = desc && desc->chunk_triangles ? desc->chunk_triangles : OIT_RD_DEFAULT_CHUNK;
    oit_status st = oit_rd_grow(b, (void **)&e->tris, &e->alloc, sizeof *e->tris, chunk, name,
                                "triangle chunk", err);
    if (st == OIT_OK)
        e->cap = chunk;
    return st;
}

oit_status oit_rd_flush(oit_rd_emitter *e)
{
    if (e->count == 0)
        return OIT_OK;
    size_t n = e->count;
    e->count = 0;
    oit_mesh_info_add(e->info, e->tris, n);
    /* ALPHA may come later (an OBJ's first material with d): kept, then
     * cleared at the end if it never does (oit_rd_ctx_close) */
    for (size_t i = 0; i < n && !(e->info->attributes & OIT_ATTR_OPAQUE); i++)
        if (e->tris[i].v[0].rgba[3] == 255 && e->tris[i].v[1].rgba[3] == 255 &&
            e->tris[i].v[2].rgba[3] == 255)
            e->info->attributes |= OIT_ATTR_OPAQUE;
    return e->sink ? e->sink(e->user, e->tris, n, e->err) : OIT_OK;
}

void oit_rd_emitter_free(oit_rd_emitter *e)
{
    if (e->budget)
        oit_rd_release(e->budget, (void **)&e->tris, &e->alloc, sizeof *e->tris);
}

/* ---- a whole read ----------------------------------------------------- */

oit_status oit_rd_ctx_open(oit_rd_ctx *c, FILE *f, const char *name, const oit_read_desc *desc,
                           oit_triangle_sink sink, void *user, oit_mesh_info *info,
                           oit_error *err)
{
    memset(c, 0, sizeof *c);
    c->budget.limit = desc && desc->memory_budget ? desc->memory_budget : OIT_RD_DEFAULT_BUDGET;
    c->info = info ? info : &c->local_info;
    oit_mesh_info_init(c->info);
    c->name = name;
    c->err = err;
    oit_status st = oit_gz_open(f, name, &c->gz_file, &c->gz, err);
    if (st != OIT_OK)
        return st;
    if (c->gz_file) {
        size_t n = strlen(name);
        int named = n >= 3 && (name[n - 1] == 'z' || name[n - 1] == 'Z') &&
                    (name[n - 2] == 'g' || name[n - 2] == 'G') && name[n - 3] == '.';
        snprintf(c->gz_name, sizeof c->gz_name, "%s%s", name, named ? "" : " (gzip)");
        c->name = name = c->gz_name;
        f = c->gz_file;
    }
    st = oit_rd_emitter_init(&c->out, desc, &c->budget, sink, user, c->info, name, err);
    if (st != OIT_OK)
        return st;
    st = oit_rd_open(&c->in, f, name, &c->budget, err);
    c->in.gz = c->gz;
    return st;
}

oit_status oit_rd_ctx_close(oit_rd_ctx *c, oit_status st)
{
    if (st == OIT_OK)
        st = oit_rd_flush(&c->out);
    if (c->info)
        oit_mesh_info_opaque(c->info, NULL, 0);
    oit_rd_close(&c->in);
    oit_rd_emitter_free(&c->out);
    if (c->gz_file)
        fclose(c->gz_file);
    c->gz_file = NULL;
    return st;
}

oit_status oit_rd_ctx_run(FILE *f, const char *name, const oit_read_desc *desc,
                          oit_triangle_sink sink, void *user, oit_mesh_info *info,
                          oit_error *err, oit_status (*parse)(oit_rd_ctx *c))
{
    oit_rd_ctx c;
    oit_status st = oit_rd_ctx_open(&c, f, name, desc, sink, user, info, err);
    if (st == OIT_OK)
        st = parse(&c);
    return oit_rd_ctx_close(&c, st);
}

oit_status oit_rd_with_file(const char *path, oit_rd_file_fn *fn, const oit_read_desc *desc,
                            oit_triangle_sink sink, void *user, oit_mesh_info *info,
                            oit_error *err)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + 1 : 0;
    if (n >= sizeof dir)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: path too long", path);
    memcpy(dir, path, n);
    dir[n] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    oit_mesh_info local;
    oit_mesh_info *in = info ? info : &local;
    oit_status st = fn(f, path, dir, desc, sink, user, in, err);
    fclose(f);
    return st == OIT_OK ? oit_rd_require_triangles(path, in, err) : st;
}
