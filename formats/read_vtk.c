/* Legacy VTK reader (.vtk), ASCII and BINARY (big-endian).
 *
 * DATASET POLYDATA (POLYGONS and TRIANGLE_STRIPS drawn; VERTICES and LINES
 * read, counted in VTK's cell ids and not drawn) and UNSTRUCTURED_GRID
 * (triangles, quads, polygons, pixels, triangle strips drawn; vertices and
 * lines not drawn; linear volume cells (tetrahedra, voxels, hexahedra,
 * wedges, pyramids) drawn as their boundary faces, vtk_cells.c; higher
 * order cells and polyhedra skipped with a note on stderr). Cells in the
 * classic layout ("POLYGONS n size", each cell "count ids...") and in the
 * layout of file version 5 and later ("POLYGONS nOffsets nConnectivity"
 * then OFFSETS and CONNECTIVITY arrays).
 *
 * Colours: POINT_DATA or CELL_DATA COLOR_SCALARS (1 to 4 components, the
 * 4th alpha; floats 0..1 in ASCII, bytes in BINARY), else SCALARS of
 * unsigned_char with 3 or 4 components (0..255), else a FIELD array of
 * unsigned_char with 3 or 4 components named like a colour ("Colors",
 * "RGBA"); the first of the best kind is used, every other array skipped.
 * A cell colour overrides its points' colours. METADATA blocks are skipped.
 *
 * The colours follow the cells, so points and cells are held (charged to
 * the memory budget, grown as data arrives, never sized by a declared
 * count) and the triangles emitted at the end (vtk_internal.h). Errors name
 * the line in ASCII files and the byte offset in BINARY ones.
 */
#include "formats/vtk_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>

typedef enum leg_type {
    LT_BAD, LT_BIT, LT_U8, LT_I8, LT_U16, LT_I16, LT_U32, LT_I32, LT_U64, LT_I64, LT_F32, LT_F64
} leg_type;

static const unsigned leg_size[] = {0, 0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};

typedef struct leg {
    oit_rd_ctx *c;
    int binary, new_cells, ugrid;
    int have_points;
    oit_rd_vtable pts;
    vtk_cells sec[4]; /* POLYDATA: verts, lines, polys, strips (VTK's id order) */
    vtk_colours pc, cc;
    int pc_rank, cc_rank; /* kind of the colour array kept (higher wins) */
    int data;             /* 0 none, 1 POINT_DATA, 2 CELL_DATA */
    uint64_t tuples;      /* of the current POINT_DATA / CELL_DATA */
    char *words[8];
    size_t lens[8];
    int nwords;
} leg;

static oit_status leg_fail(leg *L, oit_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static oit_status leg_fail(leg *L, oit_status st, const char *fmt, ...)
{
    char msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (L->binary)
        return oit_rd_fail_offset(&L->c->in, oit_rd_offset(&L->c->in), st, "%s", msg);
    return oit_rd_fail_line(&L->c->in, st, "%s", msg);
}

/* Keywords are case-insensitive, as VTK's reader takes them. */
static int leg_is(const leg *L, int i, const char *lit)
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
static oit_status leg_line(leg *L)
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

static int leg_count(const leg *L, int i, uint64_t *out)
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
static oit_status leg_type_word(leg *L, int i, leg_type *t)
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
static oit_status leg_value(leg *L, leg_type t, const char *what, double *out)
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
static oit_status leg_skip(leg *L, leg_type t, uint64_t n, const char *what)
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

static oit_status leg_index(leg *L, double v, const char *what, uint32_t *id)
{
    if (!(v >= 0) || v >= (double)L->pts.count || v != floor(v))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: point index %.0f out of range (%zu points)",
                        what, v, L->pts.count);
    *id = (uint32_t)v;
    return OIT_OK;
}

/* ---- geometry ---------------------------------------------------------- */

static oit_status leg_points(leg *L)
{
    uint64_t n;
    leg_type t;
    if (L->have_points)
        return leg_fail(L, OIT_ERR_FORMAT, "a second POINTS section");
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "POINTS: expected a point count");
    oit_status st = leg_type_word(L, 2, &t);
    if (st == OIT_OK && (t == LT_BIT))
        st = leg_fail(L, OIT_ERR_UNSUPPORTED, "POINTS of type bit");
    if (st == OIT_OK && n > UINT32_MAX)
        st = leg_fail(L, OIT_ERR_UNSUPPORTED, "POINTS: more than 2^32 points");
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double in[3];
        for (int k = 0; k < 3 && st == OIT_OK; k++)
            st = leg_value(L, t, "POINTS", &in[k]);
        oit_vertex v;
        memset(v.rgba, 255, sizeof v.rgba);
        if (st == OIT_OK) {
            oit_rd_position(L->c, in, v.pos);
            st = oit_rd_vtable_push(&L->pts, &L->c->budget, &v, L->c->name, L->c->err);
        }
    }
    L->have_points = 1;
    L->c->info->vertices_in = L->pts.count;
    return st;
}

/* Classic layout: n cells of "count id...", size values in all. */
static oit_status leg_cells_classic(leg *L, vtk_cells *cs, uint64_t n, uint64_t size,
                                    const char *what)
{
    oit_status st = OIT_OK;
    uint64_t used = 0;
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double v;
        if ((st = leg_value(L, LT_I32, what, &v)) != OIT_OK)
            break;
        if (!(v >= 0 && v <= (double)size && v == floor(v)) || used + 1 + (uint64_t)v > size)
            return leg_fail(L, OIT_ERR_FORMAT, "%s: cell %" PRIu64 " of %.0f points overruns "
                            "the declared size %" PRIu64, what, i, v, size);
        used += 1 + (uint64_t)v;
        for (uint64_t k = 0; k < (uint64_t)v && st == OIT_OK; k++) {
            double idv;
            uint32_t id = 0;
            st = leg_value(L, LT_I32, what, &idv);
            if (st == OIT_OK)
                st = leg_index(L, idv, what, &id);
            if (st == OIT_OK)
                st = vtk_cells_push_id(cs, &L->c->budget, id, L->c->name, L->c->err);
        }
        if (st == OIT_OK)
            st = vtk_cells_push_off(cs, &L->c->budget, cs->nconn, L->c->name, L->c->err);
    }
    if (st == OIT_OK && used != size)
        return leg_fail(L, OIT_ERR_FORMAT, "%s: cells hold %" PRIu64 " values, the header "
                        "says %" PRIu64, what, used, size);
    return st;
}

/* Version 5 layout: OFFSETS (nofs values from 0) then CONNECTIVITY. */
static oit_status leg_cells_new(leg *L, vtk_cells *cs, uint64_t nofs, uint64_t nconn,
                                const char *what)
{
    leg_type t;
    oit_status st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "OFFSETS"))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected OFFSETS (file version 5 layout)", what);
    if (st == OIT_OK)
        st = leg_type_word(L, 1, &t);
    uint64_t prev = 0;
    for (uint64_t i = 0; i < nofs && st == OIT_OK; i++) {
        double v;
        if ((st = leg_value(L, t, "OFFSETS", &v)) != OIT_OK)
            break;
        if (!(v >= (double)prev) || v > (double)nconn || (i == 0 && v != 0))
            return leg_fail(L, OIT_ERR_FORMAT, "%s: offset %" PRIu64 " is %.0f: offsets must "
                            "start at 0 and grow up to %" PRIu64, what, i, v, nconn);
        prev = (uint64_t)v;
        if (i > 0)
            st = vtk_cells_push_off(cs, &L->c->budget, prev, L->c->name, L->c->err);
    }
    if (st == OIT_OK && nofs > 0 && prev != nconn)
        return leg_fail(L, OIT_ERR_FORMAT, "%s: the last offset is %" PRIu64 ", not the "
                        "connectivity size %" PRIu64, what, prev, nconn);
    if (st == OIT_OK)
        st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "CONNECTIVITY"))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected CONNECTIVITY after OFFSETS", what);
    if (st == OIT_OK)
        st = leg_type_word(L, 1, &t);
    for (uint64_t i = 0; i < nconn && st == OIT_OK; i++) {
        double v;
        uint32_t id = 0;
        st = leg_value(L, t, "CONNECTIVITY", &v);
        if (st == OIT_OK)
            st = leg_index(L, v, what, &id);
        if (st == OIT_OK)
            st = vtk_cells_push_id(cs, &L->c->budget, id, L->c->name, L->c->err);
    }
    return st;
}

static oit_status leg_cells(leg *L, vtk_cells *cs, int type)
{
    uint64_t a, b;
    char what[32]; /* the words do not outlive the next read */
    snprintf(what, sizeof what, "%s", L->words[0]);
    if (!L->have_points)
        return leg_fail(L, OIT_ERR_FORMAT, "%s before POINTS", what);
    if (cs->ncells > 0)
        return leg_fail(L, OIT_ERR_FORMAT, "a second %s section", what);
    if (!leg_count(L, 1, &a) || !leg_count(L, 2, &b))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected two counts", what);
    cs->type = type;
    return L->new_cells ? leg_cells_new(L, cs, a, b, what) : leg_cells_classic(L, cs, a, b, what);
}

static oit_status leg_cell_types(leg *L)
{
    uint64_t n;
    vtk_cells *cs = &L->sec[0];
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "CELL_TYPES: expected a count");
    if (n != cs->ncells || cs->ntypes > 0)
        return leg_fail(L, OIT_ERR_FORMAT, "CELL_TYPES: %" PRIu64 " types for %zu CELLS", n,
                        cs->ncells);
    oit_status st = OIT_OK;
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double v;
        st = leg_value(L, LT_I32, "CELL_TYPES", &v);
        if (st == OIT_OK)
            st = vtk_cells_push_type(cs, &L->c->budget, v >= 0 && v < 255 ? (uint8_t)v : 255,
                                     L->c->name, L->c->err);
    }
    return st;
}

/* ---- attributes -------------------------------------------------------- */

static uint64_t leg_cell_total(const leg *L)
{
    return (uint64_t)L->sec[0].ncells + L->sec[1].ncells + L->sec[2].ncells + L->sec[3].ncells;
}

static oit_status leg_data(leg *L, int which)
{
    uint64_t n;
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected a count", L->words[0]);
    uint64_t want = which == 1 ? L->pts.count : leg_cell_total(L);
    if (n != want)
        return leg_fail(L, OIT_ERR_FORMAT, "%s %" PRIu64 " for %" PRIu64 " %s", L->words[0], n,
                        want, which == 1 ? "points" : "cells");
    L->data = which;
    L->tuples = n;
    return OIT_OK;
}

/* A colour array of comps components (rank: its kind) read, or skipped
 * when a better one is already kept. unit: values are 0..1 floats. */
static oit_status leg_colours(leg *L, int rank, leg_type t, int comps, int unit)
{
    vtk_colours *col = L->data == 1 ? &L->pc : &L->cc;
    int *kept = L->data == 1 ? &L->pc_rank : &L->cc_rank;
    if (rank <= *kept)
        return leg_skip(L, t, L->tuples * (uint64_t)comps, "a colour array");
    vtk_colours_free(col, &L->c->budget);
    oit_status st = vtk_colours_alloc(col, &L->c->budget, (size_t)L->tuples, comps, L->c->name,
                                      L->c->err);
    for (uint64_t i = 0; i < L->tuples && st == OIT_OK; i++)
        for (int k = 0; k < comps && st == OIT_OK; k++) {
            double v;
            st = leg_value(L, t, "colours", &v);
            if (st == OIT_OK)
                vtk_colour_set(col, (size_t)i, k, comps, v, unit);
        }
    *kept = rank;
    return st;
}

static oit_status leg_need_data(leg *L)
{
    if (L->data == 0)
        return leg_fail(L, OIT_ERR_FORMAT, "%s outside POINT_DATA or CELL_DATA", L->words[0]);
    return OIT_OK;
}

static oit_status leg_scalars(leg *L)
{
    leg_type t;
    uint64_t comps = 1;
    oit_status st = leg_type_word(L, 2, &t);
    if (st == OIT_OK && L->nwords > 3 && (!leg_count(L, 3, &comps) || comps < 1 || comps > 4))
        return leg_fail(L, OIT_ERR_FORMAT, "SCALARS: expected 1 to 4 components");
    if (st == OIT_OK)
        st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "LOOKUP_TABLE"))
        return leg_fail(L, OIT_ERR_FORMAT, "SCALARS: expected LOOKUP_TABLE");
    if (st != OIT_OK)
        return st;
    if (t == LT_U8 && comps >= 3)
        return leg_colours(L, 2, t, (int)comps, 0);
    return leg_skip(L, t, L->tuples * comps, "SCALARS");
}

/* VTK 9 follows an array with METADATA and lines up to a blank one. */
static oit_status leg_skip_metadata(leg *L)
{
    for (;;) {
        char *line, *p;
        int got;
        oit_status st = oit_rd_line(&L->c->in, &line, &got);
        if (st != OIT_OK || !got)
            return st;
        p = line;
        if (oit_rd_skip_blanks(&p) == '\0')
            return OIT_OK;
    }
}

static int leg_colour_name(const char *w)
{
    static const char *const names[] = {"color", "colour", "rgb"};
    for (size_t i = 0; i < 3; i++)
        for (const char *p = w; *p; p++) {
            size_t k = 0;
            while (names[i][k] && (p[k] | 0x20) == names[i][k])
                k++;
            if (!names[i][k])
                return 1;
        }
    return 0;
}

static oit_status leg_field(leg *L)
{
    uint64_t n;
    if (!leg_count(L, 2, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "FIELD: expected an array count");
    oit_status st = OIT_OK;
    for (uint64_t i = 0; i < n && st == OIT_OK;) {
        if ((st = leg_line(L)) != OIT_OK)
            return st;
        if (L->nwords == 0)
            return leg_fail(L, OIT_ERR_FORMAT, "file ends in FIELD after %" PRIu64 " of %" PRIu64
                            " arrays (truncated)", i, n);
        if (leg_is(L, 0, "METADATA")) {
            if ((st = leg_skip_metadata(L)) != OIT_OK)
                return st;
            continue;
        }
        i++;
        if (leg_is(L, 0, "NULL_ARRAY"))
            continue;
        uint64_t comps, tuples;
        leg_type t;
        if (!leg_count(L, 1, &comps) || !leg_count(L, 2, &tuples))
            return leg_fail(L, OIT_ERR_FORMAT, "FIELD array: expected 'name components tuples "
                            "type'");
        if ((st = leg_type_word(L, 3, &t)) != OIT_OK)
            return st;
        if (L->data && t == LT_U8 && (comps == 3 || comps == 4) && tuples == L->tuples &&
            leg_colour_name(L->words[0]))
            st = leg_colours(L, 1, t, (int)comps, 0);
        else
            st = leg_skip(L, t, comps * tuples, "FIELD array");
    }
    return st;
}

/* The keyword lines of an attribute section other than SCALARS/FIELD. */
static oit_status leg_attribute(leg *L, int *done)
{
    leg_type t;
    uint64_t n;
    *done = 1;
    if (leg_is(L, 0, "SCALARS"))
        return leg_need_data(L) == OIT_OK ? leg_scalars(L) : OIT_ERR_FORMAT;
    if (leg_is(L, 0, "COLOR_SCALARS")) {
        if (leg_need_data(L) != OIT_OK)
            return OIT_ERR_FORMAT;
        if (!leg_count(L, 2, &n) || n < 1 || n > 4)
            return leg_fail(L, OIT_ERR_FORMAT, "COLOR_SCALARS: expected 1 to 4 components");
        return leg_colours(L, 3, L->binary ? LT_U8 : LT_F32, (int)n, !L->binary);
    }
    int per = leg_is(L, 0, "VECTORS") || leg_is(L, 0, "NORMALS") ? 3
              : leg_is(L, 0, "TENSORS") ? 9 : leg_is(L, 0, "TENSORS6") ? 6
              : leg_is(L, 0, "GLOBAL_IDS") || leg_is(L, 0, "PEDIGREE_IDS") ? 1 : 0;
    int typ = 2;
    if (leg_is(L, 0, "TEXTURE_COORDINATES")) {
        if (!leg_count(L, 2, &n) || n < 1 || n > 3)
            return leg_fail(L, OIT_ERR_FORMAT, "TEXTURE_COORDINATES: expected 1 to 3 dimensions");
        per = (int)n, typ = 3;
    }
    if (per) {
        if (leg_need_data(L) != OIT_OK)
            return OIT_ERR_FORMAT;
        oit_status st = leg_type_word(L, typ, &t);
        return st == OIT_OK ? leg_skip(L, t, L->tuples * (uint64_t)per, "an attribute array")
                            : st;
    }
    if (leg_is(L, 0, "LOOKUP_TABLE")) {
        if (!leg_count(L, 2, &n))
            return leg_fail(L, OIT_ERR_FORMAT, "LOOKUP_TABLE: expected a count");
        return leg_skip(L, L->binary ? LT_U8 : LT_F32, 4 * n, "LOOKUP_TABLE");
    }
    *done = 0;
    return OIT_OK;
}

/* ---- the file ---------------------------------------------------------- */

static oit_status leg_header(leg *L)
{
    oit_rd_stream *s = &L->c->in;
    char *line;
    int got;
    oit_status st = oit_rd_skip_bom(s);
    if (st == OIT_OK)
        st = oit_rd_line(s, &line, &got);
    if (st != OIT_OK)
        return st;
    int major = 0, minor = 0;
    if (!got || sscanf(line, "# vtk DataFile Version %d.%d", &major, &minor) < 1)
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "not a legacy VTK file (the first line "
                                "should be '# vtk DataFile Version N.N')");
    L->new_cells = major >= 5;
    if ((st = oit_rd_line(s, &line, &got)) != OIT_OK) /* the title */
        return st;
    if (st == OIT_OK)
        st = leg_line(L);
    if (st != OIT_OK)
        return st;
    if (leg_is(L, 0, "BINARY"))
        L->binary = 1;
    else if (!leg_is(L, 0, "ASCII"))
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "expected ASCII or BINARY on line 3");
    if ((st = leg_line(L)) != OIT_OK)
        return st;
    if (!leg_is(L, 0, "DATASET"))
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "expected DATASET after ASCII/BINARY");
    if (leg_is(L, 1, "UNSTRUCTURED_GRID"))
        L->ugrid = 1;
    else if (!leg_is(L, 1, "POLYDATA"))
        return oit_rd_fail_line(s, OIT_ERR_UNSUPPORTED, "DATASET %.40s is not supported (only "
                                "POLYDATA and UNSTRUCTURED_GRID hold surfaces)",
                                L->nwords > 1 ? L->words[1] : "(none)");
    return OIT_OK;
}

static oit_status leg_section(leg *L)
{
    static const char *const poly[4] = {"VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS"};
    static const int poly_type[4] = {VTK_CELL_POLY_VERTEX, VTK_CELL_POLY_LINE, VTK_CELL_POLYGON,
                                     VTK_CELL_TRIANGLE_STRIP};
    if (leg_is(L, 0, "POINTS"))
        return leg_points(L);
    for (int i = 0; i < 4 && !L->ugrid; i++)
        if (leg_is(L, 0, poly[i]))
            return L->data ? leg_fail(L, OIT_ERR_FORMAT, "%s after the data arrays", poly[i])
                           : leg_cells(L, &L->sec[i], poly_type[i]);
    if (L->ugrid && leg_is(L, 0, "CELLS"))
        return L->data ? leg_fail(L, OIT_ERR_FORMAT, "CELLS after the data arrays")
                       : leg_cells(L, &L->sec[0], 0);
    if (L->ugrid && leg_is(L, 0, "CELL_TYPES"))
        return leg_cell_types(L);
    if (leg_is(L, 0, "POINT_DATA"))
        return leg_data(L, 1);
    if (leg_is(L, 0, "CELL_DATA"))
        return leg_data(L, 2);
    if (leg_is(L, 0, "FIELD"))
        return leg_field(L);
    if (leg_is(L, 0, "METADATA"))
        return leg_skip_metadata(L);
    int done;
    oit_status st = leg_attribute(L, &done);
    if (done)
        return st;
    return leg_fail(L, OIT_ERR_FORMAT, "unknown keyword '%.40s'", L->words[0]);
}

static oit_status leg_emit(leg *L)
{
    if (L->ugrid && L->sec[0].ntypes != L->sec[0].ncells)
        return oit_error_set(L->c->err, OIT_ERR_FORMAT, "%s: %zu CELLS but no CELL_TYPES "
                             "section", L->c->name, L->sec[0].ncells);
    vtk_apply_point_colours(&L->pts, &L->pc);
    vtk_note_colours(L->c->info, L->pc.components);
    vtk_note_colours(L->c->info, L->cc.components);
    vtk_skipped skip = {0};
    uint64_t first = 0;
    oit_status st = OIT_OK;
    for (int i = 0; i < 4 && st == OIT_OK; i++) {
        st = vtk_emit_cells(L->c, &L->pts, &L->sec[i], first, &L->cc, &skip);
        first += L->sec[i].ncells;
    }
    if (st == OIT_OK)
        st = vtk_report_skipped(L->c, &skip);
    return st;
}

static oit_status leg_parse(oit_rd_ctx *c)
{
    leg L;
    memset(&L, 0, sizeof L);
    L.c = c;
    oit_status st = leg_header(&L);
    while (st == OIT_OK) {
        if ((st = leg_line(&L)) != OIT_OK || L.nwords == 0)
            break;
        st = leg_section(&L);
    }
    if (st == OIT_OK)
        st = leg_emit(&L);
    for (int i = 0; i < 4; i++)
        vtk_cells_free(&L.sec[i], &c->budget);
    vtk_colours_free(&L.pc, &c->budget);
    vtk_colours_free(&L.cc, &c->budget);
    oit_rd_release(&c->budget, (void **)&L.pts.v, &L.pts.cap, sizeof *L.pts.v);
    return st;
}

oit_status oit_read_vtk_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    (void)dir;
    oit_rd_ctx c;
    oit_status st = oit_rd_ctx_open(&c, f, name, desc, sink, user, info, err);
    if (st == OIT_OK)
        st = leg_parse(&c);
    return oit_rd_ctx_close(&c, st);
}
