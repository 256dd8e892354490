/* STL reader, binary and ASCII.
 *
 * Binary or ASCII is decided by size arithmetic: a file of exactly
 * 84 + 50 * n bytes, n being the count at offset 80, is binary whatever its
 * first bytes say (many binary exporters write "solid" into the header, so the
 * word decides nothing on its own). Otherwise a file starting with "solid" is
 * ASCII, and anything else is a binary file of the wrong size: refused, naming
 * both sizes. STL carries no usable colour, so attributes stay 0.
 *
 * Triangles with a NaN/inf coordinate are dropped and counted in
 * info->nonfinite_dropped. ASCII loops with more than three vertices are
 * fan-triangulated; loops with fewer are skipped.
 */
#include "formats/readers_internal.h"

#include <inttypes.h>

#define STL_HEADER 84u
#define STL_RECORD 50u

static oit_status stl_binary(oit_rd_ctx *c, uint32_t n)
{
    const unsigned char *b;
    oit_status st = oit_rd_bytes(&c->in, STL_HEADER, "header", &b);
    oit_vertex v[3];
    memset(v, 255, sizeof v);
    for (uint32_t i = 0; st == OIT_OK && i < n; i++) {
        if ((st = oit_rd_bytes(&c->in, STL_RECORD, "triangle record", &b)) != OIT_OK)
            break;
        for (int j = 0; j < 3; j++) { /* skip the 12-byte facet normal */
            double in[3];
            for (int k = 0; k < 3; k++)
                in[k] = oit_rd_f32(b + 12 + 12 * j + 4 * k, 0);
            oit_rd_position(c, in, v[j].pos);
        }
        c->info->faces_in++;
        c->info->vertices_in += 3;
        st = oit_rd_emit(&c->out, &v[0], &v[1], &v[2]);
    }
    return st;
}

/* One ASCII loop in progress: fan-triangulated as its vertices arrive. */
typedef struct stl_loop {
    int open;
    uint64_t count;
    oit_vertex first, prev;
} stl_loop;

static oit_status stl_vertex(oit_rd_ctx *c, stl_loop *loop, char *p)
{
    oit_vertex v;
    memset(v.rgba, 255, sizeof v.rgba);
    if (!loop->open)
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "'vertex' outside 'outer loop'");
    double in[3];
    for (int k = 0; k < 3; k++)
        if (!oit_rd_double(&p, &in[k]))
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "expected three numbers after 'vertex'");
    oit_rd_position(c, in, v.pos);
    if (oit_rd_skip_blanks(&p) != '\0')
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "unexpected text after vertex: '%.40s'", p);
    c->info->vertices_in++;
    oit_status st = OIT_OK;
    if (loop->count == 0)
        loop->first = v;
    else if (loop->count >= 2)
        st = oit_rd_emit(&c->out, &loop->first, &loop->prev, &v);
    loop->prev = v;
    loop->count++;
    return st;
}

static oit_status stl_ascii_line(oit_rd_ctx *c, stl_loop *loop, char *p)
{
    char *w;
    size_t n = oit_rd_word(&p, &w);
    if (n == 0 || oit_rd_word_eq_nocase(w, n, "solid") || oit_rd_word_eq_nocase(w, n, "endsolid") ||
        oit_rd_word_eq_nocase(w, n, "facet") || oit_rd_word_eq_nocase(w, n, "endfacet"))
        return OIT_OK; /* names and facet normals carry nothing we use */
    if (oit_rd_word_eq_nocase(w, n, "vertex"))
        return stl_vertex(c, loop, p);
    if (oit_rd_word_eq_nocase(w, n, "outer")) {
        if (loop->open)
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "'outer loop' inside a loop");
        loop->open = 1;
        loop->count = 0;
        return OIT_OK;
    }
    if (oit_rd_word_eq_nocase(w, n, "endloop")) {
        if (!loop->open)
            return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "'endloop' without 'outer loop'");
        loop->open = 0;
        c->info->faces_in++;
        return OIT_OK;
    }
    return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "unexpected '%.*s' in ASCII STL",
                            (int)(n < 40 ? n : 40), w);
}

static oit_status stl_ascii(oit_rd_ctx *c)
{
    stl_loop loop = {0};
    for (;;) {
        char *line;
        int got;
        oit_status st = oit_rd_line(&c->in, &line, &got);
        if (st != OIT_OK)
            return st;
        if (!got)
            break;
        if ((st = stl_ascii_line(c, &loop, line)) != OIT_OK)
            return st;
    }
    if (loop.open)
        return oit_rd_fail_line(&c->in, OIT_ERR_FORMAT, "file ends inside a loop (truncated)");
    return OIT_OK;
}

/* A header of printable text, as an ASCII file's first block is: with the
 * size unknown (gzip input) it tells "solid" text from a binary header that
 * happens to start with the word. */
static int stl_is_text(const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (b[i] < 0x20 && b[i] != '\t' && b[i] != '\n' && b[i] != '\r')
            return 0;
    return 1;
}

static int stl_starts_with_solid(const unsigned char *b, size_t n)
{
    size_t i = 0;
    if (n >= 3 && b[0] == 0xef && b[1] == 0xbb && b[2] == 0xbf)
        i = 3; /* a UTF-8 byte-order mark before "solid" */
    while (i < n && (b[i] == ' ' || b[i] == '\t' || b[i] == '\r' || b[i] == '\n'))
        i++;
    return n - i >= 5 && oit_rd_word_eq_nocase((const char *)b + i, 5, "solid");
}

static oit_status stl_parse(oit_rd_ctx *c)
{
    int64_t size = oit_rd_file_size(c->in.f); /* -1: gzip */
    const unsigned char *b;
    size_t avail;
    oit_status st = oit_rd_peek(&c->in, STL_HEADER + STL_RECORD, &b, &avail);
    if (st != OIT_OK)
        return st;
    int solid = stl_starts_with_solid(b, avail);
    if (avail >= STL_HEADER) {
        uint32_t n = oit_rd_u32(b + 80, 0);
        uint64_t want = STL_HEADER + (uint64_t)STL_RECORD * n;
        if (size < 0 ? !solid || !stl_is_text(b, avail) : (uint64_t)size == want)
            return stl_binary(c, n);
        if (!solid)
            return oit_rd_fail_offset(&c->in, 80, OIT_ERR_FORMAT,
                                      "binary STL declares %" PRIu32 " triangles (%" PRIu64
                                      " bytes) but the file has %" PRId64 " bytes",
                                      n, want, size);
    } else if (!solid) {
        return oit_rd_fail_offset(&c->in, avail, OIT_ERR_FORMAT,
                                  "file too short for binary STL and not ASCII (no 'solid')");
    }
    if ((st = oit_rd_skip_bom(&c->in)) != OIT_OK)
        return st;
    return stl_ascii(c);
}

oit_status oit_read_stl_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    return oit_rd_ctx_run(f, name, desc, sink, user, info, err, stl_parse);
}
