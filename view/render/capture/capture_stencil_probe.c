/* The stencil capture's sample mode and self-test probe, without GL
 * (capture_stencil_probe.h). */
#include "view/render/capture/capture_stencil_probe.h"

#include <stdio.h>
#include <string.h>

/* ---- the sample mode ------------------------------------------------------ */

/* The mode GL allocates for K: the smallest supported count >= K. */
static const oit_sample_mode *allocated(const oit_sample_modes *m, int K)
{
    const oit_sample_mode *best = NULL;
    for (int i = 0; i < m->n; i++)
        if (m->mode[i].samples >= K && (!best || m->mode[i].samples < best->samples))
            best = &m->mode[i];
    return best;
}

static int is_true(const oit_sample_mode *m)
{
    return m && m->multisamples == m->samples && m->scale_x == 1 && m->scale_y == 1 &&
           m->conformant;
}

/* The largest K' <= K that both formats serve as K' true multisamples. */
static int largest_true(const oit_sample_modes *c, const oit_sample_modes *d, int K)
{
    for (int k = K; k >= 2; k--) {
        const oit_sample_mode *a = allocated(c, k), *b = allocated(d, k);
        if (a && b && a->samples == k && b->samples == k && is_true(a) && is_true(b))
            return k;
    }
    return 0;
}

static oit_status not_true(const oit_sample_modes *f, const oit_sample_mode *m, int K, int best,
                           oit_error *err)
{
    char most[64] = "none: the stencil capture is not offered here";
    if (best)
        snprintf(most, sizeof most, "K=%d", best);
    return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                         "stencil capture: K=%d takes %d samples of the %s, served as %d "
                         "multisamples x %dx%d supersamples (%sconformant; "
                         "GL_NV_internalformat_sample_query): the fill shader would run %d "
                         "times a pixel, so stencil routing cannot put one fragment in each "
                         "sample; the largest K of true multisamples here: %s",
                         K, m->samples, f->what, m->multisamples, m->scale_x, m->scale_y,
                         m->conformant ? "" : "not ", m->scale_x * m->scale_y, most);
}

oit_status oit_stencil_pick_samples(int K, const oit_sample_modes *colour,
                                    const oit_sample_modes *depth_stencil, int *samples,
                                    oit_error *err)
{
    const oit_sample_mode *c = allocated(colour, K), *d = allocated(depth_stencil, K);
    int best = largest_true(colour, depth_stencil, K);
    if (!c || !d)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "stencil capture: K=%d exceeds the "
                             "sample counts of the %s", K, !c ? colour->what : depth_stencil->what);
    if (c->samples != d->samples)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "stencil capture: K=%d gives %d samples "
                             "of the %s but %d of the %s: no complete target", K, c->samples,
                             colour->what, d->samples, depth_stencil->what);
    if (!is_true(c))
        return not_true(colour, c, K, best, err);
    if (!is_true(d))
        return not_true(depth_stencil, d, K, best, err);
    *samples = c->samples;
    return OIT_OK;
}

/* ---- the probe's scene ---------------------------------------------------- */

/* Triangle q's left and right edges as x at height y (window units), for
 * its row-0 columns lo..hi: the left one nearly upright 0.25-0.35 left of
 * column lo, the right one leaning at 45 degrees, 0.25 right of column
 * hi's centre at row 0's and past column hi + 1's at row 1's. */
static double left_x(int lo, double y)
{
    return lo - 0.3 + 0.1 * (y - 1.0);
}

static double right_x(int hi, double y)
{
    return hi + 1.25 + (y - 1.0);
}

static void set_vertex(oit_vertex *v, double x, double y, float z)
{
    v->pos[0] = (float)x;
    v->pos[1] = (float)y;
    v->pos[2] = z;
    const uint8_t rgba[4] = {200, 120, 40, 128};
    memcpy(v->rgba, rgba, sizeof rgba);
}

/* The edges meet below the frame; the third edge lies above it. */
static void probe_triangle(oit_triangle *t, int lo, int hi, float z, int height)
{
    double apex = 1.0 - (hi - lo + 1.55) / 0.9, top = height + 2.0;
    set_vertex(&t->v[0], left_x(lo, apex), apex, z);
    set_vertex(&t->v[1], right_x(hi, top), top, z);
    set_vertex(&t->v[2], left_x(lo, top), top, z);
}

static double edge(const float *a, const float *b, double x, double y)
{
    return ((double)b[0] - a[0]) * (y - a[1]) - ((double)b[1] - a[1]) * (x - a[0]);
}

static int covers(const oit_triangle *t, double x, double y)
{
    double e0 = edge(t->v[0].pos, t->v[1].pos, x, y);
    double e1 = edge(t->v[1].pos, t->v[2].pos, x, y);
    double e2 = edge(t->v[2].pos, t->v[0].pos, x, y);
    return (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
}

/* Window units are view units: an orthographic volume of the frame's size. */
static void probe_view(oit_view *v, int w, int h)
{
    memset(v, 0, sizeof *v);
    v->camera.target[2] = -1.0f;
    v->camera.up[1] = 1.0f;
    v->camera.fovy_deg = 45.0f;
    v->camera.znear = 0.5f;
    v->camera.zfar = 100.0f;
    v->camera.projection = OIT_PROJ_ORTHOGRAPHIC;
    v->camera.ortho_height = (float)h;
    v->camera.window[1] = (float)w;
    v->camera.window[3] = (float)h;
    v->width = w;
    v->height = h;
}

void oit_stencil_probe_build(oit_stencil_probe *p, int K)
{
    memset(p, 0, sizeof *p);
    p->K = K;
    p->width = 2 * K + 1;
    p->height = OIT_PROBE_ROWS;
    /* Drawn front to back's reverse: the draw order is not the depth order. */
    for (int q = 0; q < K; q++)
        probe_triangle(&p->tris[q], K - q, 2 * K - 1 - q, -2.0f - 0.5f * (float)(K - 1 - q),
                       p->height);
    for (int y = 0; y < p->height; y++)
        for (int x = 0; x < p->width; x++)
            for (int q = 0; q < K; q++)
                if (covers(&p->tris[q], x + 0.5, y + 0.5))
                    p->cover[x + y * p->width] |= 1u << q;
    probe_view(&p->view, p->width, p->height);
}

/* ---- the verdict ------------------------------------------------------------ */

static int popcount(uint32_t m)
{
    int n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

/* The first pixel whose count is not its covering triangles', or -1. */
static int first_bad_count(const oit_stencil_probe *p, const uint32_t *counts,
                           uint64_t *counted, uint64_t *expected)
{
    int bad = -1;
    *counted = *expected = 0;
    for (int i = 0; i < p->width * p->height; i++) {
        uint32_t want = (uint32_t)popcount(p->cover[i]);
        *counted += counts[i];
        *expected += want;
        if (bad < 0 && counts[i] != want)
            bad = i;
    }
    return bad;
}

static oit_status count_error(const oit_stencil_probe *p, int px, const uint32_t *counts,
                              uint64_t counted, uint64_t expected, oit_error *err)
{
    return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                         "stencil capture: self-test failed at K=%d: the fill shader "
                         "counted %u fragment(s) at pixel (%d, %d), whose centre %d "
                         "triangle(s) cover (%llu in the probe for %llu): it does not run "
                         "once a pixel a triangle (supersampling or sample shading), so "
                         "stencil routing cannot give each fragment one sample",
                         p->K, counts[px], px % p->width, px / p->width,
                         popcount(p->cover[px]), (unsigned long long)counted,
                         (unsigned long long)expected);
}

/* Pixel px's first samples against its covering triangles; OIT_OK or the
 * reason, naming the sample. */
static oit_status check_samples(const oit_stencil_probe *p, int px, const uint32_t *prims,
                                oit_error *err)
{
    uint32_t cover = p->cover[px], seen = 0;
    int n = popcount(cover), x = px % p->width, y = px / p->width;
    for (int i = 0; i < n; i++) {
        uint32_t id = prims[(size_t)px * (size_t)p->K + (size_t)i];
        const char *why = NULL;
        if (id == OIT_STENCIL_UNWRITTEN)
            why = "was never written: a fragment was lost";
        else if (id >= 32 || !(cover >> id & 1u))
            why = "holds a triangle that does not cover the pixel centre";
        else if (seen >> id & 1u)
            why = "holds a triangle a lower sample holds already";
        if (why) {
            char which[32] = "";
            if (id != OIT_STENCIL_UNWRITTEN)
                snprintf(which, sizeof which, " (triangle %u)", id);
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "stencil capture: self-test failed at K=%d: pixel (%d, %d), "
                                 "covered by %d triangle(s), sample %d %s%s; the driver does "
                                 "not route one fragment to each sample with the stencil",
                                 p->K, x, y, n, i, why, which);
        }
        seen |= 1u << id;
    }
    return OIT_OK;
}

oit_status oit_stencil_probe_verdict(const oit_stencil_probe *p, const uint32_t *prims,
                                     const uint32_t *counts, oit_error *err)
{
    uint64_t counted, expected;
    int bad = first_bad_count(p, counts, &counted, &expected);
    if (bad >= 0)
        return count_error(p, bad, counts, counted, expected, err);
    for (int px = 0; px < p->width * p->height; px++) {
        oit_status s = check_samples(p, px, prims, err);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}
