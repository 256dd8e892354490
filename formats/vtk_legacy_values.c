/* The legacy VTK file's lexical layer (vtk_legacy_internal.h): lines split
 * into words, counts and type names, and values read as ASCII tokens or
 * BINARY big-endian bytes. Apart as the layer below the sections
 * (read_vtk.c, vtk_legacy_attributes.c), which read values through it. */
#include "formats/vtk_legacy_internal.h"

#include <math.h>
#include <string.h>

static const unsigned leg_size[] = {0, 0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};

/* Keywords are case-insensitive, as VTK's reader takes them. */
int leg_is(const leg *L, int i, const char *lit)
{
    if (i >= L->nwords || strlen(lit) != L->lens[i])
        return 0;
    for (size_t k = 0; k < L->lens[i]; k++)
        if ((L->words[i][k] | 0x20) != (lit[k] | 0x20))
            return 0;
    return 1;
}

/* Next line with content, split into words (NUL-terminated); 0 words at the
 * end of the file. */
oit_status leg_line(leg *L)
{
    for (;;) {
        char *line;
        int got;
        oit_status st = oit_rd_line(&L->c->in, &line, &got);
        if (st != OIT_OK)
            return st;
        L->nwords = 0;
        if (!got)
            return OIT_OK;
        char *p = line, *w;
        size_t n;
        while (L->nwords < 8 && (n = oit_rd_word(&p, &w)) > 0) {
            L->words[L->nwords] = w;
            L->lens[L->nwords++] = n;
            if (*p)
                *p++ = '\0';
        }
        if (L->nwords > 0)
            return OIT_OK;
    }
}

int leg_count(const leg *L, int i, uint64_t *out)
{
    char *p = i < L->nwords ? L->words[i] : (char *)"";
    int64_t v;
    if (!oit_rd_int(&p, &v, NULL) || v < 0)
        return 0;
    *out = (uint64_t)v;
    return 1;
}

static leg_type leg_type_of(const char *w, size_t n)
{
    static const struct { const char *name; leg_type t; } map[] = {
        {"bit", LT_BIT}, {"unsigned_char", LT_U8}, {"char", LT_I8}, {"signed_char", LT_I8},
        {"unsigned_short", LT_U16}, {"short", LT_I16}, {"unsigned_int", LT_U32},
        {"int", LT_I32}, {"unsigned_long", LT_U64}, {"long", LT_I64},
        {"vtkidtype", LT_I64}, {"vtktypeint64", LT_I64}, {"vtktypeuint64", LT_U64},
        {"vtktypeint32", LT_I32}, {"vtktypeuint32", LT_U32}, {"float", LT_F32},
        {"double", LT_F64}};
    for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
        if (oit_rd_word_eq_nocase(w, n, map[i].name))
            return map[i].t;
    return LT_BAD;
}

/* The data type named by word i; strings and unknown names are refused. */
oit_status leg_type_word(leg *L, int i, leg_type *t)
{
    if (i >= L->nwords)
        return leg_fail(L, OIT_ERR_FORMAT, "%s: data type missing", L->words[0]);
    *t = leg_type_of(L->words[i], L->lens[i]);
    if (*t == LT_BAD)
        return leg_fail(L, OIT_ERR_UNSUPPORTED, "%s: data type '%.40s' is not supported",
                        L->words[0], L->words[i]);
    return OIT_OK;
}

static double leg_be(const unsigned char *b, leg_type t)
{
    uint64_t u = 0;
    for (unsigned k = 0; k < leg_size[t]; k++)
        u = u << 8 | b[k];
    switch (t) {
    case LT_U8: case LT_U16: case LT_U32: return (double)u;
    case LT_I8: return (double)(int8_t)u;
    case LT_I16: return (double)(int16_t)u;
    case LT_I32: return (double)(int32_t)u;
    case LT_I64: return (double)(int64_t)u;
    case LT_U64: return (double)u;
    case LT_F32: { uint32_t v = (uint32_t)u; float f; memcpy(&f, &v, 4); return f; }
    case LT_F64: { double d; memcpy(&d, &u, 8); return d; }
    default: return 0.0;
    }
}

/* One value of type t: a token in ASCII, big-endian bytes in BINARY. */
oit_status leg_value(leg *L, leg_type t, const char *what, double *out)
{
    oit_rd_stream *s = &L->c->in;
    if (L->binary) {
        const unsigned char *b;
        oit_status st = oit_rd_bytes(s, leg_size[t], what, &b);
        if (st == OIT_OK)
            *out = leg_be(b, t);
        return st;
    }
    char *tok, *p;
    int got;
    oit_status st = oit_rd_token(s, &tok, &got);
    if (st != OIT_OK)
        return st;
    if (!got)
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "file ends in %s (truncated)", what);
    p = tok;
    if (!oit_rd_double(&p, out) || *p)
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "%s: not a number: '%.40s'", what, tok);
    return OIT_OK;
}

/* n values of type t skipped. */
oit_status leg_skip(leg *L, leg_type t, uint64_t n, const char *what)
{
    if (L->binary) {
        uint64_t bytes = t == LT_BIT ? (n + 7) / 8 : n * leg_size[t];
        while (bytes > 0) {
            const unsigned char *b;
            size_t step = bytes > ((size_t)1 << 16) ? (size_t)1 << 16 : (size_t)bytes;
            oit_status st = oit_rd_bytes(&L->c->in, step, what, &b);
            if (st != OIT_OK)
                return st;
            bytes -= step;
        }
        return OIT_OK;
    }
    double v;
    for (uint64_t i = 0; i < n; i++) {
        oit_status st = leg_value(L, t == LT_BIT ? LT_U8 : t, what, &v);
        if (st != OIT_OK)
            return st;
    }
    return OIT_OK;
}

oit_status leg_index(leg *L, double v, const char *what, uint32_t *id)
{
    if (!(v >= 0) || v >= (double)L->pts.count || v != floor(v))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: point index %.0f out of range (%zu points)",
                        what, v, L->pts.count);
    *id = (uint32_t)v;
    return OIT_OK;
}
