/* VTK XML PolyData reader (.vtp).
 *
 * <VTKFile type="PolyData"> with any number of Pieces; DataArrays in the
 * ascii, binary (base64) and appended (raw or base64) formats, either byte
 * order, header_type UInt32 or UInt64, uncompressed or compressed with
 * vtkZLibDataCompressor (zlib, loaded as for gzip input: zlib_load.h).
 * Points, Polys and Strips are drawn; Verts and Lines are counted in VTK's
 * cell ids (verts, lines, polys, strips) and not drawn. Colours: the
 * PointData or CellData array named by its Scalars attribute when it is
 * UInt8 with 3 or 4 components (the 4th alpha), else the first such array
 * named like a colour ("Colors", "RGBA"); every other array is skipped and
 * never decoded. A cell colour overrides its points' colours.
 *
 * Appended data comes after every element that refers to it, so the whole
 * file is held (charged to the memory budget, with the arrays that are
 * decoded); a small tokenizer walks the elements, attributes and text it
 * needs, and nothing beyond it (no DTD, no entities in what is read).
 * Errors name the file and the byte offset of the element or data at fault.
 */
#include "formats/vtk_internal.h"
#include "formats/zlib_load.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>

enum { VT_BAD, VT_I8, VT_U8, VT_I16, VT_U16, VT_I32, VT_U32, VT_I64, VT_U64, VT_F32, VT_F64 };
static const unsigned vt_size[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};
enum { FMT_ASCII, FMT_BINARY, FMT_APPENDED };
enum { SEC_VERTS, SEC_LINES, SEC_POLYS, SEC_STRIPS, SEC_N };
enum { ROLE_OTHER, ROLE_POINTS, ROLE_PDATA, ROLE_CDATA, ROLE_CONN, ROLE_OFFS };
#define VTP_MAX_DEPTH 32

typedef struct vtp_array {
    size_t at;                /* byte offset of its tag, for messages */
    const char *name;         /* not NUL-terminated                    */
    size_t name_len;
    int type, comps, format, role, sec;
    uint64_t offset;          /* appended: from the '_'                */
    size_t text, text_end;    /* inline: the content's bytes           */
} vtp_array;

typedef struct vtp_piece {
    size_t at;
    uint64_t npoints, ncells[SEC_N];
    size_t first, count;               /* its arrays: arrays[first, first+count) */
    const char *scalars[2];            /* PointData / CellData Scalars=   */
    size_t scalars_len[2];
} vtp_piece;

typedef struct vtp {
    oit_rd_ctx *c;
    unsigned char *buf;
    size_t len, cap;
    int big, header64, zlib;
    size_t appended, appended_end; /* 0: none */
    int appended_b64;
    vtp_array *arrays;
    size_t narrays, arrays_cap;
    vtp_piece *pieces;
    size_t npieces, pieces_cap;
    oit_zlib z;
    unsigned char *dec; /* the decoded bytes of the array being read */
    size_t dec_len, dec_cap;
} vtp;

static oit_status vtp_fail(vtp *V, size_t at, oit_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static oit_status vtp_fail(vtp *V, size_t at, oit_status st, const char *fmt, ...)
{
    char msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return oit_error_set(V->c->err, st, "%s: byte offset %zu: %s", V->c->name, at, msg);
}

/* ---- the whole file, and the tokenizer --------------------------------- */

static oit_status vtp_slurp(vtp *V)
{
    oit_rd_stream *s = &V->c->in;
    int64_t size = V->c->gz ? -1 : oit_rd_file_size(s->f); /* one allocation when known */
    if (size > 0) {
        oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->buf, &V->cap, 1,
                                    (size_t)size + 1, V->c->name, "file buffer", V->c->err);
        if (st != OIT_OK)
            return st;
    }
    for (;;) {
        const unsigned char *p;
        size_t avail;
        oit_status st = oit_rd_peek(s, (size_t)1 << 16, &p, &avail);
        if (st != OIT_OK)
            return st;
        if (avail == 0)
            break;
        st = oit_rd_grow(&V->c->budget, (void **)&V->buf, &V->cap, 1, V->len + avail + 1,
                         V->c->name, "file buffer", V->c->err);
        if (st != OIT_OK)
            return st;
        memcpy(V->buf + V->len, p, avail);
        V->len += avail;
        s->pos += avail;
    }
    if (V->cap)
        V->buf[V->len] = '\0';
    return OIT_OK;
}

static int xml_space(unsigned char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r';
}

static int xml_name_char(unsigned char ch)
{
    return ch > ' ' && ch != '>' && ch != '/' && ch != '=' && ch != '<' && ch != '"' &&
           ch != '\'';
}

/* The value of attribute key in the tag text [p, end), or 0. */
static int xml_attr(const unsigned char *p, const unsigned char *end, const char *key,
                    const char **val, size_t *n)
{
    size_t klen = strlen(key);
    while (p < end && xml_name_char(*p)) /* the element's name */
        p++;
    for (;;) {
        while (p < end && xml_space(*p))
            p++;
        const unsigned char *name = p;
        while (p < end && xml_name_char(*p))
            p++;
        size_t nlen = (size_t)(p - name);
        while (p < end && xml_space(*p))
            p++;
        if (nlen == 0 || p >= end || *p != '=')
            return 0;
        p++;
        while (p < end && xml_space(*p))
            p++;
        if (p >= end || (*p != '"' && *p != '\''))
            return 0;
        unsigned char q = *p++;
        const unsigned char *v = p;
        while (p < end && *p != q)
            p++;
        if (p >= end)
            return 0;
        if (nlen == klen && memcmp(name, key, klen) == 0) {
            *val = (const char *)v;
            *n = (size_t)(p - v);
            return 1;
        }
        p++;
    }
}

static int xml_eq(const char *v, size_t n, const char *lit)
{
    return strlen(lit) == n && memcmp(v, lit, n) == 0;
}

/* A non-negative integer attribute; 0 when absent (*ok stays 1). */
static int xml_count(const unsigned char *p, const unsigned char *end, const char *key,
                     uint64_t *out)
{
    const char *v;
    size_t n;
    *out = 0;
    if (!xml_attr(p, end, key, &v, &n))
        return 1;
    if (n == 0 || n > 19)
        return 0;
    uint64_t x = 0;
    for (size_t i = 0; i < n; i++) {
        if (v[i] < '0' || v[i] > '9')
            return 0;
        x = x * 10 + (uint64_t)(v[i] - '0');
    }
    *out = x;
    return 1;
}

static int vtp_type(const char *v, size_t n)
{
    static const char *const names[] = {"", "Int8", "UInt8", "Int16", "UInt16", "Int32",
                                        "UInt32", "Int64", "UInt64", "Float32", "Float64"};
    for (int t = 1; t <= VT_F64; t++)
        if (xml_eq(v, n, names[t]))
            return t;
    return VT_BAD;
}

/* ---- structure --------------------------------------------------------- */

typedef struct vtp_walk {
    const char *stack[VTP_MAX_DEPTH];
    size_t lens[VTP_MAX_DEPTH];
    int depth;
    int piece_open; /* index + 1 of the open Piece */
    int in_array;   /* index + 1 of the open DataArray */
} vtp_walk;

static int walk_parent_is(const vtp_walk *w, const char *lit)
{
    return w->depth > 0 && xml_eq(w->stack[w->depth - 1], w->lens[w->depth - 1], lit);
}

static oit_status vtp_root(vtp *V, const unsigned char *t, const unsigned char *e, size_t at)
{
    const char *v;
    size_t n;
    if (!xml_attr(t, e, "type", &v, &n))
        return vtp_fail(V, at, OIT_ERR_FORMAT, "VTKFile without a type");
    if (!xml_eq(v, n, "PolyData"))
        return vtp_fail(V, at, OIT_ERR_UNSUPPORTED, "VTKFile type '%.*s' is not supported "
                        "(a .vtp holds PolyData)", (int)(n > 40 ? 40 : n), v);
    if (xml_attr(t, e, "byte_order", &v, &n))
        V->big = xml_eq(v, n, "BigEndian");
    if (xml_attr(t, e, "header_type", &v, &n)) {
        if (!xml_eq(v, n, "UInt32") && !xml_eq(v, n, "UInt64"))
            return vtp_fail(V, at, OIT_ERR_UNSUPPORTED, "header_type '%.*s' (UInt32 or UInt64 "
                            "expected)", (int)(n > 40 ? 40 : n), v);
        V->header64 = xml_eq(v, n, "UInt64");
    }
    if (xml_attr(t, e, "compressor", &v, &n) && n > 0) {
        if (!xml_eq(v, n, "vtkZLibDataCompressor"))
            return vtp_fail(V, at, OIT_ERR_UNSUPPORTED, "compressor '%.*s' is not supported "
                            "(only vtkZLibDataCompressor)", (int)(n > 40 ? 40 : n), v);
        V->zlib = 1;
    }
    return OIT_OK;
}

static oit_status vtp_piece_open(vtp *V, const unsigned char *t, const unsigned char *e,
                                 size_t at)
{
    static const char *const keys[SEC_N] = {"NumberOfVerts", "NumberOfLines", "NumberOfPolys",
                                            "NumberOfStrips"};
    if (V->npieces == V->pieces_cap) {
        oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->pieces, &V->pieces_cap,
                                    sizeof *V->pieces, V->npieces + 1, V->c->name, "piece list",
                                    V->c->err);
        if (st != OIT_OK)
            return st;
    }
    vtp_piece *p = &V->pieces[V->npieces++];
    memset(p, 0, sizeof *p);
    p->at = at;
    p->first = V->narrays;
    int ok = xml_count(t, e, "NumberOfPoints", &p->npoints);
    for (int s = 0; s < SEC_N; s++)
        ok &= xml_count(t, e, keys[s], &p->ncells[s]);
    if (!ok)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "Piece: a NumberOf... attribute is not a count");
    return OIT_OK;
}

static oit_status vtp_array_open(vtp *V, vtp_walk *w, const unsigned char *t,
                                 const unsigned char *e, size_t at)
{
    static const char *const secs[SEC_N] = {"Verts", "Lines", "Polys", "Strips"};
    if (V->narrays == V->arrays_cap) {
        oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->arrays, &V->arrays_cap,
                                    sizeof *V->arrays, V->narrays + 1, V->c->name, "array list",
                                    V->c->err);
        if (st != OIT_OK)
            return st;
    }
    vtp_array *a = &V->arrays[V->narrays++];
    memset(a, 0, sizeof *a);
    a->at = at;
    const char *v;
    size_t n;
    if (xml_attr(t, e, "Name", &v, &n))
        a->name = v, a->name_len = n;
    a->type = xml_attr(t, e, "type", &v, &n) ? vtp_type(v, n) : VT_BAD;
    uint64_t comps;
    if (!xml_count(t, e, "NumberOfComponents", &comps) || comps > 64)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "DataArray: bad NumberOfComponents");
    a->comps = comps ? (int)comps : 1;
    a->format = FMT_ASCII;
    if (xml_attr(t, e, "format", &v, &n)) {
        if (xml_eq(v, n, "binary"))
            a->format = FMT_BINARY;
        else if (xml_eq(v, n, "appended"))
            a->format = FMT_APPENDED;
        else if (!xml_eq(v, n, "ascii"))
            return vtp_fail(V, at, OIT_ERR_FORMAT, "DataArray: unknown format '%.*s'",
                            (int)(n > 40 ? 40 : n), v);
    }
    if (!xml_count(t, e, "offset", &a->offset))
        return vtp_fail(V, at, OIT_ERR_FORMAT, "DataArray: bad offset");
    if (walk_parent_is(w, "Points"))
        a->role = ROLE_POINTS;
    else if (walk_parent_is(w, "PointData"))
        a->role = ROLE_PDATA;
    else if (walk_parent_is(w, "CellData"))
        a->role = ROLE_CDATA;
    for (int s = 0; s < SEC_N; s++)
        if (walk_parent_is(w, secs[s])) {
            a->sec = s;
            a->role = a->name && xml_eq(a->name, a->name_len, "connectivity") ? ROLE_CONN
                      : a->name && xml_eq(a->name, a->name_len, "offsets")    ? ROLE_OFFS
                                                                               : ROLE_OTHER;
        }
    return OIT_OK;
}

/* A start tag [t, e) (t after '<', e at '>' or "/>"). */
static oit_status vtp_start(vtp *V, vtp_walk *w, const unsigned char *t, const unsigned char *e,
                            int empty, int *stop)
{
    size_t at = (size_t)(t - V->buf) - 1;
    const unsigned char *ne = t;
    while (ne < e && xml_name_char(*ne))
        ne++;
    const char *name = (const char *)t;
    size_t n = (size_t)(ne - t);
    oit_status st = OIT_OK;
    if (w->depth == 0 && !xml_eq(name, n, "VTKFile"))
        return vtp_fail(V, at, OIT_ERR_FORMAT, "the root element is <%.*s>, not <VTKFile>",
                        (int)(n > 40 ? 40 : n), name);
    if (w->depth == 0)
        st = vtp_root(V, t, e, at);
    else if (xml_eq(name, n, "Piece") && walk_parent_is(w, "PolyData"))
        st = vtp_piece_open(V, t, e, at), w->piece_open = (int)V->npieces;
    else if (w->piece_open && (xml_eq(name, n, "PointData") || xml_eq(name, n, "CellData"))) {
        vtp_piece *p = &V->pieces[w->piece_open - 1];
        int k = name[0] == 'C';
        const char *v;
        size_t vn;
        if (xml_attr(t, e, "Scalars", &v, &vn))
            p->scalars[k] = v, p->scalars_len[k] = vn;
    } else if (w->piece_open && xml_eq(name, n, "DataArray")) {
        st = vtp_array_open(V, w, t, e, at);
        if (st == OIT_OK && !empty)
            w->in_array = (int)V->narrays;
    } else if (xml_eq(name, n, "AppendedData")) {
        const char *v;
        size_t vn;
        V->appended_b64 = !(xml_attr(t, e, "encoding", &v, &vn) && xml_eq(v, vn, "raw"));
        size_t p = (size_t)(e - V->buf) + 1;
        while (p < V->len && xml_space(V->buf[p]))
            p++;
        if (empty || p >= V->len || V->buf[p] != '_')
            return vtp_fail(V, p, OIT_ERR_FORMAT, "AppendedData does not start with '_'");
        V->appended = p + 1;
        V->appended_end = V->len; /* raw bytes may hold anything: never parsed */
        *stop = 1;
        return OIT_OK;
    }
    if (st != OIT_OK || empty)
        return st;
    if (w->depth == VTP_MAX_DEPTH)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "elements nested more than %d deep",
                        VTP_MAX_DEPTH);
    w->stack[w->depth] = name;
    w->lens[w->depth++] = n;
    return OIT_OK;
}

static oit_status vtp_end(vtp *V, vtp_walk *w, const unsigned char *t, const unsigned char *e)
{
    const unsigned char *ne = t;
    while (ne < e && xml_name_char(*ne))
        ne++;
    size_t n = (size_t)(ne - t), at = (size_t)(t - V->buf) - 2;
    if (w->depth == 0 || w->lens[w->depth - 1] != n ||
        memcmp(w->stack[w->depth - 1], t, n) != 0)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "</%.*s> does not close the open element",
                        (int)(n > 40 ? 40 : n), (const char *)t);
    w->depth--;
    if (xml_eq((const char *)t, n, "Piece") && w->piece_open) {
        V->pieces[w->piece_open - 1].count = V->narrays - V->pieces[w->piece_open - 1].first;
        w->piece_open = 0;
    }
    if (xml_eq((const char *)t, n, "DataArray"))
        w->in_array = 0;
    return OIT_OK;
}

/* The first text directly inside an open DataArray is its data (not the
 * text of its InformationKey children, which VTK writes before it). */
static void vtp_text(vtp *V, vtp_walk *w, size_t from, size_t to)
{
    if (!w->in_array || !walk_parent_is(w, "DataArray"))
        return;
    vtp_array *a = &V->arrays[w->in_array - 1];
    if (a->text_end > a->text)
        return;
    size_t p = from;
    while (p < to && xml_space(V->buf[p]))
        p++;
    if (p < to)
        a->text = from, a->text_end = to;
}

static oit_status vtp_walk_file(vtp *V)
{
    vtp_walk w;
    memset(&w, 0, sizeof w);
    size_t p = 0;
    int stop = 0, seen_root = 0;
    if (V->len >= 3 && V->buf[0] == 0xef && V->buf[1] == 0xbb && V->buf[2] == 0xbf)
        p = 3;
    while (p < V->len && !stop) {
        const unsigned char *lt = memchr(V->buf + p, '<', V->len - p);
        size_t q = lt ? (size_t)(lt - V->buf) : V->len;
        if (!seen_root && q > p) {
            for (size_t i = p; i < q; i++)
                if (!xml_space(V->buf[i]))
                    return vtp_fail(V, i, OIT_ERR_FORMAT, "not an XML VTK file (text before "
                                    "the first element)");
        }
        vtp_text(V, &w, p, q);
        if (!lt)
            break;
        const char *close = NULL;
        const unsigned char *s = lt + 1, *end = V->buf + V->len;
        if (end - s >= 3 && memcmp(s, "!--", 3) == 0)
            close = "-->";
        else if (s < end && (*s == '?' || *s == '!'))
            close = ">";
        if (close) {
            const unsigned char *c = s;
            size_t cl = strlen(close);
            while (c + cl <= end && memcmp(c, close, cl) != 0)
                c++;
            if (c + cl > end)
                return vtp_fail(V, q, OIT_ERR_FORMAT, "unterminated '<%c' (truncated?)", *s);
            p = (size_t)(c - V->buf) + cl;
            continue;
        }
        const unsigned char *gt = memchr(s, '>', (size_t)(end - s));
        if (!gt)
            return vtp_fail(V, q, OIT_ERR_FORMAT, "unterminated tag (truncated?)");
        oit_status st;
        if (*s == '/') {
            st = vtp_end(V, &w, s + 1, gt);
        } else {
            int empty = gt > s && gt[-1] == '/';
            st = vtp_start(V, &w, s, empty ? gt - 1 : gt, empty, &stop);
            seen_root = 1;
        }
        if (st != OIT_OK)
            return st;
        p = (size_t)(gt - V->buf) + 1;
    }
    if (!seen_root)
        return oit_error_set(V->c->err, OIT_ERR_FORMAT, "%s: no <VTKFile> element: not a VTK "
                             "XML file", V->c->name);
    if (!stop && w.depth > 0)
        return vtp_fail(V, V->len, OIT_ERR_FORMAT, "file ends inside <%.*s> (truncated)",
                        (int)(w.lens[w.depth - 1] > 40 ? 40 : w.lens[w.depth - 1]),
                        w.stack[w.depth - 1]);
    return OIT_OK;
}

/* ---- decoding an array ------------------------------------------------- */

typedef struct vtp_src {
    size_t pos, end;
    int b64;
} vtp_src;

static int b64_val(unsigned char ch)
{
    if (ch >= 'A' && ch <= 'Z') return ch - 'A';
    if (ch >= 'a' && ch <= 'z') return ch - 'a' + 26;
    if (ch >= '0' && ch <= '9') return ch - '0' + 52;
    if (ch == '+') return 62;
    if (ch == '/') return 63;
    return -1;
}

/* Appends the source's next bytes to dec until it holds at least `need`
 * (base64: up to 2 more, the rest of the last quartet, kept for the next
 * call). Base64 is decoded a quartet at a time, padding allowed in each:
 * VTK encodes a header and its data as one run or as two. */
static oit_status vtp_take(vtp *V, vtp_src *s, size_t need, size_t at)
{
    if (need <= V->dec_len)
        return OIT_OK;
    size_t have_src = s->end - s->pos;
    if ((s->b64 ? have_src / 4 * 3 : have_src) < need - V->dec_len)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "the data array needs %zu bytes, the file has "
                        "fewer (truncated?)", need - V->dec_len);
    oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->dec, &V->dec_cap, 1, need + 3,
                                V->c->name, "decoded array", V->c->err);
    if (st != OIT_OK)
        return st;
    if (!s->b64) {
        memcpy(V->dec + V->dec_len, V->buf + s->pos, need - V->dec_len);
        s->pos += need - V->dec_len;
        V->dec_len = need;
        return OIT_OK;
    }
    while (V->dec_len < need) {
        int q[4], k = 0;
        while (k < 4 && s->pos < s->end) {
            unsigned char ch = V->buf[s->pos++];
            if (xml_space(ch))
                continue;
            q[k++] = ch == '=' ? -2 : b64_val(ch);
            if (q[k - 1] == -1)
                return vtp_fail(V, s->pos - 1, OIT_ERR_FORMAT, "byte 0x%02x in base64 data", ch);
        }
        if (k < 4)
            return vtp_fail(V, at, OIT_ERR_FORMAT, "base64 data ends early (truncated?)");
        if (q[0] < 0 || q[1] < 0 || (q[2] == -2 && q[3] != -2))
            return vtp_fail(V, s->pos - 4, OIT_ERR_FORMAT, "bad base64 padding");
        unsigned char out[3] = {(unsigned char)(q[0] << 2 | q[1] >> 4), 0, 0};
        int nout = 1;
        if (q[2] >= 0)
            out[1] = (unsigned char)((q[1] & 15) << 4 | q[2] >> 2), nout = 2;
        if (q[2] >= 0 && q[3] >= 0)
            out[2] = (unsigned char)((q[2] & 3) << 6 | q[3]), nout = 3;
        memcpy(V->dec + V->dec_len, out, (size_t)nout);
        V->dec_len += (size_t)nout;
    }
    return OIT_OK;
}

static uint64_t vtp_word(const vtp *V, size_t off)
{
    const unsigned char *b = V->dec + off;
    if (!V->header64)
        return oit_rd_u32(b, V->big);
    uint64_t lo = oit_rd_u32(b + (V->big ? 4 : 0), V->big);
    uint64_t hi = oit_rd_u32(b + (V->big ? 0 : 4), V->big);
    return hi << 32 | lo;
}

static oit_status vtp_inflate(vtp *V, const unsigned char *in, size_t n, unsigned char *out,
                              size_t out_n, size_t at)
{
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    if (!V->z.inflate) {
        oit_status st = oit_zlib_open(&V->z, V->c->name, V->c->err);
        if (st != OIT_OK)
            return st;
    }
    if (V->z.inflate_init2(&zs, 15, ZLIB_VERSION, (int)sizeof zs) != Z_OK)
        return vtp_fail(V, at, OIT_ERR_NOMEM, "zlib cannot start inflating");
    zs.next_in = (unsigned char *)in;
    zs.avail_in = (uInt)n;
    zs.next_out = out;
    zs.avail_out = (uInt)out_n;
    int r = V->z.inflate(&zs, Z_FINISH);
    V->z.inflate_end(&zs);
    if (r != Z_STREAM_END || zs.avail_out != 0)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "a zlib block does not inflate to its %zu bytes "
                        "(%s)", out_n, r == Z_STREAM_END ? "too short" : V->z.error(r));
    return OIT_OK;
}

/* Binary data (header then data, maybe compressed) into dec[0, *n). */
static oit_status vtp_binary(vtp *V, vtp_src *s, size_t at, size_t *n)
{
    size_t w = V->header64 ? 8 : 4;
    V->dec_len = 0;
    oit_status st = vtp_take(V, s, w, at);
    if (st != OIT_OK)
        return st;
    if (!V->zlib) {
        uint64_t bytes = vtp_word(V, 0);
        if (bytes > SIZE_MAX - w)
            return vtp_fail(V, at, OIT_ERR_FORMAT, "data array of %" PRIu64 " bytes", bytes);
        st = vtp_take(V, s, w + (size_t)bytes, at);
        if (st == OIT_OK)
            memmove(V->dec, V->dec + w, (size_t)bytes);
        *n = (size_t)bytes;
        return st;
    }
    if ((st = vtp_take(V, s, 3 * w, at)) != OIT_OK)
        return st;
    uint64_t nb = vtp_word(V, 0), bs = vtp_word(V, w), last = vtp_word(V, 2 * w);
    if (nb > (s->end - s->pos) / w + 1 || (nb > 0 && bs == 0) || last > bs ||
        (nb > 0 && (bs > V->c->budget.limit || nb - 1 > V->c->budget.limit / bs)))
        return vtp_fail(V, at, OIT_ERR_FORMAT, "bad compression header (%" PRIu64 " blocks of "
                        "%" PRIu64 " bytes, the last %" PRIu64 ")", nb, bs, last);
    size_t head = (size_t)(3 + nb) * w;
    if ((st = vtp_take(V, s, head, at)) != OIT_OK)
        return st;
    uint64_t csum = 0;
    for (uint64_t i = 0; i < nb && csum <= s->end - s->pos; i++)
        csum += vtp_word(V, (size_t)(3 + i) * w) > s->end ? s->end : vtp_word(V, (size_t)(3 + i) * w);
    uint64_t total = nb == 0 ? 0 : (nb - 1) * bs + (last ? last : bs);
    if (csum > s->end - s->pos)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "compressed blocks of %" PRIu64 " bytes: more "
                        "than the file holds (truncated?)", csum);
    /* deflate expands at most about 1032:1: a header claiming more is not
     * allocated for */
    if (total > csum * 1040 + 1024)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "compressed blocks of %" PRIu64 " bytes cannot "
                        "inflate to the %" PRIu64 " the header claims", csum, total);
    if ((st = vtp_take(V, s, head + (size_t)csum, at)) != OIT_OK)
        return st;
    unsigned char *out = NULL;
    size_t out_cap = 0;
    st = oit_rd_grow(&V->c->budget, (void **)&out, &out_cap, 1, (size_t)total + 1, V->c->name,
                     "inflated array", V->c->err);
    size_t in_at = head, out_at = 0;
    for (uint64_t i = 0; i < nb && st == OIT_OK; i++) {
        size_t cs = (size_t)vtp_word(V, (size_t)(3 + i) * w);
        size_t us = (size_t)(i + 1 == nb && last ? last : bs);
        st = vtp_inflate(V, V->dec + in_at, cs, out + out_at, us, at);
        in_at += cs, out_at += us;
    }
    oit_rd_release(&V->c->budget, (void **)&V->dec, &V->dec_cap, 1);
    V->dec = out, V->dec_cap = out_cap, V->dec_len = (size_t)total;
    *n = (size_t)total;
    return st;
}

/* ASCII numbers into dec as native doubles. */
static oit_status vtp_ascii(vtp *V, const vtp_array *a, size_t count)
{
    if (count > (a->text_end - a->text + 1) / 2) /* a digit and a blank each at least */
        return vtp_fail(V, a->at, OIT_ERR_FORMAT, "ascii DataArray '%.*s' of %zu bytes cannot "
                        "hold %zu values", (int)(a->name_len > 40 ? 40 : a->name_len),
                        a->name ? a->name : "", a->text_end - a->text, count);
    oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->dec, &V->dec_cap, sizeof(double),
                                count + 1, V->c->name, "decoded array", V->c->err);
    size_t p = a->text, i = 0;
    while (st == OIT_OK && i < count) {
        while (p < a->text_end && xml_space(V->buf[p]))
            p++;
        if (p >= a->text_end)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "ascii DataArray '%.*s' holds %zu of "
                            "%zu values", (int)(a->name_len > 40 ? 40 : a->name_len),
                            a->name ? a->name : "", i, count);
        char tmp[64];
        size_t k = 0;
        while (p < a->text_end && !xml_space(V->buf[p]) && k < sizeof tmp - 1)
            tmp[k++] = (char)V->buf[p++];
        tmp[k] = '\0';
        char *q = tmp;
        double d;
        if (!oit_rd_double(&q, &d) || *q)
            return vtp_fail(V, p - k, OIT_ERR_FORMAT, "not a number: '%.40s'", tmp);
        memcpy(V->dec + i * sizeof d, &d, sizeof d);
        i++;
    }
    return st;
}

typedef struct vtp_view {
    const unsigned char *b;
    int type, big, native_double;
    size_t count;
} vtp_view;

static double vtp_get(const vtp_view *v, size_t i)
{
    if (v->native_double) {
        double d;
        memcpy(&d, v->b + i * sizeof d, sizeof d);
        return d;
    }
    const unsigned char *b = v->b + i * vt_size[v->type];
    uint64_t u = 0;
    for (unsigned k = 0; k < vt_size[v->type]; k++)
        u |= (uint64_t)b[v->big ? vt_size[v->type] - 1 - k : k] << (8 * k);
    switch (v->type) {
    case VT_I8: return (int8_t)u;
    case VT_I16: return (int16_t)u;
    case VT_I32: return (int32_t)u;
    case VT_I64: return (double)(int64_t)u;
    case VT_F32: { uint32_t x = (uint32_t)u; float f; memcpy(&f, &x, 4); return f; }
    case VT_F64: { double d; memcpy(&d, &u, 8); return d; }
    default: return (double)u;
    }
}

/* Decodes array a, which must hold `count` values, into dec (moved out to
 * *owned so that several arrays can be held at once). */
static oit_status vtp_decode(vtp *V, const vtp_array *a, size_t count, vtp_view *view,
                             unsigned char **owned, size_t *owned_cap)
{
    if (a->type == VT_BAD)
        return vtp_fail(V, a->at, OIT_ERR_UNSUPPORTED, "DataArray '%.*s': type missing or not "
                        "numeric", (int)(a->name_len > 40 ? 40 : a->name_len),
                        a->name ? a->name : "");
    memset(view, 0, sizeof *view);
    view->type = a->type, view->big = V->big, view->count = count;
    oit_status st;
    size_t n = 0;
    V->dec_len = 0;
    if (a->format == FMT_ASCII) {
        st = vtp_ascii(V, a, count);
        view->native_double = 1;
        n = count * vt_size[a->type];
    } else if (a->format == FMT_BINARY) {
        vtp_src s = {a->text, a->text_end, 1};
        st = vtp_binary(V, &s, a->at, &n);
    } else {
        if (!V->appended)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "appended DataArray but no "
                            "<AppendedData> (truncated?)");
        if (a->offset >= V->appended_end - V->appended)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "appended offset %" PRIu64 " beyond the "
                            "appended data (truncated?)", a->offset);
        vtp_src s = {V->appended + (size_t)a->offset, V->appended_end, V->appended_b64};
        st = vtp_binary(V, &s, a->at, &n);
    }
    if (st == OIT_OK && n / vt_size[a->type] < count)
        st = vtp_fail(V, a->at, OIT_ERR_FORMAT, "DataArray '%.*s' holds %zu values, %zu "
                      "expected", (int)(a->name_len > 40 ? 40 : a->name_len),
                      a->name ? a->name : "", n / vt_size[a->type], count);
    *owned = V->dec, *owned_cap = V->dec_cap;
    V->dec = NULL, V->dec_cap = V->dec_len = 0;
    view->b = *owned;
    return st;
}

/* ---- a piece ----------------------------------------------------------- */

static int vtp_colourish(const vtp_array *a)
{
    static const char *const names[] = {"color", "colour", "rgb"};
    for (size_t i = 0; i < 3; i++)
        for (size_t p = 0; p < a->name_len; p++) {
            size_t k = 0;
            while (names[i][k] && p + k < a->name_len && (a->name[p + k] | 0x20) == names[i][k])
                k++;
            if (!names[i][k])
                return 1;
        }
    return 0;
}

static const vtp_array *vtp_find(const vtp *V, const vtp_piece *p, int role, int sec)
{
    for (size_t i = p->first; i < p->first + p->count; i++)
        if (V->arrays[i].role == role && (role == ROLE_POINTS || V->arrays[i].sec == sec))
            return &V->arrays[i];
    return NULL;
}

static const vtp_array *vtp_colour_array(const vtp *V, const vtp_piece *p, int k)
{
    int role = k ? ROLE_CDATA : ROLE_PDATA;
    const vtp_array *best = NULL;
    for (size_t i = p->first; i < p->first + p->count; i++) {
        const vtp_array *a = &V->arrays[i];
        if (a->role != role || a->type != VT_U8 || (a->comps != 3 && a->comps != 4))
            continue;
        if (p->scalars[k] && a->name && a->name_len == p->scalars_len[k] &&
            memcmp(a->name, p->scalars[k], a->name_len) == 0)
            return a;
        if (!best && vtp_colourish(a))
            best = a;
    }
    return best;
}

static oit_status vtp_colours(vtp *V, const vtp_array *a, size_t n, vtk_colours *col)
{
    if (!a)
        return OIT_OK;
    unsigned char *own = NULL;
    size_t own_cap = 0;
    vtp_view v;
    oit_status st = vtp_decode(V, a, n * (size_t)a->comps, &v, &own, &own_cap);
    if (st == OIT_OK)
        st = vtk_colours_alloc(col, &V->c->budget, n, a->comps, V->c->name, V->c->err);
    for (size_t i = 0; i < n && st == OIT_OK; i++)
        for (int k = 0; k < a->comps; k++)
            vtk_colour_set(col, i, k, a->comps, vtp_get(&v, i * (size_t)a->comps + (size_t)k), 0);
    oit_rd_release(&V->c->budget, (void **)&own, &own_cap, 1);
    return st;
}

static oit_status vtp_section(vtp *V, const vtp_piece *p, int sec, size_t npts, vtk_cells *cs)
{
    static const char *const names[SEC_N] = {"Verts", "Lines", "Polys", "Strips"};
    static const int types[SEC_N] = {VTK_CELL_POLY_VERTEX, VTK_CELL_POLY_LINE, VTK_CELL_POLYGON,
                                     VTK_CELL_TRIANGLE_STRIP};
    size_t n = (size_t)p->ncells[sec];
    cs->type = types[sec];
    if (n == 0)
        return OIT_OK;
    const vtp_array *ca = vtp_find(V, p, ROLE_CONN, sec), *oa = vtp_find(V, p, ROLE_OFFS, sec);
    if (!ca || !oa)
        return vtp_fail(V, p->at, OIT_ERR_FORMAT, "%s of %zu cells without its connectivity "
                        "and offsets arrays", names[sec], n);
    unsigned char *co = NULL, *oo = NULL;
    size_t cc = 0, oc = 0;
    vtp_view ov, cv;
    oit_status st = vtp_decode(V, oa, n, &ov, &oo, &oc);
    double last = st == OIT_OK ? vtp_get(&ov, n - 1) : 0;
    if (st == OIT_OK && !(last >= 0 && last < 1e15))
        st = vtp_fail(V, oa->at, OIT_ERR_FORMAT, "%s: bad last offset %g", names[sec], last);
    if (st == OIT_OK)
        st = vtp_decode(V, ca, (size_t)last, &cv, &co, &cc);
    double prev = 0;
    for (size_t i = 0; i < n && st == OIT_OK; i++) {
        double end = vtp_get(&ov, i);
        if (!(end >= prev) || end > last || end != floor(end))
            st = vtp_fail(V, oa->at, OIT_ERR_FORMAT, "%s: offset %zu is %g: offsets must grow",
                          names[sec], i, end);
        for (size_t k = (size_t)prev; st == OIT_OK && k < (size_t)end; k++) {
            double id = vtp_get(&cv, k);
            if (!(id >= 0) || id >= (double)npts || id != floor(id))
                st = vtp_fail(V, ca->at, OIT_ERR_FORMAT, "%s: point index %g out of range "
                              "(%zu points)", names[sec], id, npts);
            else
                st = vtk_cells_push_id(cs, &V->c->budget, (uint32_t)id, V->c->name, V->c->err);
        }
        if (st == OIT_OK)
            st = vtk_cells_push_off(cs, &V->c->budget, cs->nconn, V->c->name, V->c->err);
        prev = end;
    }
    oit_rd_release(&V->c->budget, (void **)&oo, &oc, 1);
    oit_rd_release(&V->c->budget, (void **)&co, &cc, 1);
    return st;
}

static oit_status vtp_points(vtp *V, const vtp_piece *p, oit_rd_vtable *pts)
{
    size_t n = (size_t)p->npoints;
    if (n == 0)
        return OIT_OK;
    if (p->npoints > UINT32_MAX)
        return vtp_fail(V, p->at, OIT_ERR_UNSUPPORTED, "more than 2^32 points in a piece");
    const vtp_array *a = vtp_find(V, p, ROLE_POINTS, 0);
    if (!a)
        return vtp_fail(V, p->at, OIT_ERR_FORMAT, "Piece of %zu points without <Points>", n);
    if (a->comps != 3)
        return vtp_fail(V, a->at, OIT_ERR_FORMAT, "Points with %d components, 3 expected",
                        a->comps);
    unsigned char *own = NULL;
    size_t own_cap = 0;
    vtp_view v;
    oit_status st = vtp_decode(V, a, 3 * n, &v, &own, &own_cap);
    for (size_t i = 0; i < n && st == OIT_OK; i++) {
        double in[3] = {vtp_get(&v, 3 * i), vtp_get(&v, 3 * i + 1), vtp_get(&v, 3 * i + 2)};
        oit_vertex vx;
        memset(vx.rgba, 255, sizeof vx.rgba);
        oit_rd_position(V->c, in, vx.pos);
        st = oit_rd_vtable_push(pts, &V->c->budget, &vx, V->c->name, V->c->err);
    }
    oit_rd_release(&V->c->budget, (void **)&own, &own_cap, 1);
    return st;
}

static oit_status vtp_piece_emit(vtp *V, const vtp_piece *p, vtk_skipped *skip)
{
    oit_rd_vtable pts = {0};
    vtk_cells cs[SEC_N];
    vtk_colours pc = {0}, cc = {0};
    memset(cs, 0, sizeof cs);
    uint64_t ncells = 0;
    for (int s = 0; s < SEC_N; s++)
        ncells += p->ncells[s];
    oit_status st = vtp_points(V, p, &pts);
    for (int s = 0; s < SEC_N && st == OIT_OK; s++)
        st = vtp_section(V, p, s, pts.count, &cs[s]);
    if (st == OIT_OK)
        st = vtp_colours(V, vtp_colour_array(V, p, 0), pts.count, &pc);
    if (st == OIT_OK)
        st = vtp_colours(V, vtp_colour_array(V, p, 1), (size_t)ncells, &cc);
    if (st == OIT_OK) {
        V->c->info->vertices_in += pts.count;
        vtk_apply_point_colours(&pts, &pc);
        vtk_note_colours(V->c->info, pc.components);
        vtk_note_colours(V->c->info, cc.components);
    }
    uint64_t first = 0;
    for (int s = 0; s < SEC_N && st == OIT_OK; s++) {
        st = vtk_emit_cells(V->c, &pts, &cs[s], first, &cc, skip);
        first += cs[s].ncells;
    }
    for (int s = 0; s < SEC_N; s++)
        vtk_cells_free(&cs[s], &V->c->budget);
    vtk_colours_free(&pc, &V->c->budget);
    vtk_colours_free(&cc, &V->c->budget);
    oit_rd_release(&V->c->budget, (void **)&pts.v, &pts.cap, sizeof *pts.v);
    return st;
}

static oit_status vtp_parse(oit_rd_ctx *c)
{
    vtp V;
    memset(&V, 0, sizeof V);
    V.c = c;
    vtk_skipped skip = {0};
    oit_status st = vtp_slurp(&V);
    if (st == OIT_OK)
        st = vtp_walk_file(&V);
    for (size_t i = 0; i < V.npieces && st == OIT_OK; i++)
        st = vtp_piece_emit(&V, &V.pieces[i], &skip);
    if (st == OIT_OK)
        st = vtk_report_skipped(c, &skip);
    oit_zlib_close(&V.z);
    oit_rd_release(&c->budget, (void **)&V.dec, &V.dec_cap, 1);
    oit_rd_release(&c->budget, (void **)&V.arrays, &V.arrays_cap, sizeof *V.arrays);
    oit_rd_release(&c->budget, (void **)&V.pieces, &V.pieces_cap, sizeof *V.pieces);
    oit_rd_release(&c->budget, (void **)&V.buf, &V.cap, 1);
    return st;
}

oit_status oit_read_vtp_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    (void)dir;
    oit_rd_ctx c;
    oit_status st = oit_rd_ctx_open(&c, f, name, desc, sink, user, info, err);
    if (st == OIT_OK)
        st = vtp_parse(&c);
    return oit_rd_ctx_close(&c, st);
}
