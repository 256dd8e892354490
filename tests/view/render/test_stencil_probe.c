/* The stencil capture's checks without GL (view/render/capture/capture_stencil_probe.h):
 * the self-test's probe scene has what it must (partial coverage, pixels
 * with K, with fewer and with no fragments, edges clear of pixel centres);
 * its verdict accepts a correct read-back and refuses crafted wrong ones
 * (each fragment twice, one lost, one foreign, counts doubled as NVIDIA's
 * 8 x 2 supersampled "16 samples" give), and the sample mode refuses K
 * samples that are not K true multisamples, naming the largest that is. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/capture/capture_stencil_probe.h"
#include "tests/lib/test_check.h"

static int bits(uint32_t m)
{
    int n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

/* Distance from (x, y) to the segment's line, in pixels. */
static double line_dist(const float *a, const float *b, double x, double y)
{
    double dx = (double)b[0] - a[0], dy = (double)b[1] - a[1];
    return fabs(dx * (y - a[1]) - dy * (x - a[0])) / sqrt(dx * dx + dy * dy);
}

static void check_scene(int K)
{
    oit_stencil_probe p;
    oit_stencil_probe_build(&p, K);
    int full = 0, fewer = 0, none = 0, rows_differ = 0, pixels = p.width * p.height;
    for (int i = 0; i < pixels; i++) {
        int n = bits(p.cover[i]);
        CHECK(n <= K, "K=%d: pixel %d gets %d fragments, more than K", K, i, n);
        full += n == K;
        fewer += n > 0 && n < K;
        none += n == 0;
        if (i < p.width)
            rows_differ |= p.cover[i] != p.cover[i + p.width];
    }
    CHECK(full > 0 && fewer > 0 && none > 0, "K=%d: %d pixels of K fragments, %d of fewer, "
          "%d of none; the probe needs each", K, full, fewer, none);
    CHECK(rows_differ, "K=%d: both rows alike: a row mix-up would go unseen", K);
    double closest = 1e9;
    for (int q = 0; q < K; q++) {
        int covered = 0;
        for (int i = 0; i < pixels; i++)
            covered += p.cover[i] >> q & 1u;
        CHECK(covered > 0 && covered < pixels, "K=%d: triangle %d covers %d of %d pixels", K,
              q, covered, pixels);
        for (int e = 0; e < 3; e++)
            for (int i = 0; i < pixels; i++) {
                double d = line_dist(p.tris[q].v[e].pos, p.tris[q].v[(e + 1) % 3].pos,
                                     i % p.width + 0.5, i / p.width + 0.5);
                closest = d < closest ? d : closest;
            }
    }
    CHECK(closest >= 0.14, "K=%d: an edge passes %.3f pixel from a pixel centre", K, closest);
}

/* A correct read-back of p: every pixel counted once a covering triangle,
 * its samples holding them in draw order, the rest unwritten. */
static void correct_readback(const oit_stencil_probe *p, uint32_t *prims, uint32_t *counts)
{
    for (int i = 0; i < p->width * p->height; i++) {
        int k = 0;
        for (int q = 0; q < p->K; q++)
            if (p->cover[i] >> q & 1u)
                prims[i * p->K + k++] = (uint32_t)q;
        counts[i] = (uint32_t)k;
        while (k < p->K)
            prims[i * p->K + k++] = OIT_STENCIL_UNWRITTEN;
    }
}

/* The first pixel with n covering triangles. */
static int pixel_with(const oit_stencil_probe *p, int n)
{
    for (int i = 0; i < p->width * p->height; i++)
        if (bits(p->cover[i]) == n)
            return i;
    return -1;
}

static void expect_verdict(const oit_stencil_probe *p, const uint32_t *prims,
                           const uint32_t *counts, const char *want, const char *what)
{
    oit_error err = {0};
    oit_status s = oit_stencil_probe_verdict(p, prims, counts, &err);
    printf("K=%d %s: %s\n", p->K, what, s == OIT_OK ? "accepted" : err.message);
    if (!want)
        CHECK(s == OIT_OK, "K=%d %s: refused: %s", p->K, what, err.message);
    else
        CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, want),
              "K=%d %s: want a refusal saying '%s', got %s: %s", p->K, what, want,
              oit_status_name(s), err.message);
}

static void check_verdicts(int K)
{
    oit_stencil_probe p;
    oit_stencil_probe_build(&p, K);
    size_t pixels = (size_t)p.width * p.height;
    uint32_t *prims = malloc(sizeof *prims * pixels * (size_t)K), counts[OIT_PROBE_MAX_COLS * 2];
    int full = pixel_with(&p, K);
    correct_readback(&p, prims, counts);
    expect_verdict(&p, prims, counts, NULL, "correct");

    /* the samples in another order: the resolve sorts, any order routes */
    uint32_t *f = prims + (size_t)full * K, t = f[0];
    f[0] = f[K - 1];
    f[K - 1] = t;
    expect_verdict(&p, prims, counts, NULL, "correct, samples reordered");

    /* each fragment landed twice: samples 2i and 2i+1 of every pixel hold
     * its i-th, and the later half of its fragments none */
    correct_readback(&p, prims, counts);
    for (size_t i = 0; i < pixels; i++)
        for (int k = K - 1; k >= 0; k--)
            prims[i * K + (size_t)k] = prims[i * K + (size_t)k / 2];
    expect_verdict(&p, prims, counts, "a lower sample holds already", "each fragment twice");

    correct_readback(&p, prims, counts);
    prims[(size_t)full * K + (size_t)K - 1] = OIT_STENCIL_UNWRITTEN;
    expect_verdict(&p, prims, counts, "never written", "a fragment missing");

    /* a triangle that misses the centre, in a pixel only one covers */
    correct_readback(&p, prims, counts);
    int one = pixel_with(&p, 1);
    prims[(size_t)one * K] = (prims[(size_t)one * K] + 1) % (uint32_t)K;
    expect_verdict(&p, prims, counts, "does not cover the pixel centre", "a foreign fragment");

    /* the count doubled everywhere, samples right: two shader runs a pixel */
    correct_readback(&p, prims, counts);
    for (size_t i = 0; i < pixels; i++)
        counts[i] *= 2;
    expect_verdict(&p, prims, counts, "counted", "count doubled");

    /* one pixel's count one short */
    correct_readback(&p, prims, counts);
    counts[full]--;
    expect_verdict(&p, prims, counts, "counted", "count one short");
    free(prims);
}

/* NVIDIA's answers as the brief and its users report them: 16 samples of
 * both formats are 8 multisamples x 2x1 supersamples, not conformant. */
static oit_sample_modes nvidia_like(const char *what, int sixteen_true)
{
    oit_sample_modes m = {.what = what, .n = 4};
    m.mode[0] = sixteen_true ? (oit_sample_mode){16, 16, 1, 1, 1}
                             : (oit_sample_mode){16, 8, 2, 1, 0};
    m.mode[1] = (oit_sample_mode){8, 8, 1, 1, 1};
    m.mode[2] = (oit_sample_mode){4, 4, 1, 1, 1};
    m.mode[3] = (oit_sample_mode){2, 2, 1, 1, 1};
    return m;
}

static void expect_pick(int K, const oit_sample_modes *c, const oit_sample_modes *d,
                        int want_samples, const char *want_a, const char *want_b)
{
    oit_error err = {0};
    int samples = -1;
    oit_status s = oit_stencil_pick_samples(K, c, d, &samples, &err);
    printf("pick K=%d: %s\n", K, s == OIT_OK ? "ok" : err.message);
    if (want_samples) {
        CHECK(s == OIT_OK && samples == want_samples, "K=%d: want %d samples, got %s %d: %s",
              K, want_samples, oit_status_name(s), samples, err.message);
        return;
    }
    CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, want_a) &&
              (!want_b || strstr(err.message, want_b)),
          "K=%d: want a refusal saying '%s' and '%s', got %s: %s", K, want_a,
          want_b ? want_b : "", oit_status_name(s), err.message);
}

static void check_pick(void)
{
    oit_sample_modes c = nvidia_like("GL_RGBA32UI texture", 0);
    oit_sample_modes d = nvidia_like("GL_DEPTH24_STENCIL8 renderbuffer", 0);
    expect_pick(16, &c, &d, 0, "8 multisamples x 2x1 supersamples", "largest K of true "
                "multisamples here: K=8");
    expect_pick(12, &c, &d, 0, "takes 16 samples", "K=8");
    expect_pick(8, &c, &d, 8, NULL, NULL);
    expect_pick(5, &c, &d, 8, NULL, NULL); /* GL gives 8 for 5: all true */
    expect_pick(2, &c, &d, 2, NULL, NULL);
    /* only the depth-stencil supersampled at 16 */
    oit_sample_modes c16 = nvidia_like("GL_RGBA32UI texture", 1);
    expect_pick(16, &c16, &d, 0, "GL_DEPTH24_STENCIL8 renderbuffer, served as 8", "K=8");
    /* a driver without the query: every count true as far as it says */
    oit_sample_modes d16 = nvidia_like("GL_DEPTH24_STENCIL8 renderbuffer", 1);
    expect_pick(16, &c16, &d16, 16, NULL, NULL);
    /* the formats round K to different counts: no complete target */
    oit_sample_modes d_no8 = d16;
    d_no8.mode[1] = d_no8.mode[0];
    d_no8.n = 2;
    expect_pick(6, &c16, &d_no8, 0, "gives 8 samples of the GL_RGBA32UI texture but 16", NULL);
    expect_pick(17, &c16, &d16, 0, "exceeds the sample counts", NULL);
    /* nothing true at all */
    oit_sample_modes bad = {.what = "GL_RGBA32UI texture", .n = 1};
    bad.mode[0] = (oit_sample_mode){4, 1, 2, 2, 0};
    expect_pick(4, &bad, &d16, 0, "1 multisamples x 2x2", "none");
}

int main(void)
{
    for (int K = 2; K <= 16; K++)
        check_scene(K);
    for (int K = 2; K <= 16; K += 2)
        check_verdicts(K);
    check_verdicts(3);
    check_pick();
    return test_verdict();
}
