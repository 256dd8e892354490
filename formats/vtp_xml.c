/* The VTK XML file held whole and walked (vtp_internal.h): a small
 * tokenizer for the elements, attributes and text the reader needs (no DTD,
 * no entities), and the walk that records the root's settings, the pieces
 * and their DataArrays. Apart from read_vtp.c as the XML, not the
 * PolyData. */
#include "formats/vtp_internal.h"

#include <stdint.h>
#include <string.h>

#define VTP_MAX_DEPTH 32

oit_status vtp_slurp(vtp *V)
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
        while (p < end && vtp_xml_space(*p))
            p++;
        const unsigned char *name = p;
        while (p < end && xml_name_char(*p))
            p++;
        size_t nlen = (size_t)(p - name);
        while (p < end && vtp_xml_space(*p))
            p++;
        if (nlen == 0 || p >= end || *p != '=')
            return 0;
        p++;
        while (p < end && vtp_xml_space(*p))
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
        while (p < V->len && vtp_xml_space(V->buf[p]))
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
    while (p < to && vtp_xml_space(V->buf[p]))
        p++;
    if (p < to)
        a->text = from, a->text_end = to;
}

oit_status vtp_walk_file(vtp *V)
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
                if (!vtp_xml_space(V->buf[i]))
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
