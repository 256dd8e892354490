/* oitbench's measurement (bench_run.h). */
#include "tools/oitbench/bench_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/gl/gpu_timer.h"
#include "tools/common/method_run.h"

const char *oit_bench_geometry_label(oit_bench_geometry g, uint64_t drawn, uint64_t source)
{
    if (g != OIT_BENCH_GEOMETRY_PART_FILE)
        return "source mesh";
    return drawn > source ? "part file (clipped)" : "part file";
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double oit_bench_percentile(double *v, size_t n, double pct)
{
    qsort(v, n, sizeof *v, cmp_double);
    size_t rank = (size_t)ceil(pct / 100.0 * (double)n);
    return v[rank > 0 ? rank - 1 : 0];
}

/* Median and 95th percentile of n samples, without reordering them. */
static void median_p95(const double *v, size_t n, double *median, double *p95)
{
    double *tmp = malloc(n * sizeof *tmp);
    if (!tmp || n == 0) {
        *median = *p95 = NAN;
        free(tmp);
        return;
    }
    memcpy(tmp, v, n * sizeof *tmp);
    *median = oit_bench_percentile(tmp, n, 50.0);
    *p95 = oit_bench_percentile(tmp, n, 95.0);
    free(tmp);
}

/* view < 0: the method could not open. */
static void mark_failed(oit_bench_method *m, int view, const char *msg)
{
    m->runnable = 0;
    if (view < 0)
        snprintf(m->reason, sizeof m->reason, "%s", msg);
    else
        snprintf(m->reason, sizeof m->reason, "view %d: %.480s", view, msg);
}

/* One GL context for all GL methods, made here so that they render in turn
 * in the same context (each method's own headless context would not be
 * current when another method rendered last). */
static void open_methods(const oit_bench_desc *d, oit_bench_result *r, oit_gl **gl)
{
    oit_error err = {0};
    int need_gl = 0;
    for (int i = 0; i < r->method_count; i++)
        need_gl |= (r->methods[i].method->flags & OIT_RENDER_METHOD_GL);
    oit_status gs = OIT_OK;
    snprintf(r->renderer, sizeof r->renderer, "none (no GL method requested)");
    if (need_gl && (gs = oit_gl_create(&(oit_gl_desc){0}, gl, &err)) == OIT_OK)
        snprintf(r->renderer, sizeof r->renderer, "%s", oit_gl_renderer(*gl));
    else if (need_gl)
        snprintf(r->renderer, sizeof r->renderer, "none (no GL context: %.200s)", err.message);
    /* The stream method opens the part file again through liboit. */
    oit_run_source so = {.path = d->partfile ? oit_partfile_name(d->partfile) : NULL,
                            .desc = {.capture = d->capture}};
    oit_run_options opt = {.max_layers = d->max_layers, .gl = *gl, .source = &so};
    for (int i = 0; i < r->method_count; i++) {
        oit_bench_method *m = &r->methods[i];
        m->runnable = 1;
        opt.threshold = m->epsilon >= 0.0f ? &m->epsilon : NULL;
        if ((m->method->flags & OIT_RENDER_METHOD_GL) && gs != OIT_OK)
            mark_failed(m, -1, r->renderer);
        else if ((m->method->flags & OIT_RENDER_METHOD_PART_FILE) && !d->partfile)
            mark_failed(m, -1, "renders a part file (.oitp), and this run has none");
        else if (oit_run_open(m->method, d->mesh, &opt, &m->state, &err) != OIT_OK)
            mark_failed(m, -1, err.message);
    }
}

static oit_shading bench_shading(const oit_mesh_info *info, oit_shading_mode mode,
                                 oit_colour_space space)
{
    oit_shading s = {0};
    s.mode = mode;
    s.colour_space = space;
    s.attributes = info->attributes;
    s.scene_scale = oit_scene_scale(info->bounds_min, info->bounds_max);
    oit_shading_resolve_defaults(&s);
    return s;
}

/* One frame of m; keeps the image in *keep when keep is non-NULL. */
static oit_status render_frame(oit_bench_method *m, const oit_view *view, oit_frame_stats *st,
                               oit_image *keep, oit_error *err)
{
    oit_image img = {0};
    memset(st, 0, sizeof *st);
    oit_status s = oit_run_render(m->state, view, &img, NULL, NULL, st, err);
    if (s == OIT_OK && oit_run_stream_stats(m->state)) {
        uint64_t b = oit_run_stream_stats(m->state)->gpu_bytes_peak;
        st->gpu_bytes_peak = b > st->gpu_bytes_peak ? b : st->gpu_bytes_peak;
    }
    if (s == OIT_OK && keep) {
        oit_image_free(keep);
        *keep = img;
    } else {
        oit_image_free(&img);
    }
    return s;
}

static void record(oit_bench_method *m, oit_bench_cell *c, const oit_frame_stats *st)
{
    m->gpu_ms[m->ms_count] = -1.0;
    m->gpu_frame[m->ms_count] = st->gpu_frame;
    m->ms[m->ms_count++] = st->ms;
    c->gpu_bytes_peak = st->gpu_bytes_peak > c->gpu_bytes_peak ? st->gpu_bytes_peak
                                                                : c->gpu_bytes_peak;
    c->gpu_mesh_bytes = st->gpu_mesh_bytes > c->gpu_mesh_bytes ? st->gpu_mesh_bytes
                                                                : c->gpu_mesh_bytes;
    c->max_layers = st->max_layers > c->max_layers ? st->max_layers : c->max_layers;
    c->host_waits_max = st->host_waits > c->host_waits_max ? st->host_waits : c->host_waits_max;
    c->fragments = st->fragments;
}

/* Every GPU figure of m's frames (waited for: the view's frames are done),
 * each to the timed frame of its number from index first on. */
static void take_gpu_times(oit_bench_method *m, size_t first)
{
    oit_gpu_times t;
    while (m->state && oit_run_gpu_poll(m->state, &t, 1))
        for (size_t k = first; k < m->ms_count; k++)
            if (m->gpu_frame[k] == t.frame)
                m->gpu_ms[k] = t.ms;
}

/* The median of the GPU times from index first on; -1 when none. */
static double gpu_median(const oit_bench_method *m, size_t first)
{
    size_t n = 0;
    double *v = malloc((m->ms_count - first + 1) * sizeof *v), med = -1.0, p95 = 0;
    for (size_t k = first; v && k < m->ms_count; k++)
        if (m->gpu_ms[k] >= 0)
            v[n++] = m->gpu_ms[k];
    if (n)
        median_p95(v, n, &med, &p95);
    free(v);
    return med;
}

/* Warm-up rounds, then timed rounds, every runnable method once per round. */
static void measure_view(const oit_bench_desc *d, oit_bench_result *r, int v,
                         const oit_view *view, oit_image *last)
{
    oit_error err = {0};
    oit_frame_stats st;
    size_t *first = calloc((size_t)r->method_count, sizeof *first);
    for (int i = 0; first && i < r->method_count; i++)
        first[i] = r->methods[i].ms_count;
    for (int round = 0; round < d->warmup + d->frames; round++) {
        int timed = round >= d->warmup;
        for (int i = 0; i < r->method_count; i++) {
            oit_bench_method *m = &r->methods[i];
            if (!m->runnable)
                continue;
            if (render_frame(m, view, &st, timed ? &last[i] : NULL, &err) != OIT_OK)
                mark_failed(m, v, err.message);
            else if (timed)
                record(m, &m->cells[v], &st);
        }
    }
    for (int i = 0; first && i < r->method_count; i++) {
        oit_bench_method *m = &r->methods[i];
        oit_bench_cell *c = &m->cells[v];
        c->ok = m->runnable;
        take_gpu_times(m, first[i]);
        c->gpu_ms_median = gpu_median(m, first[i]);
        if (c->ok)
            median_p95(m->ms + first[i], m->ms_count - first[i], &c->ms_median, &c->ms_p95);
    }
    free(first);
}

/* img's % of pixels off by > 1/255 among those outside the mask
 * (ambiguous: 1 inside): img's masked pixels take ref's values, so that
 * they count as equal, and the count is over the rest (0 when none). */
static oit_status compare_outside(const oit_image *ref, oit_image *img, const uint8_t *ambiguous,
                                  uint64_t masked, double *pct, oit_error *err)
{
    size_t n = (size_t)ref->width * (size_t)ref->height;
    oit_image_diff d;
    for (size_t p = 0; p < n; p++)
        if (ambiguous[p])
            memcpy(img->rgba + p * 4, ref->rgba + p * 4, 4 * sizeof(float));
    oit_status s = oit_image_compare(ref, img, &d, NULL, 1.0f, err);
    *pct = n > masked ? 100.0 * (double)d.pixels_over / (double)(n - masked) : 0.0;
    return s;
}

static void compare_view(oit_bench_result *r, int v, const oit_image *ref,
                         const uint8_t *ambiguous, oit_image *last)
{
    oit_error err = {0};
    size_t n = (size_t)ref->width * (size_t)ref->height;
    uint64_t masked = 0;
    for (size_t p = 0; p < n; p++)
        masked += ambiguous[p] != 0;
    r->ref_ambiguous_pct[v] = n ? 100.0 * (double)masked / (double)n : 0.0;
    for (int i = 0; i < r->method_count; i++) {
        oit_bench_method *m = &r->methods[i];
        oit_bench_cell *c = &m->cells[v];
        if (c->ok && (oit_image_compare(ref, &last[i], &c->diff, NULL, 1.0f, &err) != OIT_OK ||
                      compare_outside(ref, &last[i], ambiguous, masked,
                                      &c->pct_over_outside_ambiguity, &err) != OIT_OK)) {
            c->ok = 0;
            mark_failed(m, v, err.message);
        }
        oit_image_free(&last[i]);
    }
}

static void print_view(FILE *f, const oit_bench_result *r, int v)
{
    if (!f)
        return;
    fprintf(f, "oitbench: view %d/%d: reference image %.1f ms", v + 1, r->views, r->ref_ms[v]);
    for (int i = 0; i < r->method_count; i++) {
        const oit_bench_method *m = &r->methods[i];
        if (m->cells[v].ok)
            fprintf(f, "; %s %.2f ms (gpu %.2f) rmse %.3g", m->name, m->cells[v].ms_median,
                    m->cells[v].gpu_ms_median, m->cells[v].diff.rmse);
        else
            fprintf(f, "; %s not run", m->name);
    }
    fprintf(f, "\n");
}

static void summarise(oit_bench_method *m, int views)
{
    int n = 0;
    m->psnr_min = INFINITY;
    for (int v = 0; v < views; v++) {
        const oit_bench_cell *c = &m->cells[v];
        if (!c->ok)
            continue;
        n++;
        m->rmse_mean += c->diff.rmse;
        m->max_abs_worst = fmax(m->max_abs_worst, c->diff.max_abs);
        m->pct_over_worst = fmax(m->pct_over_worst, c->diff.pct_over_1_255);
        m->pct_over_outside_ambiguity_worst =
            fmax(m->pct_over_outside_ambiguity_worst, c->pct_over_outside_ambiguity);
        m->psnr_min = fmin(m->psnr_min, c->diff.psnr);
        m->gpu_bytes_peak = c->gpu_bytes_peak > m->gpu_bytes_peak ? c->gpu_bytes_peak
                                                                   : m->gpu_bytes_peak;
        m->gpu_mesh_bytes = c->gpu_mesh_bytes > m->gpu_mesh_bytes ? c->gpu_mesh_bytes
                                                                   : m->gpu_mesh_bytes;
        m->max_layers = c->max_layers > m->max_layers ? c->max_layers : m->max_layers;
        m->host_waits_max = c->host_waits_max > m->host_waits_max ? c->host_waits_max
                                                                  : m->host_waits_max;
    }
    m->rmse_mean = n ? m->rmse_mean / n : NAN;
    median_p95(m->ms, m->ms_count, &m->ms_median, &m->ms_p95);
    m->gpu_ms_median = gpu_median(m, 0);
}

static oit_status alloc_result(const oit_bench_desc *d, oit_bench_result *r, oit_error *err)
{
    memset(r, 0, sizeof *r);
    r->method_count = d->entry_count;
    r->views = d->views;
    r->methods = calloc((size_t)d->entry_count, sizeof *r->methods);
    r->ref_ms = calloc((size_t)d->views, sizeof *r->ref_ms);
    r->ref_layers = calloc((size_t)d->views, sizeof *r->ref_layers);
    r->ref_ambiguous_pct = calloc((size_t)d->views, sizeof *r->ref_ambiguous_pct);
    int ok = r->methods && r->ref_ms && r->ref_layers && r->ref_ambiguous_pct;
    for (int i = 0; ok && i < d->entry_count; i++) {
        oit_bench_method *m = &r->methods[i];
        m->method = oit_method_find(d->entries[i].method);
        m->epsilon = d->entries[i].epsilon;
        snprintf(m->name, sizeof m->name, "%s", d->entries[i].name);
        int parts = m->method && (m->method->flags & OIT_RENDER_METHOD_PART_FILE);
        m->geometry = parts ? OIT_BENCH_GEOMETRY_PART_FILE : d->mesh_geometry;
        m->triangles = parts ? d->partfile_triangles : (uint64_t)d->mesh->count;
        m->source_triangles = d->source_triangles;
        size_t frames = (size_t)d->views * (size_t)d->frames + 1;
        m->ms = malloc(frames * sizeof *m->ms);
        m->gpu_ms = malloc(frames * sizeof *m->gpu_ms);
        m->gpu_frame = malloc(frames * sizeof *m->gpu_frame);
        m->cells = calloc((size_t)d->views, sizeof *m->cells);
        ok = m->method && m->ms && m->gpu_ms && m->gpu_frame && m->cells;
    }
    if (!ok)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate results for %d methods x %d "
                             "views (or a method name is unknown)", d->entry_count, d->views);
    return OIT_OK;
}

static oit_status run_views(const oit_bench_desc *d, oit_bench_result *r, oit_error *err)
{
    const oit_render_method_info *refm = oit_method_find("reference");
    const oit_mesh *refmesh = d->reference_mesh ? d->reference_mesh : d->mesh;
    oit_run *ref_state = NULL;
    oit_image *last = calloc((size_t)r->method_count, sizeof *last);
    uint8_t *ambiguous = calloc((size_t)d->width * (size_t)d->height, 1);
    oit_status s = last && ambiguous
                       ? oit_run_open(refm, refmesh, NULL, &ref_state, err)
                       : oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate image slots and "
                                       "a %dx%d ambiguity mask", d->width, d->height);
    /* one view for every method, framed on the reference's mesh */
    oit_view view = {.width = d->width, .height = d->height,
                     .shading = bench_shading(&refmesh->info, d->shading, d->colour_space)};
    for (int v = 0; v < d->views && s == OIT_OK; v++) {
        oit_image ref = {0};
        oit_frame_stats st = {0};
        oit_camera_default_up(&view.camera, refmesh->info.bounds_min, refmesh->info.bounds_max,
                              (float)(v * 360.0 / d->views), 20.0f, d->up_axis);
        s = oit_run_render(ref_state, &view, &ref, NULL, ambiguous, &st, err);
        if (s != OIT_OK) {
            oit_error_prefix(err, "reference");
            break;
        }
        r->ref_ms[v] = st.ms;
        r->ref_layers[v] = st.max_layers;
        measure_view(d, r, v, &view, last);
        compare_view(r, v, &ref, ambiguous, last);
        oit_image_free(&ref);
        print_view(d->progress, r, v);
    }
    if (ref_state)
        oit_run_close(ref_state);
    free(ambiguous);
    free(last);
    return s;
}

oit_status oit_bench_run(const oit_bench_desc *d, oit_bench_result *r, oit_error *err)
{
    oit_gl *gl = NULL;
    oit_status s = alloc_result(d, r, err);
    if (s == OIT_OK) {
        open_methods(d, r, &gl);
        s = run_views(d, r, err);
    }
    for (int i = 0; s == OIT_OK && i < r->method_count; i++)
        summarise(&r->methods[i], r->views);
    /* GL objects go before the context they live in. */
    for (int i = 0; r->methods && i < r->method_count; i++)
        if (r->methods[i].state) {
            oit_run_close(r->methods[i].state);
            r->methods[i].state = NULL;
        }
    if (gl)
        oit_gl_destroy(gl);
    return s;
}

void oit_bench_result_free(oit_bench_result *r)
{
    for (int i = 0; r->methods && i < r->method_count; i++) {
        free(r->methods[i].ms);
        free(r->methods[i].gpu_ms);
        free(r->methods[i].gpu_frame);
        free(r->methods[i].cells);
    }
    free(r->methods);
    free(r->ref_ms);
    free(r->ref_layers);
    free(r->ref_ambiguous_pct);
    memset(r, 0, sizeof *r);
}
