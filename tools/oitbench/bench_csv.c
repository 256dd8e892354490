/* results.csv written and read (bench_csv.h). */
#include "tools/oitbench/bench_csv.h"

#include <errno.h>
#include <float.h>
#include <stdarg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/args.h"

enum { FIELDS = 20, FIELDS_19 = 19, FIELDS_18 = 18, FIELDS_17 = 17, OLD_FIELDS = 15, LINE_MAX_BYTES = 4096, ROWS_MAX = 1 << 20 };

/* ---- writing ---- */

const char *oit_bench_number(char *buf, size_t cap, double x, const char *fmt,
                             const char *nonfinite)
{
    if (isfinite(x))
        snprintf(buf, cap, fmt, x);
    else
        snprintf(buf, cap, "%s", nonfinite);
    return buf;
}

static void csv_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s == '\n' || *s == '\r' ? ' ' : *s, f);
    }
    fputc('"', f);
}

typedef struct row_figures {
    int ok;
    double med, p95;
    uint64_t gpu;
    uint32_t layers;
    double rmse, max_abs, pct, psnr;
    uint32_t view_layers;
    double gpu_ms; /* < 0: none */
    uint64_t mesh;
    double pct_outside; /* pct outside the reference's ambiguity mask */
} row_figures;

static const char *geometry_token(oit_bench_geometry g)
{
    return g == OIT_BENCH_GEOMETRY_PART_FILE ? "part_file" : "source_mesh";
}

static void csv_row(FILE *f, const char *row, const oit_bench_method *m, int view,
                    const row_figures *x, uint64_t triangles)
{
    const char *method = m->name, *reason = m->reason;
    char b[8][40];
    int ok = x->ok;
    fprintf(f, "%s,%s,", row, method);
    if (view >= 0) fprintf(f, "%d", view);
    fprintf(f, ",%s,%s,%s,", ok ? "ok" : "not_runnable", oit_bench_number(b[0], 40, x->med, "%.4f", ""),
            oit_bench_number(b[1], 40, x->p95, "%.4f", ""));
    if (ok) fprintf(f, "%llu,%u", (unsigned long long)x->gpu, x->layers);
    else fprintf(f, ",");
    fprintf(f, ",%s,%s,%s,%s,", oit_bench_number(b[2], 40, ok ? x->rmse : NAN, "%.9g", ""),
            oit_bench_number(b[3], 40, ok ? x->max_abs : NAN, "%.9g", ""),
            oit_bench_number(b[4], 40, ok ? x->pct : NAN, "%.6f", ""),
            oit_bench_number(b[5], 40, ok ? x->psnr : NAN, "%.4f", ok ? "inf" : ""));
    csv_text(f, ok ? "" : reason);
    fprintf(f, ",%llu,%u,%s,%llu,%s,", (unsigned long long)triangles, x->view_layers,
            geometry_token(m->geometry), (unsigned long long)m->triangles,
            oit_bench_number(b[6], 40, ok && x->gpu_ms >= 0 ? x->gpu_ms : NAN, "%.4f", ""));
    if (ok) fprintf(f, "%llu", (unsigned long long)x->mesh);
    fprintf(f, ",%s\n", oit_bench_number(b[7], 40, ok ? x->pct_outside : NAN, "%.6f", ""));
}

void oit_bench_csv_write(FILE *f, const oit_bench_result *r, uint64_t triangles)
{
    uint32_t deepest = 0;
    fprintf(f, "%s\n", OIT_BENCH_CSV_HEADER);
    for (int v = 0; v < r->views; v++) {
        deepest = r->ref_layers[v] > deepest ? r->ref_layers[v] : deepest;
        for (int i = 0; i < r->method_count; i++) {
            const oit_bench_method *m = &r->methods[i];
            const oit_bench_cell *c = &m->cells[v];
            row_figures x = {c->ok, c->ok ? c->ms_median : NAN, c->ok ? c->ms_p95 : NAN,
                             c->gpu_bytes_peak, c->max_layers, c->diff.rmse, c->diff.max_abs,
                             c->diff.pct_over_1_255, c->diff.psnr, r->ref_layers[v],
                             c->gpu_ms_median, c->gpu_mesh_bytes,
                             c->pct_over_outside_ambiguity};
            csv_row(f, "view", m, v, &x, triangles);
        }
    }
    for (int i = 0; i < r->method_count; i++) {
        const oit_bench_method *m = &r->methods[i];
        row_figures x = {m->runnable, m->ms_median, m->ms_p95, m->gpu_bytes_peak, m->max_layers,
                         m->rmse_mean, m->max_abs_worst, m->pct_over_worst, m->psnr_min, deepest,
                         m->gpu_ms_median, m->gpu_mesh_bytes,
                         m->pct_over_outside_ambiguity_worst};
        csv_row(f, "summary", m, -1, &x, triangles);
    }
}

/* ---- reading ---- */

typedef struct field {
    char *s;
    int quoted;
} field;

typedef struct reader {
    const char *name;
    size_t line;
    oit_error *err;
    int fields; /* FIELDS, or FIELDS_19 ... OLD_FIELDS after an older header */
} reader;

static oit_status bad(const reader *rd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* "NAME: line L: what", OIT_ERR_FORMAT */
static oit_status bad(const reader *rd, const char *fmt, ...)
{
    char what[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return oit_error_set(rd->err, OIT_ERR_FORMAT, "%s: line %zu: %s", rd->name, rd->line, what);
}

/* Reads one line without its end ("\n" or "\r\n") into buf (cap bytes with
 * the NUL); 0 at the end of the file or on a failure (*s says which). */
static int read_line(FILE *f, char *buf, size_t cap, const reader *rd, oit_status *s)
{
    size_t n = 0;
    int c;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (c == 0) {
            *s = bad(rd, "a NUL byte (not a text file)");
            return 0;
        }
        if (n + 1 == cap) {
            *s = bad(rd, "longer than %zu bytes", cap - 1);
            return 0;
        }
        buf[n++] = (char)c;
    }
    if (ferror(f)) {
        *s = oit_error_set(rd->err, OIT_ERR_IO, "%s: read failed at line %zu", rd->name, rd->line);
        return 0;
    }
    if (c == EOF && n == 0)
        return 0;
    if (n > 0 && buf[n - 1] == '\r')
        n--;
    buf[n] = 0;
    return 1;
}

/* A quoted field starting at p (on the quote), unescaped in place; returns
 * the position after it, or NULL when it is malformed. */
static char *unquote(char *p, field *out)
{
    char *w = p, *r = p + 1;
    out->s = p;
    out->quoted = 1;
    for (;;) {
        if (*r == 0)
            return NULL;
        if (*r == '"') {
            if (r[1] != '"')
                break;
            r++;
        }
        *w++ = *r++;
    }
    *w = 0;
    r++;
    return *r == ',' || *r == 0 ? r : NULL;
}

/* Splits line into at most rd->fields fields in place. */
static oit_status split(char *line, field *fs, int *count, const reader *rd)
{
    char *p = line;
    *count = 0;
    for (;;) {
        if (*count == rd->fields)
            return bad(rd, "more than %d fields (the header has %d)", rd->fields, rd->fields);
        field *fd = &fs[(*count)++];
        if (*p == '"') {
            if (!(p = unquote(p, fd)))
                return bad(rd, "field %d: unterminated quoted text, or text after its "
                           "closing quote", *count);
        } else {
            fd->s = p;
            fd->quoted = 0;
            p += strcspn(p, ",\"");
            if (*p == '"')
                return bad(rd, "field %d: a quote inside an unquoted field", *count);
        }
        if (*p == 0)
            return OIT_OK;
        *p++ = 0;
    }
}

static int parse_uint(const char *s, uint64_t max, uint64_t *out)
{
    return oit_parse_u64(s, 0, max, out) == 0;
}

/* A finite number >= 0 as %f / %g write it (a digit first: no ".5", no
 * "-0"); empty gives NAN when allowed. */
static int parse_figure(const char *s, int allow_empty, double *out)
{
    if (!*s) {
        *out = NAN;
        return allow_empty;
    }
    return *s >= '0' && *s <= '9' && oit_parse_double(s, 0.0, DBL_MAX, out) == 0;
}

static int valid_method(const char *s)
{
    size_t n = strlen(s);
    return n > 0 && n < OIT_BENCH_NAME_MAX &&
           strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.@+-") == n;
}

static oit_status row_identity(const field *fs, oit_bench_row *row, const reader *rd)
{
    if (!strcmp(fs[0].s, "view")) row->summary = 0;
    else if (!strcmp(fs[0].s, "summary")) row->summary = 1;
    else return bad(rd, "column row: '%.40s' is neither view nor summary", fs[0].s);
    if (!valid_method(fs[1].s))
        return bad(rd, "column method: '%.40s' is not a method name (1 to %d of "
                   "A-Z a-z 0-9 _ . @ + -)", fs[1].s, OIT_BENCH_NAME_MAX - 1);
    snprintf(row->method, sizeof row->method, "%s", fs[1].s);
    uint64_t v = 0;
    if (row->summary && *fs[2].s)
        return bad(rd, "column view: '%.40s' on a summary row (expected empty)", fs[2].s);
    if (!row->summary && !parse_uint(fs[2].s, 1000000, &v))
        return bad(rd, "column view: '%.40s' is not a view number", fs[2].s);
    row->view = row->summary ? -1 : (int)v;
    if (!strcmp(fs[3].s, "ok")) row->ok = 1;
    else if (!strcmp(fs[3].s, "not_runnable")) row->ok = 0;
    else return bad(rd, "column status: '%.40s' is neither ok nor not_runnable", fs[3].s);
    return OIT_OK;
}

static oit_status row_memory(const field *fs, oit_bench_row *row, const reader *rd)
{
    uint64_t layers = 0;
    row->has_gpu = *fs[6].s || *fs[7].s;
    if (row->has_gpu != row->ok)
        return bad(rd, "columns gpu_bytes_peak, max_layers: %s on a%s row",
                   row->ok ? "missing" : "present", row->ok ? "n ok" : " not_runnable");
    if (row->ok && !parse_uint(fs[6].s, UINT64_MAX, &row->gpu_bytes_peak))
        return bad(rd, "column gpu_bytes_peak: '%.40s' is not a byte count", fs[6].s);
    if (row->ok && !parse_uint(fs[7].s, UINT32_MAX, &layers))
        return bad(rd, "column max_layers: '%.40s' is not a layer count", fs[7].s);
    row->max_layers = (uint32_t)layers;
    return OIT_OK;
}

static oit_status row_figures_read(const field *fs, oit_bench_row *row, const reader *rd)
{
    static const char *const names[] = {"ms_median", "ms_p95", "rmse", "max_abs",
                                        "pct_over_1_255"};
    static const int cols[] = {4, 5, 8, 9, 10};
    double *dst[] = {&row->ms_median, &row->ms_p95, &row->rmse, &row->max_abs,
                     &row->pct_over_1_255};
    for (int i = 0; i < 5; i++) {
        /* a stopped entry's summary keeps the ms of the views it rendered */
        int need = row->ok, allow = i < 2 || !row->ok;
        if (!parse_figure(fs[cols[i]].s, !need, dst[i]) || (!allow && !*fs[cols[i]].s))
            return bad(rd, "column %s: '%.40s' is not a figure >= 0", names[i], fs[cols[i]].s);
        if (!row->ok && i >= 2 && *fs[cols[i]].s)
            return bad(rd, "column %s: '%.40s' on a not_runnable row (expected empty)",
                       names[i], fs[cols[i]].s);
    }
    if (row->ok && !strcmp(fs[11].s, "inf")) row->psnr = INFINITY;
    else if (!parse_figure(fs[11].s, !row->ok, &row->psnr) || (!row->ok && *fs[11].s))
        return bad(rd, "column psnr: '%.40s' is not a PSNR in dB or inf (an ok row) or "
                   "empty (a not_runnable one)", fs[11].s);
    return OIT_OK;
}

static oit_status row_tail(const field *fs, oit_bench_row *row, const reader *rd)
{
    if (!fs[12].quoted)
        return bad(rd, "column reason: '%.40s' is not quoted", fs[12].s);
    if (strlen(fs[12].s) >= sizeof row->reason)
        return bad(rd, "column reason: longer than %zu characters", sizeof row->reason - 1);
    if (row->ok && *fs[12].s)
        return bad(rd, "column reason: '%.40s' on an ok row (expected empty)", fs[12].s);
    snprintf(row->reason, sizeof row->reason, "%s", fs[12].s);
    uint64_t layers = 0;
    if (!parse_uint(fs[13].s, UINT64_MAX, &row->triangles))
        return bad(rd, "column triangles: '%.40s' is not a triangle count", fs[13].s);
    if (!parse_uint(fs[14].s, UINT32_MAX, &layers))
        return bad(rd, "column view_max_layers: '%.40s' is not a layer count", fs[14].s);
    row->view_max_layers = (uint32_t)layers;
    row->geometry = -1;
    row->drawn_triangles = row->triangles;
    return OIT_OK;
}

/* gpu_mesh_bytes: on an ok row, at most its gpu_bytes_peak (which holds
 * it); none on a not_runnable one. */
static oit_status row_mesh(const field *fs, oit_bench_row *row, const reader *rd)
{
    row->mesh_counted = rd->fields >= FIELDS_19;
    if (rd->fields < FIELDS_19)
        return OIT_OK;
    if (!row->ok && *fs[18].s)
        return bad(rd, "column gpu_mesh_bytes: '%.40s' on a not_runnable row (expected empty)",
                   fs[18].s);
    if (row->ok && !parse_uint(fs[18].s, row->gpu_bytes_peak, &row->gpu_mesh_bytes))
        return bad(rd, "column gpu_mesh_bytes: '%.40s' is not a byte count within "
                   "gpu_bytes_peak (%llu)", fs[18].s, (unsigned long long)row->gpu_bytes_peak);
    return OIT_OK;
}

/* pct_over_1_255_outside_ambiguity: a figure on an ok row, empty on a
 * not_runnable one; NAN from a file before the column. */
static oit_status row_ambiguity(const field *fs, oit_bench_row *row, const reader *rd)
{
    row->pct_over_outside_ambiguity = NAN;
    if (rd->fields != FIELDS)
        return OIT_OK;
    if (!row->ok && *fs[19].s)
        return bad(rd, "column pct_over_1_255_outside_ambiguity: '%.40s' on a not_runnable "
                   "row (expected empty)", fs[19].s);
    if (row->ok && (!parse_figure(fs[19].s, 0, &row->pct_over_outside_ambiguity) ||
                    row->pct_over_outside_ambiguity > 100.0))
        return bad(rd, "column pct_over_1_255_outside_ambiguity: '%.40s' is not a "
                   "percentage on an ok row", fs[19].s);
    return OIT_OK;
}

static oit_status row_geometry(const field *fs, oit_bench_row *row, const reader *rd)
{
    row->gpu_ms_median = -1.0;
    if (rd->fields == OLD_FIELDS)
        return OIT_OK;
    if (rd->fields >= FIELDS_18 && *fs[17].s &&
        (!row->ok || !parse_figure(fs[17].s, 0, &row->gpu_ms_median)))
        return bad(rd, "column gpu_ms_median: '%.40s' is not a figure >= 0 on an ok row",
                   fs[17].s);
    if (!strcmp(fs[15].s, "source_mesh")) row->geometry = OIT_BENCH_GEOMETRY_SOURCE_MESH;
    else if (!strcmp(fs[15].s, "part_file")) row->geometry = OIT_BENCH_GEOMETRY_PART_FILE;
    else return bad(rd, "column geometry: '%.40s' is neither source_mesh nor part_file",
                    fs[15].s);
    if (!parse_uint(fs[16].s, UINT64_MAX, &row->drawn_triangles))
        return bad(rd, "column drawn_triangles: '%.40s' is not a triangle count", fs[16].s);
    return OIT_OK;
}

static oit_status parse_row(char *line, oit_bench_row *row, const reader *rd)
{
    field fs[FIELDS];
    int n;
    memset(row, 0, sizeof *row);
    oit_status s = split(line, fs, &n, rd);
    if (s != OIT_OK)
        return s;
    if (n != rd->fields)
        return bad(rd, "%d fields, expected %d (%s)", n, rd->fields,
                   rd->fields == FIELDS      ? OIT_BENCH_CSV_HEADER
                   : rd->fields == FIELDS_19 ? OIT_BENCH_CSV_HEADER_19
                   : rd->fields == FIELDS_18 ? OIT_BENCH_CSV_HEADER_18
                   : rd->fields == FIELDS_17 ? OIT_BENCH_CSV_HEADER_17
                                             : OIT_BENCH_CSV_HEADER_15);
    for (int i = 0; i < n; i++)
        if (i != 12 && fs[i].quoted)
            return bad(rd, "field %d is quoted; only reason (field 13) is", i + 1);
    if ((s = row_identity(fs, row, rd)) == OIT_OK && (s = row_memory(fs, row, rd)) == OIT_OK &&
        (s = row_figures_read(fs, row, rd)) == OIT_OK && (s = row_tail(fs, row, rd)) == OIT_OK)
        s = row_geometry(fs, row, rd);
    if (s == OIT_OK)
        s = row_mesh(fs, row, rd);
    if (s == OIT_OK)
        s = row_ambiguity(fs, row, rd);
    return s;
}

static oit_status append(oit_bench_table *t, size_t *cap, const oit_bench_row *row,
                         const reader *rd)
{
    if (t->count == ROWS_MAX)
        return bad(rd, "more than %d rows", ROWS_MAX);
    if (t->count == *cap) {
        size_t nc = *cap ? *cap * 2 : 32;
        oit_bench_row *nr = realloc(t->rows, nc * sizeof *nr);
        if (!nr)
            return oit_error_set(rd->err, OIT_ERR_NOMEM, "%s: cannot hold %zu rows", rd->name, nc);
        t->rows = nr;
        *cap = nc;
    }
    t->rows[t->count++] = *row;
    return OIT_OK;
}

static oit_status check_header(FILE *f, char *buf, size_t cap, reader *rd)
{
    oit_status s = OIT_OK;
    rd->line = 1;
    if (!read_line(f, buf, cap, rd, &s))
        return s != OIT_OK ? s : bad(rd, "empty file, expected the header '%s'",
                                     OIT_BENCH_CSV_HEADER);
    rd->fields = !strcmp(buf, OIT_BENCH_CSV_HEADER)      ? FIELDS
                 : !strcmp(buf, OIT_BENCH_CSV_HEADER_19) ? FIELDS_19
                 : !strcmp(buf, OIT_BENCH_CSV_HEADER_18) ? FIELDS_18
                 : !strcmp(buf, OIT_BENCH_CSV_HEADER_17) ? FIELDS_17
                 : !strcmp(buf, OIT_BENCH_CSV_HEADER_15) ? OLD_FIELDS
                                                         : 0;
    if (!rd->fields)
        return bad(rd, "not the header of this oitbench's results.csv (written by an older "
                   "oitbench? run it again); expected '%s'", OIT_BENCH_CSV_HEADER);
    return OIT_OK;
}

static oit_status read_rows(FILE *f, oit_bench_table *t, char *buf, reader *rd)
{
    size_t cap = 0;
    oit_status s = OIT_OK;
    oit_bench_row row;
    for (rd->line = 2; s == OIT_OK && read_line(f, buf, LINE_MAX_BYTES, rd, &s); rd->line++) {
        if (strlen(buf) == 0)
            s = bad(rd, "empty line");
        else if ((s = parse_row(buf, &row, rd)) == OIT_OK && t->count > 0 &&
                 row.triangles != t->rows[0].triangles)
            s = bad(rd, "column triangles: %llu differs from the first row's %llu (one model "
                    "a file)", (unsigned long long)row.triangles,
                    (unsigned long long)t->rows[0].triangles);
        if (s == OIT_OK)
            s = append(t, &cap, &row, rd);
    }
    if (s == OIT_OK && t->count == 0)
        s = bad(rd, "no rows after the header");
    return s;
}

oit_status oit_bench_csv_read(FILE *f, const char *name, oit_bench_table *t, oit_error *err)
{
    memset(t, 0, sizeof *t);
    char *buf = malloc(LINE_MAX_BYTES);
    if (!buf)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate a line buffer", name);
    reader rd = {name, 0, err, FIELDS};
    oit_status s = check_header(f, buf, LINE_MAX_BYTES, &rd);
    if (s == OIT_OK)
        s = read_rows(f, t, buf, &rd);
    free(buf);
    if (s != OIT_OK)
        oit_bench_table_free(t);
    return s;
}

oit_status oit_bench_csv_load(const char *path, oit_bench_table *t, oit_error *err)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "rb");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    oit_status s = oit_bench_csv_read(f, path, t, err);
    fclose(f);
    return s;
}

void oit_bench_table_free(oit_bench_table *t)
{
    free(t->rows);
    memset(t, 0, sizeof *t);
}
