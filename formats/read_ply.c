/* PLY reader: ascii, binary_little_endian and binary_big_endian.
 *
 * Any element/property layout: the "vertex" element supplies x, y, z and
 * optionally red/green/blue[/alpha] (or diffuse_red...), as integers in
 * 0..255 or floats in 0..1; the "face" element supplies a list property named
 * vertex_indices or vertex_index (any integer count and index types) and
 * optionally a per-face colour, which overrides the vertex colour of that
 * face's triangles. Every other property and element, lists included, is
 * skipped. Polygons are fan-triangulated; faces with fewer than three
 * vertices are skipped; an index outside the vertex table is an error.
 * Header lines other than format/element/property/end_header are ignored
 * like comments (old Blender exporters wrote bare text there).
 *
 * Nothing is allocated from a declared count: the vertex table and polygon
 * scratch grow as values arrive, and each element's declared count is first
 * checked against the bytes left in the file, so a header claiming billions
 * of items in a small file fails at once. The face element must follow the
 * vertex element (streaming faces needs the table); the reverse order is
 * reported as unsupported.
 *
 * Triangles touching a NaN/inf vertex are dropped and counted in
 * info->nonfinite_dropped.
 */
#include "formats/readers_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>

#define PLY_MAX_PROPS 64
#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_NAME 24 /* longer names are kept truncated: none we use is */

typedef enum ply_type {
    PLY_NONE, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64
} ply_type;

static const unsigned ply_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

enum ply_role { ROLE_NONE, ROLE_X, ROLE_Y, ROLE_Z, ROLE_R, ROLE_G, ROLE_B, ROLE_A, ROLE_INDICES };

typedef enum ply_kind { ELEM_OTHER, ELEM_VERTEX, ELEM_FACE } ply_kind;

typedef struct ply_prop {
    ply_type type;       /* value type (of the items, for a list)   */
    ply_type count_type; /* PLY_NONE for a scalar property          */
    int role;
    char name[PLY_MAX_NAME];
} ply_prop;

typedef struct ply_element {
    char name[PLY_MAX_NAME];
    uint64_t count;
    ply_prop props[PLY_MAX_PROPS];
    int nprops;
    ply_kind kind;
    int role_prop[ROLE_INDICES + 1]; /* property index per role, -1 if absent */
} ply_element;

typedef struct ply_reader {
    oit_rd_ctx *c;
    int ascii, swap; /* swap: file byte order differs from the host's */
    ply_element el[PLY_MAX_ELEMENTS];
    int nel;
    int64_t file_size; /* -1 when unknown */
    oit_rd_vtable tab;
    int have_vertices;
    size_t *idx; /* the current polygon's indices */
    size_t nidx, capidx;
    char what[PLY_MAX_NAME + 16];
} ply_reader;

/* Errors name the line in ascii files and the byte offset in binary ones:
 * ply_fail(r, st, fmt, ...). */
#define ply_fail(r, ...) oit_rd_fail_here(&(r)->c->in, !(r)->ascii, __VA_ARGS__)

/* ---- header ----------------------------------------------------------- */

static ply_type ply_type_named(const char *w, size_t n)
{
    static const struct { const char *name; ply_type t; } names[] = {
        {"char", PLY_I8},     {"int8", PLY_I8},    {"uchar", PLY_U8},    {"uint8", PLY_U8},
        {"short", PLY_I16},   {"int16", PLY_I16},  {"ushort", PLY_U16},  {"uint16", PLY_U16},
        {"int", PLY_I32},     {"int32", PLY_I32},  {"uint", PLY_U32},    {"uint32", PLY_U32},
        {"float", PLY_F32},   {"float32", PLY_F32}, {"double", PLY_F64}, {"float64", PLY_F64},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (oit_rd_word_eq(w, n, names[i].name))
            return names[i].t;
    return PLY_NONE;
}

static oit_status ply_header_format(ply_reader *r, char *p)
{
    char *w;
    size_t n = oit_rd_word(&p, &w);
    int host_be = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
    if (oit_rd_word_eq(w, n, "ascii"))
        r->ascii = 1;
    else if (oit_rd_word_eq(w, n, "binary_little_endian"))
        r->swap = host_be;
    else if (oit_rd_word_eq(w, n, "binary_big_endian"))
        r->swap = !host_be;
    else
        return oit_rd_fail_line(&r->c->in, OIT_ERR_FORMAT, "unknown PLY format '%.*s'",
                                (int)(n < 40 ? n : 40), w);
    return OIT_OK;
}

static oit_status ply_header_element(ply_reader *r, char *p)
{
    char *w;
    size_t n = oit_rd_word(&p, &w);
    int64_t count;
    if (n == 0 || !oit_rd_int(&p, &count, NULL) || count < 0)
        return oit_rd_fail_line(&r->c->in, OIT_ERR_FORMAT, "expected 'element NAME COUNT'");
    if (r->nel == PLY_MAX_ELEMENTS)
        return oit_rd_fail_line(&r->c->in, OIT_ERR_UNSUPPORTED, "more than %d elements",
                                PLY_MAX_ELEMENTS);
    ply_element *e = &r->el[r->nel++];
    memset(e, 0, sizeof *e);
    memcpy(e->name, w, n < PLY_MAX_NAME ? n : PLY_MAX_NAME - 1);
    e->count = (uint64_t)count;
    return OIT_OK;
}

static oit_status ply_header_property(ply_reader *r, char *p)
{
    oit_rd_stream *in = &r->c->in;
    if (r->nel == 0)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "property before any element");
    ply_element *e = &r->el[r->nel - 1];
    if (e->nprops == PLY_MAX_PROPS)
        return oit_rd_fail_line(in, OIT_ERR_UNSUPPORTED, "more than %d properties in element '%s'",
                                PLY_MAX_PROPS, e->name);
    ply_prop *pr = &e->props[e->nprops];
    memset(pr, 0, sizeof *pr);
    char *w;
    size_t n = oit_rd_word(&p, &w);
    if (oit_rd_word_eq(w, n, "list")) {
        n = oit_rd_word(&p, &w);
        pr->count_type = ply_type_named(w, n);
        if (pr->count_type == PLY_NONE || pr->count_type >= PLY_F32)
            return oit_rd_fail_line(in, OIT_ERR_FORMAT, "bad list count type '%.*s'",
                                    (int)(n < 40 ? n : 40), w);
        n = oit_rd_word(&p, &w);
    }
    pr->type = ply_type_named(w, n);
    if (pr->type == PLY_NONE)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "unknown property type '%.*s'",
                                (int)(n < 40 ? n : 40), w);
    n = oit_rd_word(&p, &w);
    if (n == 0)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "property without a name");
    memcpy(pr->name, w, n < PLY_MAX_NAME ? n : PLY_MAX_NAME - 1);
    e->nprops++;
    return OIT_OK;
}

static oit_status ply_header(ply_reader *r)
{
    oit_rd_stream *in = &r->c->in;
    int have_format = 0;
    for (uint64_t lineno = 1;; lineno++) {
        char *line, *p, *w;
        int got;
        oit_status st = oit_rd_line(in, &line, &got);
        if (st != OIT_OK)
            return st;
        if (!got)
            return oit_rd_fail_line(in, OIT_ERR_FORMAT, "file ends before 'end_header'");
        p = line;
        size_t n = oit_rd_word(&p, &w);
        if (lineno == 1) {
            if (!oit_rd_word_eq(w, n, "ply") || oit_rd_skip_blanks(&p) != '\0')
                return oit_rd_fail_line(in, OIT_ERR_FORMAT, "not a PLY file (no 'ply' line)");
        } else if (oit_rd_word_eq(w, n, "format")) {
            st = ply_header_format(r, p);
            have_format = 1;
        } else if (oit_rd_word_eq(w, n, "element")) {
            st = ply_header_element(r, p);
        } else if (oit_rd_word_eq(w, n, "property")) {
            st = ply_header_property(r, p);
        } else if (oit_rd_word_eq(w, n, "end_header")) {
            if (!have_format)
                return oit_rd_fail_line(in, OIT_ERR_FORMAT, "no 'format' line in the header");
            return OIT_OK;
        } /* comment, obj_info and stray text (Blender 2.4 wrote a bare line) */
        if (st != OIT_OK)
            return st;
    }
}

/* ---- roles ------------------------------------------------------------ */

static int ply_role_of(ply_kind kind, const ply_prop *p)
{
    static const char *colour[][2] = {{"red", "diffuse_red"},   {"green", "diffuse_green"},
                                      {"blue", "diffuse_blue"}, {"alpha", "diffuse_alpha"}};
    const char *n = p->name;
    if (p->count_type != PLY_NONE)
        return kind == ELEM_FACE && (!strcmp(n, "vertex_indices") || !strcmp(n, "vertex_index"))
                   ? ROLE_INDICES : ROLE_NONE;
    if (kind == ELEM_VERTEX && (!strcmp(n, "x") || !strcmp(n, "y") || !strcmp(n, "z")))
        return ROLE_X + (n[0] - 'x');
    for (int k = 0; k < 4; k++)
        if (!strcmp(n, colour[k][0]) || !strcmp(n, colour[k][1]))
            return ROLE_R + k;
    return ROLE_NONE;
}

static oit_status ply_assign_roles(ply_reader *r)
{
    for (int i = 0; i < r->nel; i++) {
        ply_element *e = &r->el[i];
        e->kind = !strcmp(e->name, "vertex") ? ELEM_VERTEX
                  : !strcmp(e->name, "face") ? ELEM_FACE : ELEM_OTHER;
        for (int k = 0; k <= ROLE_INDICES; k++)
            e->role_prop[k] = -1;
        for (int j = 0; j < e->nprops; j++) {
            int role = e->kind == ELEM_OTHER ? ROLE_NONE : ply_role_of(e->kind, &e->props[j]);
            e->props[j].role = role;
            if (role != ROLE_NONE && e->role_prop[role] < 0)
                e->role_prop[role] = j;
            else
                e->props[j].role = ROLE_NONE; /* a repeated name is just skipped */
        }
        int *rp = e->role_prop;
        if (e->kind == ELEM_VERTEX && (rp[ROLE_X] < 0 || rp[ROLE_Y] < 0 || rp[ROLE_Z] < 0))
            return oit_error_set(r->c->err, OIT_ERR_FORMAT,
                                 "%s: header: element 'vertex' lacks x, y or z", r->c->name);
        if (e->kind == ELEM_FACE && rp[ROLE_INDICES] < 0)
            return oit_error_set(r->c->err, OIT_ERR_FORMAT,
                                 "%s: header: element 'face' has no vertex_indices list",
                                 r->c->name);
        if (e->kind != ELEM_OTHER && rp[ROLE_R] >= 0 && rp[ROLE_G] >= 0 && rp[ROLE_B] >= 0)
            r->c->info->attributes |= OIT_ATTR_COLOUR;
        if (e->kind != ELEM_OTHER && rp[ROLE_A] >= 0)
            r->c->info->attributes |= OIT_ATTR_ALPHA;
    }
    return OIT_OK;
}

/* ---- values ----------------------------------------------------------- */

static double ply_decode(const unsigned char *b, ply_type t, int swap)
{
    unsigned char v[8];
    unsigned n = ply_size[t];
    for (unsigned i = 0; i < n; i++)
        v[i] = swap ? b[n - 1 - i] : b[i];
    int8_t i8; uint8_t u8; int16_t i16; uint16_t u16;
    int32_t i32; uint32_t u32; float f32; double f64;
    switch (t) {
    case PLY_I8: memcpy(&i8, v, 1); return i8;
    case PLY_U8: memcpy(&u8, v, 1); return u8;
    case PLY_I16: memcpy(&i16, v, 2); return i16;
    case PLY_U16: memcpy(&u16, v, 2); return u16;
    case PLY_I32: memcpy(&i32, v, 4); return i32;
    case PLY_U32: memcpy(&u32, v, 4); return u32;
    case PLY_F32: memcpy(&f32, v, 4); return f32;
    case PLY_F64: memcpy(&f64, v, 8); return f64;
    default: return 0.0;
    }
}

static oit_status ply_value(ply_reader *r, ply_type t, double *out)
{
    oit_status st;
    if (!r->ascii) {
        const unsigned char *b;
        if ((st = oit_rd_bytes(&r->c->in, ply_size[t], r->what, &b)) == OIT_OK)
            *out = ply_decode(b, t, r->swap);
        return st;
    }
    char *tok;
    int got;
    if ((st = oit_rd_token(&r->c->in, &tok, &got)) != OIT_OK)
        return st;
    if (!got)
        return ply_fail(r, OIT_ERR_FORMAT, "file ends inside %s (truncated)", r->what);
    char *p = tok;
    int64_t i;
    int ok = t >= PLY_F32 ? oit_rd_double(&p, out) : oit_rd_int(&p, &i, NULL);
    if (!ok)
        return ply_fail(r, OIT_ERR_FORMAT, "bad number '%.40s' in %s", tok, r->what);
    if (t < PLY_F32)
        *out = (double)i;
    return OIT_OK;
}

/* A list: its indices go to r->idx when `keep`, otherwise they are skipped. */
static oit_status ply_list(ply_reader *r, const ply_prop *p, int keep)
{
    double d;
    oit_status st = ply_value(r, p->count_type, &d);
    if (st != OIT_OK)
        return st;
    if (d < 0)
        return ply_fail(r, OIT_ERR_FORMAT, "negative list length %.0f in %s", d, r->what);
    uint64_t n = (uint64_t)d;
    if (keep)
        r->nidx = 0;
    for (uint64_t k = 0; k < n; k++) {
        if ((st = ply_value(r, p->type, &d)) != OIT_OK)
            return st;
        if (!keep)
            continue;
        if (!(d >= 0 && d < (double)r->tab.count) || d != floor(d))
            return ply_fail(r, OIT_ERR_FORMAT, "vertex index %.0f out of range (%zu vertices)", d,
                            r->tab.count);
        if (r->nidx == r->capidx &&
            (st = oit_rd_grow(&r->c->budget, (void **)&r->idx, &r->capidx, sizeof *r->idx,
                              r->nidx + 1, r->c->name, "polygon", r->c->err)) != OIT_OK)
            return st;
        r->idx[r->nidx++] = (size_t)d;
    }
    return OIT_OK;
}

/* One item of element e: scalar values into vals[], the index list (if the
 * element has one) into r->idx. */
static oit_status ply_item(ply_reader *r, const ply_element *e, double *vals)
{
    oit_status st = OIT_OK;
    for (int j = 0; j < e->nprops && st == OIT_OK; j++) {
        const ply_prop *p = &e->props[j];
        if (p->count_type != PLY_NONE)
            st = ply_list(r, p, p->role == ROLE_INDICES);
        else
            st = ply_value(r, p->type, &vals[j]);
    }
    return st;
}

static uint8_t ply_color(const ply_prop *p, double v)
{
    return p->type >= PLY_F32 ? oit_rd_unit_to_u8(v) : oit_rd_clamp_u8(v);
}

/* Overwrites rgba components for the colour roles the element has. */
static void ply_apply_color(const ply_element *e, const double *vals, uint8_t rgba[4])
{
    for (int k = 0; k < 4; k++) {
        int j = e->role_prop[ROLE_R + k];
        if (j >= 0)
            rgba[k] = ply_color(&e->props[j], vals[j]);
    }
}

/* ---- elements --------------------------------------------------------- */

/* Minimum bytes per item: what a declared count must fit in. */
static uint64_t ply_min_item_bytes(const ply_reader *r, const ply_element *e)
{
    uint64_t bytes = 0;
    for (int j = 0; j < e->nprops; j++) {
        const ply_prop *p = &e->props[j];
        bytes += r->ascii ? 2 : ply_size[p->count_type != PLY_NONE ? p->count_type : p->type];
    }
    return r->ascii && bytes ? bytes - 1 : bytes;
}

static oit_status ply_check_count(ply_reader *r, const ply_element *e)
{
    if (r->file_size < 0)
        return OIT_OK;
    uint64_t left = (uint64_t)r->file_size - oit_rd_offset(&r->c->in);
    uint64_t min = ply_min_item_bytes(r, e);
    if (min > 0 && e->count > (left + 1) / min)
        return ply_fail(r, OIT_ERR_FORMAT,
                        "element '%s' declares %" PRIu64 " items (at least %" PRIu64
                        " bytes each) but only %" PRIu64 " bytes follow",
                        e->name, e->count, min, left);
    return OIT_OK;
}

static oit_status ply_vertex(ply_reader *r, const ply_element *e, const double *vals)
{
    oit_vertex v;
    double in[3];
    for (int k = 0; k < 3; k++)
        in[k] = vals[e->role_prop[ROLE_X + k]];
    oit_rd_position(r->c, in, v.pos);
    memset(v.rgba, 255, sizeof v.rgba);
    ply_apply_color(e, vals, v.rgba);
    return oit_rd_vtable_push(&r->tab, &r->c->budget, &v, r->c->name, r->c->err);
}

static oit_status ply_face(ply_reader *r, const ply_element *e, const double *vals)
{
    r->c->info->faces_in++;
    oit_status st = OIT_OK;
    oit_vertex v[3];
    for (size_t k = 2; k < r->nidx && st == OIT_OK; k++) {
        v[0] = r->tab.v[r->idx[0]];
        v[1] = r->tab.v[r->idx[k - 1]];
        v[2] = r->tab.v[r->idx[k]];
        for (int j = 0; j < 3; j++)
            ply_apply_color(e, vals, v[j].rgba);
        st = oit_rd_emit(&r->c->out, &v[0], &v[1], &v[2]);
    }
    return st;
}

static oit_status ply_element_data(ply_reader *r, const ply_element *e)
{
    snprintf(r->what, sizeof r->what, "element '%s'", e->name);
    oit_status st = ply_check_count(r, e);
    if (st != OIT_OK || e->nprops == 0)
        return st;
    if (e->kind == ELEM_FACE && !r->have_vertices && e->count > 0)
        return ply_fail(r, OIT_ERR_UNSUPPORTED, "element 'face' comes before element 'vertex'");
    double vals[PLY_MAX_PROPS];
    for (uint64_t i = 0; i < e->count && st == OIT_OK; i++) {
        if ((st = ply_item(r, e, vals)) != OIT_OK)
            break;
        if (e->kind == ELEM_VERTEX)
            st = ply_vertex(r, e, vals);
        else if (e->kind == ELEM_FACE)
            st = ply_face(r, e, vals);
    }
    if (e->kind == ELEM_VERTEX)
        r->have_vertices = 1;
    return st;
}

static oit_status ply_parse(ply_reader *r)
{
    oit_status st = ply_header(r);
    if (st == OIT_OK)
        st = ply_assign_roles(r);
    int seen_vertex = 0;
    for (int i = 0; i < r->nel && st == OIT_OK; i++) {
        ply_element *e = &r->el[i];
        if (e->kind == ELEM_VERTEX && seen_vertex++)
            e->kind = ELEM_OTHER; /* only the first vertex element is the table */
        st = ply_element_data(r, e);
    }
    r->c->info->vertices_in = r->tab.count;
    return st;
}

oit_status oit_read_ply_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    oit_rd_ctx c;
    ply_reader *r = calloc(1, sizeof *r); /* ~80 KiB of element tables: not on the stack */
    if (!r)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", name);
    r->c = &c;
    oit_status st = oit_rd_ctx_open(&c, f, name, desc, sink, user, info, err);
    r->file_size = st == OIT_OK ? oit_rd_file_size(c.in.f) : -1; /* -1: gzip */
    if (st == OIT_OK)
        st = oit_rd_skip_bom(&c.in);
    if (st == OIT_OK)
        st = ply_parse(r);
    oit_rd_release(&c.budget, (void **)&r->tab.v, &r->tab.cap, sizeof *r->tab.v);
    oit_rd_release(&c.budget, (void **)&r->idx, &r->capidx, sizeof *r->idx);
    free(r);
    return oit_rd_ctx_close(&c, st);
}
