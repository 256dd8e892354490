/* Wavefront OBJ reader.
 *
 * Reads `v x y z [r g b]` (an optional vertex colour in 0..1) and
 * `f` with v, v/vt, v//vn and v/vt/vn references, 1-based or negative
 * (relative to the vertices read so far); polygons are fan-triangulated and
 * faces with fewer than three vertices skipped. A reference to a vertex not
 * yet defined is an error. vt, vn, g, o, s, l, p and other statements are
 * accepted and ignored; '#' starts a comment and a line ending in '\'
 * continues on the next.
 *
 * Materials: `mtllib` files are read from the OBJ's folder; `usemtl` selects
 * Kd as the face colour (unless the file has vertex colours, which win) and
 * d, or else Tr as 1 - d, as its alpha. A material library that cannot be
 * opened is skipped with a warning on stderr naming the OBJ's line (the
 * faces then carry no material colour), and so is the first usemtl of a
 * material no library defined; a malformed library (a missing, malformed
 * or non-finite number, Kd with two numbers, Kd/d/Tr before any newmtl) is
 * an error naming it and its line. Kd, d and Tr outside 0..1 are clamped,
 * the first such value of a library reported on stderr. Texture maps
 * (map_Kd, map_d, ...) are not rendered: the first one met is reported
 * once on stderr. A face of a
 * material with d or Tr carries that alpha, one of a material without
 * (or of no material) alpha 1, MTL's default: with alpha in the file,
 * those are opaque (view/render/image/shade.h, "Opaque triangles").
 *
 * Triangles touching a NaN/inf vertex are dropped and counted in
 * info->nonfinite_dropped.
 */
#include "formats/readers_internal.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>

#define OBJ_MAX_NAME 1024
#define NO_MATERIAL SIZE_MAX

typedef struct obj_material {
    char *name;
    uint8_t rgba[4];
    int has_kd, has_d, has_alpha;
} obj_material;

typedef struct obj_reader {
    oit_rd_ctx *c;
    const char *mtl_dir;
    FILE *mtl_file;       /* oit_read_obj_stream_mtl: every mtllib reads it */
    const char *mtl_name;
    oit_rd_vtable tab;
    int vertex_colors;
    obj_material *mats;
    size_t nmat, capmat;
    size_t cur; /* the usemtl material, an index into mats (which a later
                   mtllib may move), or NO_MATERIAL */
    int map_said;     /* a texture map was reported (once per OBJ)       */
    int range_said;   /* a value outside 0..1 (once per library read)    */
    int unknown_said; /* a usemtl of no known material (once per OBJ)    */
} obj_reader;

/* The rest of a statement (a name), trimmed of blanks on both sides. */
static char *obj_rest(char *p)
{
    oit_rd_skip_blanks(&p);
    size_t n = strlen(p);
    while (n > 0 && (p[n - 1] == ' ' || p[n - 1] == '\t'))
        p[--n] = '\0';
    return p;
}

static void obj_strip_comment(char *line)
{
    char *hash = strchr(line, '#');
    if (hash)
        *hash = '\0';
}

/* ---- material libraries ----------------------------------------------- */

static oit_status mtl_new(obj_reader *r, oit_rd_stream *in, char *name)
{
    if (strlen(name) > OBJ_MAX_NAME)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "material name longer than %d bytes",
                                OBJ_MAX_NAME);
    oit_status st = oit_rd_grow(&r->c->budget, (void **)&r->mats, &r->capmat, sizeof *r->mats,
                                r->nmat + 1, in->name, "material table", in->err);
    if (st != OIT_OK)
        return st;
    obj_material *m = &r->mats[r->nmat];
    memset(m, 0, sizeof *m);
    memset(m->rgba, 255, sizeof m->rgba);
    if (!(m->name = strdup(name)))
        return oit_error_set(in->err, OIT_ERR_NOMEM, "%s: out of memory", in->name);
    r->nmat++;
    return OIT_OK;
}

/* The next number of statement w: a missing, malformed or non-finite one is
 * an error naming the statement and what stood there. */
static oit_status mtl_number(oit_rd_stream *in, const char *w, size_t n, char **p, double *v)
{
    char *at = *p, *tok;
    if (oit_rd_double(p, v) && isfinite(*v))
        return OIT_OK;
    size_t len = oit_rd_word(&at, &tok);
    if (len == 0)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "'%.*s' needs a number", (int)n, w);
    return oit_rd_fail_line(in, OIT_ERR_FORMAT, "'%.*s': '%.*s' is not a finite number", (int)n,
                            w, (int)(len < 40 ? len : 40), tok);
}

/* Kd, d and Tr are fractions; a value outside 0..1 is drawn clamped, as
 * viewers do, and the first one of a library read is reported. */
static void mtl_range(obj_reader *r, oit_rd_stream *in, const char *w, size_t n, double v)
{
    if ((v >= 0.0 && v <= 1.0) || r->range_said)
        return;
    r->range_said = 1;
    fprintf(stderr,
            "%s: line %" PRIu64 ": %.*s %g is outside 0..1; drawn as %g (further values out of "
            "range in this library are clamped without a word)\n",
            in->name, in->tok_line, (int)n, w, v, v < 0.0 ? 0.0 : 1.0);
}

static oit_status mtl_statement(obj_reader *r, oit_rd_stream *in, char *p)
{
    char *w;
    size_t n = oit_rd_word(&p, &w);
    if (oit_rd_word_eq(w, n, "newmtl"))
        return mtl_new(r, in, obj_rest(p));
    int kd = oit_rd_word_eq(w, n, "Kd"), d = oit_rd_word_eq(w, n, "d"),
        tr = oit_rd_word_eq(w, n, "Tr");
    if (!kd && !d && !tr) {
        if (n > 4 && strncmp(w, "map_", 4) == 0 && !r->map_said) {
            r->map_said = 1; /* once per file: texture maps are out of scope */
            fprintf(stderr, "%s: %.*s textures are not supported; using Kd\n", in->name, (int)n,
                    w);
        }
        return OIT_OK; /* Ka, Ks, Ns, illum, other maps...: nothing we render */
    }
    if (r->nmat == 0)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "'%.*s' before any 'newmtl'", (int)n, w);
    obj_material *m = &r->mats[r->nmat - 1];
    if (d) { /* "d -halo f": the MTL specification's dissolve option */
        char *q = p, *opt;
        size_t k = oit_rd_word(&q, &opt);
        if (oit_rd_word_eq(opt, k, "-halo"))
            p = q;
    }
    double v[3];
    int got = 0;
    oit_status st = OIT_OK;
    /* Kd takes three numbers, or one for grey (MTL specification); d and
     * Tr one. What follows them is ignored. */
    while (st == OIT_OK && got < (kd ? 3 : 1) && (got == 0 || oit_rd_skip_blanks(&p) != '\0'))
        if ((st = mtl_number(in, w, n, &p, &v[got])) == OIT_OK)
            got++;
    if (st != OIT_OK)
        return st;
    if (got == 2)
        return oit_rd_fail_line(in, OIT_ERR_FORMAT, "'Kd' needs one or three numbers, not two");
    for (int k = 0; k < got; k++)
        mtl_range(r, in, w, n, v[k]);
    if (kd) {
        if (got == 1)
            v[1] = v[2] = v[0];
        for (int k = 0; k < 3; k++)
            m->rgba[k] = oit_rd_unit_to_u8(v[k]);
        m->has_kd = 1;
    } else if (d || !m->has_d) { /* d wins over Tr, whose sense exporters disagree on */
        m->rgba[3] = oit_rd_unit_to_u8(d ? v[0] : 1.0 - v[0]);
        m->has_alpha = 1;
        m->has_d |= d;
    }
    return OIT_OK;
}

static oit_status mtl_read(obj_reader *r, FILE *f, const char *path)
{
    oit_rd_stream in;
    r->range_said = 0;
    oit_status st = oit_rd_open(&in, f, path, &r->c->budget, r->c->err);
    while (st == OIT_OK) {
        char *line;
        int got;
        if ((st = oit_rd_line(&in, &line, &got)) != OIT_OK || !got)
            break;
        obj_strip_comment(line);
        st = mtl_statement(r, &in, line);
    }
    oit_rd_close(&in);
    return st;
}

/* Opens dir + name; 1 when read (or failed: see *st), 0 when it cannot be
 * opened (errno says why). */
static int mtl_try(obj_reader *r, const char *name, oit_status *st)
{
    if (r->mtl_file) { /* a library in memory (fuzzing), read from its start */
        rewind(r->mtl_file);
        *st = mtl_read(r, r->mtl_file, r->mtl_name);
        return 1;
    }
    char path[4096];
    if (snprintf(path, sizeof path, "%s%s", r->mtl_dir, name) >= (int)sizeof path) {
        errno = ENAMETOOLONG;
        return 0;
    }
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    *st = mtl_read(r, f, path);
    fclose(f);
    return 1;
}

static oit_status obj_mtllib(obj_reader *r, char *p)
{
    oit_status st = OIT_OK;
    char *names = obj_rest(p);
    if ((!r->mtl_dir && !r->mtl_file) || mtl_try(r, names, &st))
        return st; /* one library, possibly with blanks in its name */
    char *w;
    size_t n;
    while ((n = oit_rd_word(&names, &w)) > 0 && st == OIT_OK) {
        char save = w[n];
        w[n] = '\0';
        if (!mtl_try(r, w, &st)) /* not fatal: its materials are then unknown */
            fprintf(stderr, "%s: line %" PRIu64 ": material library %s%s: %s; its materials "
                            "are drawn in the default colour\n",
                    r->c->name, r->c->in.tok_line, r->mtl_dir, w, strerror(errno));
        w[n] = save;
    }
    return st;
}

static void obj_usemtl(obj_reader *r, char *p)
{
    const char *name = obj_rest(p);
    r->cur = NO_MATERIAL;
    for (size_t i = r->nmat; i-- > 0;) /* the last definition wins */
        if (strcmp(r->mats[i].name, name) == 0) {
            r->cur = i;
            return;
        }
    /* Libraries skipped by design (read from memory) or "usemtl" alone
     * (no material) are no news; one report an OBJ is enough. */
    if ((r->mtl_dir || r->mtl_file) && name[0] && !r->unknown_said) {
        r->unknown_said = 1;
        fprintf(stderr, "%s: line %" PRIu64 ": usemtl %.200s: no such material in the material "
                        "libraries read; drawn in the default colour (further unknown "
                        "materials are not reported)\n",
                r->c->name, r->c->in.tok_line, name);
    }
}

/* ---- geometry --------------------------------------------------------- */

static oit_status obj_vertex(obj_reader *r, char *p)
{
    oit_vertex v;
    memset(v.rgba, 255, sizeof v.rgba);
    double in[3];
    for (int k = 0; k < 3; k++)
        if (!oit_rd_double(&p, &in[k]))
            return oit_rd_fail_line(&r->c->in, OIT_ERR_FORMAT, "bad vertex coordinate: '%.40s'", p);
    oit_rd_position(r->c, in, v.pos);
    double extra[3];
    int n = 0;
    while (n < 3 && oit_rd_double(&p, &extra[n]))
        n++;
    if (n == 3) {
        for (int k = 0; k < 3; k++)
            v.rgba[k] = oit_rd_unit_to_u8(extra[k]);
        r->vertex_colors = 1;
        r->c->info->attributes |= OIT_ATTR_COLOUR;
    }
    return oit_rd_vtable_push(&r->tab, &r->c->budget, &v, r->c->name, r->c->err);
}

/* Resolves one face reference ("7", "-1", "7/2", "7//3", "7/2/3"). */
static oit_status obj_ref(obj_reader *r, char **p, oit_vertex *out)
{
    char *start = *p;
    int64_t i;
    if (!oit_rd_int(p, &i, "/"))
        return oit_rd_fail_line(&r->c->in, OIT_ERR_FORMAT, "bad vertex reference '%.40s'", start);
    while (**p && **p != ' ' && **p != '\t' && **p != '\r')
        (*p)++; /* texture and normal references: unused */
    int64_t n = (int64_t)r->tab.count;
    int64_t k = i > 0 ? i - 1 : n + i;
    if (i == 0 || k < 0 || k >= n)
        return oit_rd_fail_line(&r->c->in, OIT_ERR_FORMAT,
                                "vertex index %" PRId64 " out of range (%" PRId64 " vertices so far)",
                                i, n);
    *out = r->tab.v[k];
    const obj_material *m = r->cur == NO_MATERIAL ? NULL : &r->mats[r->cur];
    if (m && m->has_kd && !r->vertex_colors)
        memcpy(out->rgba, m->rgba, 3);
    if (m && m->has_alpha)
        out->rgba[3] = m->rgba[3];
    return OIT_OK;
}

static oit_status obj_face(obj_reader *r, char *p)
{
    oit_vertex first, prev, v;
    uint64_t count = 0;
    oit_status st = OIT_OK;
    while (st == OIT_OK && oit_rd_skip_blanks(&p) != '\0') {
        if ((st = obj_ref(r, &p, &v)) != OIT_OK)
            break;
        if (count == 0)
            first = v;
        else if (count >= 2)
            st = oit_rd_emit(&r->c->out, &first, &prev, &v);
        prev = v;
        count++;
    }
    r->c->info->faces_in++;
    if (r->cur != NO_MATERIAL && count >= 3)
        r->c->info->attributes |= (r->mats[r->cur].has_kd ? OIT_ATTR_COLOUR : 0) |
                                  (r->mats[r->cur].has_alpha ? OIT_ATTR_ALPHA : 0);
    return st;
}

static oit_status obj_statement(obj_reader *r, char *p)
{
    char *w;
    size_t n = oit_rd_word(&p, &w);
    if (n == 1 && w[0] == 'v')
        return obj_vertex(r, p);
    if (n == 1 && w[0] == 'f')
        return obj_face(r, p);
    if (oit_rd_word_eq(w, n, "usemtl"))
        obj_usemtl(r, p);
    else if (oit_rd_word_eq(w, n, "mtllib"))
        return obj_mtllib(r, p);
    return OIT_OK; /* vt, vn, g, o, s, l, p, curves...: not rendered */
}

static oit_status obj_parse(obj_reader *r)
{
    oit_rd_ctx *c = r->c;
    c->in.continuation = 1;
    oit_status st = oit_rd_text_begin(&c->in, "OBJ");
    while (st == OIT_OK) {
        char *line;
        int got;
        if ((st = oit_rd_line(&c->in, &line, &got)) != OIT_OK || !got)
            break;
        obj_strip_comment(line);
        st = obj_statement(r, line);
    }
    c->info->vertices_in = r->tab.count;
    return st;
}

static oit_status obj_read(obj_reader r, FILE *f, const char *name, const oit_read_desc *desc,
                           oit_triangle_sink sink, void *user, oit_mesh_info *info,
                           oit_error *err)
{
    oit_rd_ctx c;
    r.c = &c;
    oit_status st = oit_rd_ctx_open(&c, f, name, desc, sink, user, info, err);
    if (st == OIT_OK)
        st = obj_parse(&r);
    for (size_t i = 0; i < r.nmat; i++)
        free(r.mats[i].name);
    oit_rd_release(&c.budget, (void **)&r.mats, &r.capmat, sizeof *r.mats);
    oit_rd_release(&c.budget, (void **)&r.tab.v, &r.tab.cap, sizeof *r.tab.v);
    return oit_rd_ctx_close(&c, st);
}

oit_status oit_read_obj_stream(FILE *f, const char *name, const char *mtl_dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    return obj_read((obj_reader){.mtl_dir = mtl_dir, .cur = NO_MATERIAL}, f, name, desc, sink, user, info, err);
}

oit_status oit_read_obj_stream_mtl(FILE *f, const char *name, FILE *mtl, const char *mtl_name,
                                   const oit_read_desc *desc, oit_triangle_sink sink,
                                   void *user, oit_mesh_info *info, oit_error *err)
{
    return obj_read((obj_reader){.mtl_file = mtl, .mtl_name = mtl_name, .cur = NO_MATERIAL}, f, name, desc, sink,
                    user, info, err);
}
