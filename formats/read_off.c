/* OFF reader (Geomview Object File Format, ASCII).
 *
 * Headers OFF, COFF, NOFF, CNOFF and the ST prefix (texture coordinates,
 * skipped); the counts may follow the keyword on the same line, and a file
 * without a keyword starts directly with the counts. Per vertex:
 * x y z [nx ny nz] [r g b [a]] [s t]; per face: n i1..in [r g b [a]] (a
 * single colour-map index is ignored). Colours are floats in 0..1 when any
 * component is written with a decimal point or exponent, or when all are 0
 * or 1; otherwise integers in 0..255. A face colour overrides its vertices'.
 * '#' starts a comment anywhere; blank lines are skipped. Polygons are
 * fan-triangulated; faces with fewer than three vertices are skipped.
 * Triangles touching a NaN/inf vertex are dropped and counted in
 * info->nonfinite_dropped. Binary OFF and 4D/nD variants are unsupported.
 */
#include "formats/readers_internal.h"

#include <inttypes.h>

typedef struct off_layout {
    int color, normals, st;
} off_layout;

/* Next line with content, comments removed; end of file is an error. */
static oit_status off_next(oit_rd_ctx *c, char **line, uint64_t done, uint64_t total,
                           const char *what)
{
    for (;;) {
        int got;
        oit_status st = oit_rd_line(&c->in, line, &got);
        if (st != OIT_OK)
            return st;
        if (!got)
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT,
                                    "file ends after %" PRIu64 " of %" PRIu64 " %s (truncated)",
                                    done, total, what);
        char *hash = strchr(*line, '#');
        if (hash)
            *hash = '\0';
        char *p = *line;
        if (oit_rd_skip_blanks(&p) != '\0') {
            *line = p;
            return OIT_OK;
        }
    }
}

/* Reads the trailing colour of a vertex or face line into rgba; *has is
 * 0 (none or colour-map index), 3 or 4. skip_tail values at the end belong
 * to something else (texture coordinates). */
static oit_status off_color(oit_rd_ctx *c, char *p, int skip_tail, uint8_t rgba[4], int *has)
{
    double v[8];
    int n = 0, is_float = 0, all_unit = 1;
    while (oit_rd_skip_blanks(&p) != '\0') {
        if (n == 8)
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "too many values on the line");
        char *start = p;
        if (!oit_rd_double(&p, &v[n]))
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "not a number: '%.40s'", start);
        for (const char *q = start; q < p; q++)
            is_float |= strchr(".eEnNiI", *q) != NULL;
        all_unit &= v[n] == 0.0 || v[n] == 1.0;
        n++;
    }
    n -= skip_tail;
    if (n == 2 || n > 4)
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT,
                                "expected 3 or 4 colour components, found %d", n);
    /* 0 or 1 value: a colour-map index, which carries no colour. */
    const int channels = n >= 3 ? n : 0;
    for (int k = 0; k < channels && k < 4; k++)
        rgba[k] = is_float || all_unit ? oit_rd_unit_to_u8(v[k]) : oit_rd_clamp_u8(v[k]);
    *has = channels;
    return OIT_OK;
}

static void off_note_color(oit_rd_ctx *c, int has)
{
    if (has >= 3)
        c->info->attributes |= OIT_ATTR_COLOUR;
    if (has == 4)
        c->info->attributes |= OIT_ATTR_ALPHA;
}

static oit_status off_vertex(oit_rd_ctx *c, const off_layout *lay, oit_rd_vtable *tab,
                             uint64_t i, uint64_t nv)
{
    char *p;
    oit_status st = off_next(c, &p, i, nv, "vertices");
    if (st != OIT_OK)
        return st;
    oit_vertex v;
    memset(v.rgba, 255, sizeof v.rgba);
    float skip;
    double in[3];
    for (int k = 0; k < 3; k++)
        if (!oit_rd_double(&p, &in[k]))
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "vertex %" PRIu64 ": bad coordinate", i);
    oit_rd_position(c, in, v.pos);
    for (int k = 0; lay->normals && k < 3; k++)
        if (!oit_rd_float(&p, &skip))
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "vertex %" PRIu64 ": bad normal", i);
    if (lay->color) {
        int has;
        if ((st = off_color(c, p, lay->st ? 2 : 0, v.rgba, &has)) != OIT_OK)
            return st;
        off_note_color(c, has);
    }
    return oit_rd_vtable_push(tab, &c->budget, &v, c->name, c->err);
}

/* Parses the n indices at *p (checking range), leaving *p after them. */
static oit_status off_indices(oit_rd_ctx *c, char **p, int64_t n, uint64_t nv)
{
    for (int64_t k = 0; k < n; k++) {
        int64_t idx;
        if (!oit_rd_int(p, &idx, NULL))
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT,
                                    "face has fewer indices than its count %" PRId64, n);
        if (idx < 0 || (uint64_t)idx >= nv)
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT,
                                    "vertex index %" PRId64 " out of range (%" PRIu64 " vertices)",
                                    idx, nv);
    }
    return OIT_OK;
}

static oit_status off_face(oit_rd_ctx *c, const oit_rd_vtable *tab, uint64_t i, uint64_t nf)
{
    char *p;
    oit_status st = off_next(c, &p, i, nf, "faces");
    if (st != OIT_OK)
        return st;
    int64_t n;
    if (!oit_rd_int(&p, &n, NULL) || n < 0)
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "face %" PRIu64 ": bad vertex count", i);
    char *first = p;
    if ((st = off_indices(c, &p, n, tab->count)) != OIT_OK)
        return st;
    uint8_t rgba[4] = {255, 255, 255, 255};
    int has;
    if ((st = off_color(c, p, 0, rgba, &has)) != OIT_OK)
        return st;
    off_note_color(c, has);
    c->info->faces_in++;
    /* Second pass over the already validated indices, now that the colour
     * (written after them) is known. */
    int64_t a = 0, b = 0, idx = 0;
    oit_vertex v[3];
    for (int64_t k = 0; k < n && st == OIT_OK; k++) {
        oit_rd_int(&first, &idx, NULL);
        if (k == 0)
            a = idx;
        if (k >= 2) {
            v[0] = tab->v[a], v[1] = tab->v[b], v[2] = tab->v[idx];
            for (int j = 0; j < 3; j++)
                memcpy(v[j].rgba, rgba, (size_t)has);
            st = oit_rd_emit(&c->out, &v[0], &v[1], &v[2]);
        }
        b = idx;
    }
    return st;
}

/* Keyword [ST][C][N]OFF; 0 when the word is not an OFF keyword. */
static int off_keyword(const char *w, size_t n, off_layout *lay, int *unsupported)
{
    memset(lay, 0, sizeof *lay);
    *unsupported = 0;
    if (n >= 2 && w[0] == 'S' && w[1] == 'T')
        lay->st = 1, w += 2, n -= 2;
    if (n >= 1 && w[0] == 'C')
        lay->color = 1, w++, n--;
    if (n >= 1 && w[0] == 'N')
        lay->normals = 1, w++, n--;
    if (n >= 1 && (w[0] == '4' || w[0] == 'n'))
        *unsupported = 1, w++, n--;
    return oit_rd_word_eq(w, n, "OFF");
}

static oit_status off_header(oit_rd_ctx *c, off_layout *lay, uint64_t *nv, uint64_t *nf)
{
    char *p, *w;
    oit_status st = off_next(c, &p, 0, 1, "header lines");
    if (st != OIT_OK)
        return st;
    char *line = p;
    size_t n = oit_rd_word(&p, &w);
    int unsupported;
    if (off_keyword(w, n, lay, &unsupported)) {
        if (unsupported)
            return oit_rd_fail_line(&c->in, OIT_ERR_UNSUPPORTED, "4D/nD OFF is not supported");
        n = oit_rd_word(&p, &w);
        if (oit_rd_word_eq(w, n, "BINARY"))
            return oit_rd_fail_line(&c->in, OIT_ERR_UNSUPPORTED, "binary OFF is not supported");
        p = w;
        if (n == 0 && (st = off_next(c, &p, 0, 1, "count lines")) != OIT_OK)
            return st;
    } else {
        p = line; /* no keyword: the counts come first */
    }
    int64_t v, f;
    if (!oit_rd_int(&p, &v, NULL) || !oit_rd_int(&p, &f, NULL) || v < 0 || f < 0)
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT,
                                "expected 'OFF' and vertex and face counts");
    *nv = (uint64_t)v;
    *nf = (uint64_t)f;
    return OIT_OK;
}

static oit_status off_parse(oit_rd_ctx *c)
{
    off_layout lay;
    uint64_t nv = 0, nf = 0;
    oit_status st = oit_rd_text_begin(&c->in, "OFF");
    if (st == OIT_OK)
        st = off_header(c, &lay, &nv, &nf);
    oit_rd_vtable tab = {0};
    for (uint64_t i = 0; st == OIT_OK && i < nv; i++)
        st = off_vertex(c, &lay, &tab, i, nv);
    c->info->vertices_in = tab.count;
    for (uint64_t i = 0; st == OIT_OK && i < nf; i++)
        st = off_face(c, &tab, i, nf);
    oit_rd_release(&c->budget, (void **)&tab.v, &tab.cap, sizeof *tab.v);
    return st;
}

oit_status oit_read_off_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    return oit_rd_ctx_run(f, name, desc, sink, user, info, err, off_parse);
}
