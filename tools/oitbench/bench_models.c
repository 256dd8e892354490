/* The source mesh and the part file of one oitbench run (bench_models.h). */
#include "tools/oitbench/bench_models.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "tools/oitbench/bench_match.h"
#include "partfile/triangles.h"

int oit_bench_is_part_file(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && !strcasecmp(path + n - 5, ".oitp");
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static void add_note(oit_bench_models *m, FILE *progress, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A note goes into the outputs and, at once, to the progress stream. */
static void add_note(oit_bench_models *m, FILE *progress, const char *fmt, ...)
{
    if (m->note_count == OIT_BENCH_NOTES_MAX)
        return;
    char *line = m->notes[m->note_count++];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof m->notes[0], fmt, ap);
    va_end(ap);
    if (progress)
        fprintf(progress, "oitbench: %s\n", line);
}

oit_status oit_bench_temp_part_file(char *path, size_t cap, oit_error *err)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    if ((size_t)snprintf(path, cap, "%s/oitbench-parts-XXXXXX", dir) >= cap)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "TMPDIR '%s' is too long", dir);
    int fd = mkstemp(path);
    if (fd < 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create a temporary part file: %s",
                             path, strerror(errno));
    close(fd);
    return OIT_OK;
}

/* mesh_path's mesh against the open part file: a hard difference is an error
 * (fatal) or, for a mesh only found beside the file, *usable = 0. */
static oit_status check_pair(oit_bench_models *m, const oit_bench_models_desc *d,
                             const char *mesh_path, int fatal, int *usable, oit_error *err)
{
    char why[512];
    const char *recorded = oit_partfile_source_name(m->pf);
    oit_status s = oit_bench_match(&m->source, m->pf, why, sizeof why, err);
    if (s != OIT_OK)
        return s;
    *usable = !why[0];
    if (why[0] && fatal)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s was not made from %s: %s (refusing to "
                             "compare different models)", m->parts_path, mesh_path, why);
    if (why[0])
        add_note(m, d->progress, "%s lies beside %s but is not its source (%s): the in-core "
                 "methods draw the part file's clipped triangles", mesh_path, m->parts_path, why);
    else if (strcmp(recorded, base_name(mesh_path)))
        add_note(m, d->progress, "%s records its source as '%s', not '%s'; triangle count, "
                 "origin, bounds and surface agree, so it is taken as the same model", m->parts_path,
                 recorded, base_name(mesh_path));
    return OIT_OK;
}

static oit_status open_parts(oit_bench_models *m, const char *path, int defer, oit_error *err)
{
    oit_partfile_open_desc od = {defer};
    snprintf(m->parts_path, sizeof m->parts_path, "%s", path);
    oit_status s = oit_partfile_open(path, &od, &m->pf, err);
    if (s == OIT_OK) {
        oit_partfile_summary sum;
        oit_partfile_get_summary(m->pf, &sum);
        m->part_triangles = sum.triangles;
    }
    return s;
}

static oit_status load_source(oit_bench_models *m, const char *path, oit_error *err)
{
    oit_status s = oit_mesh_load(path, NULL, &m->source, err);
    if (s != OIT_OK)
        return s;
    m->have_source = 1;
    snprintf(m->source_path, sizeof m->source_path, "%s", path);
    m->source_triangles = m->source.info.triangles + m->source.info.nonfinite_dropped;
    return OIT_OK;
}

static void drop_source(oit_bench_models *m)
{
    oit_mesh_free(&m->source);
    m->have_source = 0;
    m->source_path[0] = 0;
}

/* The conversion into d->convert.output, then that file opened (a temporary
 * one is removed at close, or at once when this fails). */
static oit_status convert_now(oit_bench_models *m, const oit_bench_models_desc *d,
                              oit_error *err)
{
    oit_convert_options o = d->convert;
    oit_convert_stats st;
    o.input = d->model;
    if (d->progress)
        fprintf(d->progress, "oitbench: converting %s (scheme %s) into %s%s\n", d->model,
                oit_scheme_name(o.scheme), d->output_is_temp ? "the temporary " : "",
                o.output);
    oit_status s = oit_convert(&o, &st, err);
    if (s == OIT_OK) {
        m->conv = (oit_bench_conversion){1, !d->output_is_temp, oit_scheme_name(o.scheme),
                                         o.scheme == OIT_SCHEME_FAST
                                             ? (o.part_triangles ? o.part_triangles
                                                                 : OIT_FAST_PART_TRIANGLES) : 0,
                                         st.seconds_total, st.triangles_in, st.triangles_out,
                                         st.parts};
        if (d->progress)
            fprintf(d->progress, "oitbench: converted %s: %llu triangles in, %llu out, %llu "
                    "parts, %.2f s\n", d->model, (unsigned long long)st.triangles_in,
                    (unsigned long long)st.triangles_out, (unsigned long long)st.parts,
                    st.seconds_total);
        s = open_parts(m, o.output, 1, err);
    }
    if (d->output_is_temp && s != OIT_OK)
        unlink(o.output);
    else if (d->output_is_temp)
        snprintf(m->temp_path, sizeof m->temp_path, "%s", o.output);
    return s;
}

/* MODEL is a mesh: the in-core methods draw it; the stream's part file. */
static oit_status open_mesh_model(oit_bench_models *m, const oit_bench_models_desc *d,
                                  oit_error *err)
{
    int usable;
    oit_status s = load_source(m, d->model, err);
    if (s != OIT_OK || !d->need_parts)
        return s;
    if (!d->parts)
        return convert_now(m, d, err);
    s = open_parts(m, d->parts, 1, err);
    return s == OIT_OK ? check_pair(m, d, d->model, 1, &usable, err) : s;
}

/* The source recorded in META, beside the part file. */
static void beside(const char *parts, const char *source, char *out, size_t cap)
{
    const char *slash = strrchr(parts, '/');
    if (slash)
        snprintf(out, cap, "%.*s/%s", (int)(slash - parts), parts, source);
    else
        snprintf(out, cap, "%s", source);
}

/* A source found beside the part file is a guess, not the user's word: one
 * that cannot be read or does not match is noted and not used. */
static oit_status found_beside(oit_bench_models *m, const oit_bench_models_desc *d,
                               const char *path, oit_error *err)
{
    int usable = 0;
    oit_error why = {0};
    if (load_source(m, path, &why) != OIT_OK) {
        add_note(m, d->progress, "the source beside %s cannot be read (%s): the in-core "
                 "methods draw the part file's clipped triangles", m->parts_path, why.message);
        return OIT_OK;
    }
    oit_status s = check_pair(m, d, path, 0, &usable, err);
    if (s == OIT_OK && !usable)
        drop_source(m);
    return s;
}

/* MODEL is a part file: the in-core methods draw its source when there is
 * one that matches, else its own triangles. */
static oit_status open_part_model(oit_bench_models *m, const oit_bench_models_desc *d,
                                  oit_error *err)
{
    char path[OIT_BENCH_PATH_MAX];
    int usable = 0;
    oit_status s = open_parts(m, d->model, d->need_parts, err);
    if (s != OIT_OK)
        return s;
    const char *recorded = oit_partfile_source_name(m->pf);
    beside(d->model, recorded, path, sizeof path);
    if (d->mesh) {
        if ((s = load_source(m, d->mesh, err)) == OIT_OK)
            s = check_pair(m, d, d->mesh, 1, &usable, err);
    } else if (*recorded && !strchr(recorded, '/') && access(path, R_OK) == 0) {
        s = found_beside(m, d, path, err);
    } else {
        add_note(m, d->progress, "the source mesh '%s' recorded in %s is not beside it and "
                 "no --mesh was given: the in-core methods and the reference draw the part "
                 "file's clipped triangles", *recorded ? recorded : "(none)", d->model);
    }
    if (s != OIT_OK || m->have_source)
        return s;
    oit_partfile_summary sum;
    oit_partfile_get_summary(m->pf, &sum);
    m->source_triangles = sum.triangles_in;
    s = oit_partfile_load_mesh(m->pf, &m->clipped, err);
    m->have_clipped = s == OIT_OK;
    return s;
}

oit_status oit_bench_models_open(const oit_bench_models_desc *d, oit_bench_models *m,
                                 oit_error *err)
{
    memset(m, 0, sizeof *m);
    oit_status s = oit_bench_is_part_file(d->model) ? open_part_model(m, d, err)
                                          : open_mesh_model(m, d, err);
    if (s != OIT_OK)
        oit_bench_models_close(m);
    return s;
}

void oit_bench_models_close(oit_bench_models *m)
{
    if (m->have_source)
        oit_mesh_free(&m->source);
    if (m->have_clipped)
        oit_mesh_free(&m->clipped);
    oit_partfile_close(m->pf);
    if (m->temp_path[0])
        unlink(m->temp_path);
    memset(m, 0, sizeof *m);
}

const oit_mesh *oit_bench_models_in_core(const oit_bench_models *m)
{
    return m->have_source ? &m->source : &m->clipped;
}

oit_bench_geometry oit_bench_models_in_core_geometry(const oit_bench_models *m)
{
    return m->have_source ? OIT_BENCH_GEOMETRY_SOURCE_MESH : OIT_BENCH_GEOMETRY_PART_FILE;
}
