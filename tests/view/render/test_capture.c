/* Capture backends against DFB and hand compositing: one batch of <= K
 * layers, the same scene in several front-to-back batches (transparent and
 * translucent, with a closed object split across batches), exact overflow
 * counts, and the stencil backend either agreeing or saying why not. The
 * first-K capture: pixels far over its slots composited exactly once (the
 * fragment totals equal DFB's, the image DFB's and the hand result), the
 * exact count of pixels that took the second pass, none where nothing
 * overflows, pass 2 in bands under a small slot budget, and the counted
 * fallback where 2 slots a pixel do not fit. A mesh past one storage
 * buffer, counted and first-K. Counted batches predicted from the last
 * frame's counts, the prediction held and not. */
#include <stdio.h>
#include <stdlib.h>

#include "tests/lib/gl_test_dfb.h"
#include "tests/lib/gl_test_scene.h"
#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_context.h"
#include "view/render/image/image.h"
#include "tests/lib/capture_set.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"


/* Renders q split into batches [start[i], start[i+1]); rect[i] may be NULL. */
static int capture_scene(oit_capture *c, const oit_view *v, const quad_spec *q,
                         const int *start, int nb, const int (*rects)[4],
                         oit_image *img, oit_frame_stats *st)
{
    oit_error err = {0};
    oit_status s = capture_quads(c, v, q, start, nb, rects, img, st, &err);
    if (s != OIT_OK)
        fprintf(stderr, "FAIL: capture: %s\n", err.message);
    return s == OIT_OK;
}

/* Eight quads front to back (two partial), so batches can split them. */
static void transparent_scene(quad_spec q[8])
{
    for (int i = 0; i < 8; i++) {
        float z = -1.5f - 0.75f * i;
        float half = i == 2 ? 0.37f * -z : i == 5 ? 0.61f * -z : 2.0f * -z;
        q[i] = mk(z, half, (i * 97) % 256, (i * 53 + 40) % 256, 255 - i * 30, 60 + 20 * i, i % 3 != 1);
    }
}

/* oit_capture_end into an image the caller holds: the same pixels as into
 * an empty one, written in place (the caller's pointer kept, every pixel
 * overwritten: the buffer starts poisoned with NaN), never freed (ASan
 * would see the caller's free as a double free). */
static void test_end_in_place(oit_capture *c, const char *name)
{
    quad_spec q[8];
    transparent_scene(q);
    oit_view v;
    scene_view(&v, 40, 24, OIT_SHADING_TRANSPARENT);
    oit_image a = {0}, given = {0};
    oit_frame_stats sa, sg;
    int one[2] = {0, 8};
    oit_error err = {0};
    if (!capture_scene(c, &v, q, one, 1, NULL, &a, &sa) ||
        oit_image_alloc(&given, v.width, v.height, &err) != OIT_OK) {
        test_failures++;
        oit_image_free(&a);
        return;
    }
    for (size_t i = 0; i < (size_t)v.width * v.height * 4; i++)
        given.rgba[i] = NAN;
    float *mine = given.rgba;
    if (capture_scene(c, &v, q, one, 1, NULL, &given, &sg)) {
        CHECK(given.rgba == mine && given.width == v.width && given.height == v.height,
              "%s: the given image was replaced", name);
        size_t off = 0; /* NaN differs from every value: a pixel left out counts */
        for (size_t i = 0; i < (size_t)v.width * v.height * 4; i++)
            off += !(given.rgba[i] == a.rgba[i]);
        CHECK(off == 0, "%s: written in place, %zu values differ from an allocated image",
              name, off);
    } else {
        test_failures++;
    }
    oit_image_free(&given);
    oit_image_free(&a);
}

static void test_equals_dfb(oit_capture *c, const char *name, int nq)
{
    quad_spec q[8];
    transparent_scene(q);
    shuffle_quads(q, nq, 4242u);
    oit_view v;
    scene_view(&v, 64, 48, OIT_SHADING_TRANSPARENT);
    oit_image a = {0}, b = {0};
    oit_frame_stats sa, sb;
    int one[2] = {0, nq};
    if (!capture_scene(c, &v, q, one, 1, NULL, &a, &sa) || !dfb_scene(&v, q, nq, &b, &sb)) {
        test_failures++;
        return;
    }
    double d = image_diff(&a, &b), h = hand_max_diff(&a, &v, q, nq);
    printf("%s one batch of %d quads vs DFB: max_abs_diff=%.6f vs hand=%.6f fragments=%llu/%llu "
           "max_layers=%u/%u overflow=%llu bytes=%llu ms=%.1f\n", name, nq, d, h,
           (unsigned long long)sa.fragments, (unsigned long long)sb.fragments, sa.max_layers,
           sb.max_layers, (unsigned long long)sa.overflow_pixels,
           (unsigned long long)sa.gpu_bytes_peak, sa.ms);
    CHECK(d <= 1.0 / 255 && h <= 1.0 / 255, "%s: capture differs from DFB/hand", name);
    CHECK(sa.fragments == sb.fragments && sa.max_layers == sb.max_layers, "%s: stats", name);
    CHECK(sa.overflow_pixels == 0 && sa.batches == 1, "%s: overflow/batches", name);
    oit_image_free(&a);
    oit_image_free(&b);
}

static void test_batches(oit_capture *c, const char *name, oit_shading_mode mode,
                         const quad_spec *q, int n, const int *start, int nb, int use_rects)
{
    oit_view v;
    scene_view(&v, 48, 40, mode);
    int (*rects)[4] = calloc((size_t)nb, sizeof *rects);
    for (int b = 0; b < nb; b++) /* tight rects */
        batch_rect(&v, q, start[b], start[b + 1], rects[b]);
    oit_image one = {0}, many = {0};
    oit_frame_stats s1, sn;
    int all[2] = {0, n};
    if (capture_scene(c, &v, q, all, 1, NULL, &one, &s1) &&
        capture_scene(c, &v, q, start, nb, use_rects ? (const int(*)[4])rects : NULL, &many, &sn)) {
        double d = image_diff(&one, &many), h = hand_max_diff(&many, &v, q, n);
        printf("%s %s: %d batches%s vs one: max_abs_diff=%.6f vs hand=%.6f fragments=%llu/%llu "
               "batches=%u\n", name,
               mode == OIT_SHADING_TRANSLUCENT ? "translucent" : "transparent", nb, use_rects ? " (tight rects)" : "", d, h,
               (unsigned long long)sn.fragments, (unsigned long long)s1.fragments, sn.batches);
        CHECK(d <= 1.0 / 255 && h <= 1.0 / 255, "%s: batched image differs", name);
        CHECK(sn.fragments == s1.fragments && sn.batches == (uint32_t)nb, "%s: stats", name);
        CHECK(sn.overflow_pixels == 0, "%s: overflow", name);
    } else {
        test_failures++;
    }
    free(rects);
    oit_image_free(&one);
    oit_image_free(&many);
}

static void test_overflow(oit_capture *c, int K, int extra, const char *name)
{
    /* K+extra equal quads on a rectangle, twice: every covered pixel
     * overflows once per batch; extra = 1 is the boundary (one fragment
     * more than the slots). */
    enum { MAXQ = 19 };
    quad_spec q[2 * MAXQ];
    int n = K + extra;
    for (int i = 0; i < 2 * n; i++)
        q[i] = mk(-2.0f - 0.25f * i, 0.43f * (2.0f + 0.25f * i), 200, 100, 50, 100, 1);
    oit_view v;
    scene_view(&v, 40, 40, OIT_SHADING_TRANSPARENT);
    uint64_t P = 0;
    for (int y = 0; y < v.height; y++)
        for (int x = 0; x < v.width; x++) {
            int cov = 0;
            for (int i = 0; i < n; i++) {
                double dx = (x + 0.5) / v.width * 2 - 1, dy = 1 - (y + 0.5) / v.height * 2;
                cov += fabs(dx * q[i].z) < q[i].half && fabs(dy * q[i].z) < q[i].half;
            }
            P += cov > K;
        }
    int start[3] = {0, n, 2 * n};
    oit_image img = {0};
    oit_frame_stats st;
    if (capture_scene(c, &v, q, start, 2, NULL, &img, &st)) {
        printf("%s overflow: K=%d quads/batch=%d P=%llu overflow_pixels=%llu (expect %llu) "
               "fragments=%llu max_layers=%u\n", name, K, n, (unsigned long long)P,
               (unsigned long long)st.overflow_pixels, (unsigned long long)(2 * P),
               (unsigned long long)st.fragments, st.max_layers);
        CHECK(P > 0 && st.overflow_pixels == 2 * P, "%s: overflow count", name);
        CHECK(st.max_layers == (uint32_t)(2 * n), "%s: max_layers counts dropped ones", name);
    } else {
        test_failures++;
    }
    oit_image_free(&img);
}

static void run_all(oit_capture *c, int K, const char *name)
{
    int nq = K < 8 ? K : 8;
    test_equals_dfb(c, name, nq);
    quad_spec q[8];
    transparent_scene(q);
    /* Batches of at most 3 quads, so K >= 4 never overflows. */
    int start[4] = {0, 2, 2 + (nq - 2) / 2, nq};
    test_batches(c, name, OIT_SHADING_TRANSPARENT, q, nq, start, 3, 0);
    test_batches(c, name, OIT_SHADING_TRANSPARENT, q, nq, start, 3, 1);
    /* Nested closed slabs, front to back; the outer slab's front and back
     * faces and the inner one's land in different batches. */
    quad_spec t[4] = {mk(-2.0f, 8.0f, 200, 120, 40, 255, 1), mk(-3.0f, 1.1f, 30, 90, 230, 255, 1),
                      mk(-4.5f, 1.7f, 30, 90, 230, 255, 0), mk(-6.0f, 20.0f, 200, 120, 40, 255, 0)};
    int tstart[4] = {0, 2, 3, 4};
    test_batches(c, name, OIT_SHADING_TRANSLUCENT, t, 4, tstart, 3, 1);
    test_overflow(c, K, 3, name);
    test_overflow(c, K, 1, name);
}

/* 24 quads of 5 sizes front to back: from 0 to 24 layers a pixel. */
static void deep_scene(quad_spec q[24])
{
    for (int i = 0; i < 24; i++) {
        float z = -1.5f - 0.4f * i;
        float half = (0.25f + 0.2f * (float)(i % 5)) * -z;
        q[i] = mk(z, half, (i * 71) % 256, (i * 37 + 90) % 256, 255 - i * 9, 50 + 7 * i, i % 4 != 2);
    }
}

/* A capture of kind with K slots a pixel, or NULL after a failed check
 * naming what it was for. */
static oit_capture *new_capture(oit_capture_kind kind, int K, const char *name)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    if (oit_capture_create(&(oit_capture_desc){.fill = capture_fill(kind),
                                               .cut = capture_cut(kind), .K = K},
        &c, &err) != OIT_OK) {
        CHECK(0, "%s: capture: %s", name, err.message);
        return NULL;
    }
    return c;
}

/* Pixels (by centre, as the rasterizer samples) covered by more than W of
 * the quads of batch [first, first + n). */
static uint64_t pixels_over(const oit_view *v, const quad_spec *q, int first, int n, int W)
{
    uint64_t P = 0;
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * v->width / v->height;
            double dy = 1 - (y + 0.5) / v->height * 2;
            int cov = 0;
            for (int i = first; i < first + n; i++)
                cov += fabs(dx * q[i].z) < q[i].half && fabs(dy * q[i].z) < q[i].half;
            P += cov > W;
        }
    return P;
}

typedef struct firstk_case {
    const char *name;
    oit_shading_mode mode;
    int nq, K;              /* quads of deep_scene, slots */
    int nb;                 /* batches: nq split evenly, front to back */
    uint64_t slot_budget;   /* 0: none */
    int W;                  /* the slots the capture must pick (0: counted fallback) */
    int min_draws;          /* the geometry draws the frame must at least make */
    int tiny;               /* 1: every other quad covers only the 4 centre pixels */
    uint64_t store_budget;  /* 0: the slot budget's; else one that holds every fragment */
} firstk_case;

/* Whether the case's stores are cut in bands: a slot budget that also
 * bounds the stores (none of their own). */
static int banded(const firstk_case *fc)
{
    return fc->slot_budget && !fc->store_budget;
}

/* The host's waits of a first frame (host_wait.h), by the capture's
 * structure: first-K reads each batch's totals back after pass 1, and the
 * fragments of each band of pass 2 (one band a second-pass batch unless a
 * slot budget splits it); the counted fallback reads each count's totals. */
static void check_waits(const firstk_case *fc, const oit_frame_stats *s)
{
    uint64_t one_band = (uint64_t)fc->nb + s->second_pass_packs;
    if (fc->W && !banded(fc))
        CHECK(s->host_waits == one_band, "%s: %u host waits, want %llu (%d batches, %u second "
              "passes)", fc->name, s->host_waits, (unsigned long long)one_band, fc->nb,
              s->second_pass_packs);
    else if (fc->W)
        CHECK(s->host_waits > one_band, "%s: %u host waits, want more than %llu (bands)",
              fc->name, s->host_waits, (unsigned long long)one_band);
    else
        CHECK(s->host_waits >= (uint32_t)fc->nb, "%s: %u host waits, want >= %d (counted)",
              fc->name, s->host_waits, fc->nb);
    CHECK(s->redraws == 0, "%s: the capture reports %u redraws", fc->name, s->redraws);
}

/* The same frame again with pass 2 driven by the GPU
 * (oit_capture_settings.no_wait): the first frame measured the need, so this
 * one fits it, waits 0 times where first-K ran within the slot budget, and
 * is still DFB's image, fragment for fragment. */
static void test_firstk_no_wait(oit_capture *c, const firstk_case *fc, const oit_view *v,
                                const quad_spec *q, const int *start, const oit_image *d,
                                const oit_frame_stats *sd, uint64_t want)
{
    CAPTURE_SET(c, no_wait, 1);
    oit_image a = {0};
    oit_frame_stats sa;
    if (!capture_scene(c, v, q, start, fc->nb, NULL, &a, &sa)) {
        test_failures++;
        return;
    }
    double diff = image_diff(&a, d);
    printf("first-k %s, no wait: vs DFB %.6f, %u host waits, short %d, second pass %llu "
           "pixels in %u packs\n", fc->name, diff, sa.host_waits, oit_capture_short(c),
           (unsigned long long)sa.second_pass_pixels, sa.second_pass_packs);
    CHECK(!oit_capture_short(c), "%s: no wait: the frame ended short", fc->name);
    CHECK(diff <= 1.0 / 255 && sa.fragments == sd->fragments,
          "%s: no wait: %.6f from DFB, fragments %llu/%llu", fc->name, diff,
          (unsigned long long)sa.fragments, (unsigned long long)sd->fragments);
    CHECK(sa.second_pass_pixels == want, "%s: no wait: second-pass pixels %llu, want %llu",
          fc->name, (unsigned long long)sa.second_pass_pixels, (unsigned long long)want);
    CHECK(!fc->W || banded(fc) || sa.host_waits == 0, "%s: no wait: %u host waits",
          fc->name, sa.host_waits);
    oit_image_free(&a);
    CAPTURE_SET(c, no_wait, 0);
}

static void test_firstk(const firstk_case *fc)
{
    oit_capture *c = new_capture(OIT_CAPTURE_FIRSTK, fc->K, fc->name);
    if (!c)
        return;
    CAPTURE_SET(c, slot_budget, fc->slot_budget);
    CAPTURE_SET(c, store_budget, fc->store_budget);
    quad_spec q[24];
    deep_scene(q);
    for (int i = 0; fc->tiny && i < 24; i += 2)
        q[i].half = 0.03f * -q[i].z;
    oit_view v;
    scene_view(&v, 48, 40, fc->mode);
    int start[5] = {0};
    uint64_t want = 0;
    for (int b = 1; b <= fc->nb; b++)
        start[b] = fc->nq * b / fc->nb;
    for (int b = 0; fc->W && b < fc->nb; b++)
        want += pixels_over(&v, q, start[b], start[b + 1] - start[b], fc->W);
    oit_image a = {0}, d = {0};
    oit_frame_stats sa, sd;
    if (capture_scene(c, &v, q, start, fc->nb, NULL, &a, &sa) && dfb_scene(&v, q, fc->nq, &d, &sd)) {
        double diff = image_diff(&a, &d), h = hand_max_diff(&a, &v, q, fc->nq);
        uint64_t draws = oit_capture_draw_calls(c);
        printf("first-k %s: %d quads in %d batches, K=%d: vs DFB %.6f, vs hand %.6f, fragments "
               "%llu/%llu, max_layers %u/%u, second pass %llu pixels (want %llu) in %u packs, "
               "%llu draws, overflow %llu\n", fc->name, fc->nq, fc->nb, fc->K, diff, h,
               (unsigned long long)sa.fragments, (unsigned long long)sd.fragments, sa.max_layers,
               sd.max_layers, (unsigned long long)sa.second_pass_pixels,
               (unsigned long long)want, sa.second_pass_packs, (unsigned long long)draws,
               (unsigned long long)sa.overflow_pixels);
        CHECK(diff <= 1.0 / 255 && h <= 1.0 / 255, "%s: image differs from DFB/hand", fc->name);
        /* a pixel composited twice or skipped changes the total */
        CHECK(sa.fragments == sd.fragments && sa.max_layers == sd.max_layers,
              "%s: fragments or max layers differ from DFB", fc->name);
        CHECK(sa.overflow_pixels == 0, "%s: overflow", fc->name);
        CHECK(sa.second_pass_pixels == want, "%s: second-pass pixels", fc->name);
        CHECK((sa.second_pass_packs > 0) == (want > 0), "%s: second-pass packs", fc->name);
        CHECK(draws >= (uint64_t)fc->min_draws, "%s: %llu draws, want >= %d", fc->name,
              (unsigned long long)draws, fc->min_draws);
        /* without overflow, first-K draws a batch once; counted packs
         * count it and store it, in bands of rows where its fragments
         * outgrow the store budget (the fallback's: 1 slot a pixel), in
         * one where a store budget of its own holds them */
        CHECK(want > 0 || (fc->W         ? draws == (uint64_t)fc->nb
                           : banded(fc) ? draws > (uint64_t)fc->nb * 2 + 2
                                        : draws == (uint64_t)fc->nb * 2),
              "%s: %llu draws without overflow", fc->name, (unsigned long long)draws);
        check_waits(fc, &sa);
        test_firstk_no_wait(c, fc, &v, q, start, &d, &sd, want);
    } else {
        test_failures++;
    }
    oit_image_free(&a);
    oit_image_free(&d);
    oit_capture_destroy(c);
}

/* deep_pixels (the pixels over K a batch, auto's hint for first-K) from
 * counted batches: the counted capture's, and the first-K backend's
 * switched off from its very first frame, whose counted half is set up
 * mid-frame (it once counted every covered pixel there, as if K were 0,
 * so a shallow view looked deep). */
static void test_deep_pixels(int firstk_off)
{
    const char *name = firstk_off ? "first-k switched off" : "counted";
    oit_capture *c = new_capture(firstk_off ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_COUNTED, 4, name);
    if (!c)
        return;
    if (firstk_off)
        oit_capture_set_first_k(c, 0);
    quad_spec q[24];
    deep_scene(q);
    oit_view v;
    scene_view(&v, 48, 40, OIT_SHADING_TRANSPARENT);
    int start[3] = {0, 10, 24};
    uint64_t want = pixels_over(&v, q, 0, 10, 4) + pixels_over(&v, q, 10, 14, 4);
    for (int frame = 0; frame < 2; frame++) {
        oit_image a = {0};
        oit_frame_stats sa;
        if (!capture_scene(c, &v, q, start, 2, NULL, &a, &sa)) {
            test_failures++;
            break;
        }
        printf("%s, frame %d: deep_pixels %llu (want %llu)\n", name, frame,
               (unsigned long long)sa.deep_pixels, (unsigned long long)want);
        CHECK(want > 0 && sa.deep_pixels == want, "%s, frame %d: deep_pixels %llu, want %llu",
              name, frame, (unsigned long long)sa.deep_pixels, (unsigned long long)want);
        oit_image_free(&a);
    }
    oit_capture_destroy(c);
}

static void test_firstk_all(void)
{
    const uint64_t two_slots = 48u * 40u * 16u * 2u; /* W = 2 over the frame */
    const uint64_t all = 48u * 40u * 16u * 24u;      /* every fragment of the frame */
    const firstk_case cases[] = {
        {"deep", OIT_SHADING_TRANSPARENT, 24, 4, 1, 0, 4, 2, 0, 0},
        {"deep K=16", OIT_SHADING_TRANSPARENT, 24, 16, 1, 0, 16, 2, 0, 0},
        {"deep batches", OIT_SHADING_TRANSPARENT, 24, 4, 3, 0, 4, 4, 0, 0},
        {"deep translucent", OIT_SHADING_TRANSLUCENT, 24, 4, 4, 0, 4, 5, 0, 0},
        /* the overflowed fragments exceed the budget: pass 2 in bands */
        {"bands", OIT_SHADING_TRANSPARENT, 24, 8, 1, two_slots, 2, 4, 0, 0},
        /* only the 4 centre pixels get more than 16 (24): a second pass
         * for 4 pixels */
        {"4 pixels over", OIT_SHADING_TRANSPARENT, 24, 16, 1, 0, 16, 2, 1, 0},
        {"shallow", OIT_SHADING_TRANSPARENT, 4, 4, 1, 0, 4, 1, 0, 0},
        {"shallow batches", OIT_SHADING_TRANSLUCENT, 12, 8, 3, 0, 8, 3, 0, 0},
        /* fewer than 2 slots fit: counted packs, still exact */
        {"fallback", OIT_SHADING_TRANSPARENT, 24, 8, 2, two_slots / 2, 0, 4, 0, 0},
        /* the stores apart from the slots (oit_capture_settings.store_budget):
         * the same slots, but pass 2 and the counted fallback each in one
         * band, no more waits and draws than that */
        {"bands, store apart", OIT_SHADING_TRANSPARENT, 24, 8, 1, two_slots, 2, 2, 0, all},
        {"fallback, store apart", OIT_SHADING_TRANSPARENT, 24, 8, 2, two_slots / 2, 0, 4, 0, all},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        test_firstk(&cases[i]);
}

/* One mesh whose fragments outgrow one storage buffer (a store limit of 2
 * layers a pixel against up to 24): the counted capture and first-K's second
 * pass store it in bands of rows, both still DFB's image and
 * fragment total; before, the counted capture refused such a mesh. */
static void test_store_limit(oit_capture_kind kind, const char *name)
{
    oit_capture *c = new_capture(kind, 4, name);
    if (!c)
        return;
    CAPTURE_SET(c, store_limit, 48u * 40u * 16u * 2u);
    quad_spec q[24];
    deep_scene(q);
    oit_view v;
    scene_view(&v, 48, 40, OIT_SHADING_TRANSPARENT);
    int start[2] = {0, 24};
    oit_image a = {0}, d = {0};
    oit_frame_stats sa, sd;
    if (capture_scene(c, &v, q, start, 1, NULL, &a, &sa) && dfb_scene(&v, q, 24, &d, &sd)) {
        double diff = image_diff(&a, &d), h = hand_max_diff(&a, &v, q, 24);
        uint64_t draws = oit_capture_draw_calls(c);
        printf("store limit %s: vs DFB %.6f, vs hand %.6f, fragments %llu/%llu, batches %u, "
               "%llu draws\n", name, diff, h, (unsigned long long)sa.fragments,
               (unsigned long long)sd.fragments, sa.batches, (unsigned long long)draws);
        CHECK(diff <= 1.0 / 255 && h <= 1.0 / 255, "%s: image differs from DFB/hand", name);
        CHECK(sa.fragments == sd.fragments && sa.max_layers == sd.max_layers,
              "%s: fragments or max layers differ from DFB", name);
        /* taken whole it would be 2 draws (count and store, or first-K's two passes) */
        CHECK(draws > 2, "%s: %llu draws: the mesh was not taken in pieces", name,
              (unsigned long long)draws);
    } else {
        test_failures++;
    }
    oit_image_free(&a);
    oit_image_free(&d);
    oit_capture_destroy(c);
}

/* Early termination at E = 0.05 over nq deep layers (K slots hold them
 * all, so the reference keeps every fragment: which fragments win an
 * overflowing pixel's slots is up to the order of atomics, undefined across
 * primitives). The reference, at E = 0, is DFB's image and fragment total;
 * in one batch nothing is saturated before it, so the capture keeps every
 * fragment and its image at E = 0; in 4 batches front to back the later
 * ones drop the fragments of pixels the earlier saturated, and the image
 * stays within E of the exact one. */
static void test_epsilon_batches(oit_capture_kind kind, int K, int nq, const char *name)
{
    oit_capture *c = new_capture(kind, K, name);
    if (!c)
        return;
    quad_spec q[24];
    deep_scene(q);
    for (int i = 0; i < nq; i++)
        q[i].rgba[3] = 200; /* saturates after a few layers */
    oit_view v;
    scene_view(&v, 48, 40, OIT_SHADING_TRANSPARENT);
    int one[2] = {0, nq}, four[5] = {0, nq / 4, nq / 2, 3 * nq / 4, nq};
    oit_image ex = {0}, dfb = {0}, e1 = {0}, e4 = {0};
    oit_frame_stats sx, sd, s1, s4;
    int ok = capture_scene(c, &v, q, one, 1, NULL, &ex, &sx) && dfb_scene(&v, q, nq, &dfb, &sd);
    CAPTURE_SET(c, epsilon, 0.05f);
    ok = ok && capture_scene(c, &v, q, one, 1, NULL, &e1, &s1) &&
         capture_scene(c, &v, q, four, 4, NULL, &e4, &s4);
    if (ok) {
        double dx = image_diff(&ex, &dfb), d1 = image_diff(&e1, &ex), d4 = image_diff(&e4, &dfb);
        printf("epsilon %s: E = 0 %llu/%llu fragments (DFB), %u layers, %llu overflow, diff %.6f; "
               "one batch %llu (diff %.6f), four batches %llu (diff %.6f)\n", name,
               (unsigned long long)sx.fragments, (unsigned long long)sd.fragments, sd.max_layers,
               (unsigned long long)sx.overflow_pixels, dx, (unsigned long long)s1.fragments, d1,
               (unsigned long long)s4.fragments, d4);
        CHECK(sd.max_layers == (uint32_t)nq && sx.overflow_pixels == 0 &&
                  sx.fragments == sd.fragments && dx <= 1.0 / 255,
              "%s: the reference: %u layers, %llu overflow pixels, %llu of DFB's %llu "
              "fragments, %.6f from DFB", name, sd.max_layers,
              (unsigned long long)sx.overflow_pixels, (unsigned long long)sx.fragments,
              (unsigned long long)sd.fragments, dx);
        CHECK(s1.fragments == sx.fragments && d1 == 0.0,
              "%s: a frame's first batch dropped fragments", name);
        CHECK(s4.fragments < sx.fragments, "%s: later batches dropped nothing", name);
        CHECK(d4 <= 0.05 + 1.0 / 255, "%s: %.6f from exact, over E", name, d4);
    } else {
        test_failures++;
    }
    oit_image_free(&ex);
    oit_image_free(&dfb);
    oit_image_free(&e1);
    oit_image_free(&e4);
    oit_capture_destroy(c);
}

/* deep_scene with each quad given another's size: per pixel more
 * fragments here and fewer there, about as many in all. */
static void moved_scene(quad_spec q[24])
{
    deep_scene(q);
    for (int i = 0; i < 24; i++)
        q[i].half = (0.25f + 0.2f * (float)((i + 2) % 5)) * -q[i].z;
}

/* One frame of q against DFB's: exact, fragment for fragment; unless
 * want_predicted < 0 (a first frame), without waits, not short, and every
 * batch drawn predicted where want_predicted, none where 0; a batch in
 * bands where want_bands. */
static void predicted_frame(oit_capture *c, const char *name, const char *what,
                            const quad_spec *q, int want_predicted, int want_bands)
{
    oit_view v;
    scene_view(&v, 48, 40, OIT_SHADING_TRANSPARENT);
    int start[3] = {0, 10, 24};
    oit_image a = {0}, d = {0};
    oit_frame_stats sa, sd;
    int ok = capture_scene(c, &v, q, start, 2, NULL, &a, &sa);
    /* a first frame may end short (first-K's pass 2 store): the stream
     * draws it again */
    if (ok && want_predicted < 0 && oit_capture_short(c))
        ok = capture_scene(c, &v, q, start, 2, NULL, &a, &sa);
    if (!ok || !dfb_scene(&v, q, 24, &d, &sd)) {
        test_failures++;
        oit_image_free(&a);
        return;
    }
    double diff = image_diff(&a, &d);
    printf("%s, %s: vs DFB %.6f, fragments %llu/%llu, batches %u, predicted %u, host waits "
           "%u, short %d\n", name, what, diff, (unsigned long long)sa.fragments,
           (unsigned long long)sd.fragments, sa.batches, sa.predicted_batches, sa.host_waits,
           oit_capture_short(c));
    CHECK(want_bands == 0 || sa.batches > 2, "%s, %s: %u batches, want bands", name, what,
          sa.batches);
    CHECK(diff <= 1.0 / 255 && sa.fragments == sd.fragments,
          "%s, %s: %.6f from DFB, fragments %llu/%llu", name, what, diff,
          (unsigned long long)sa.fragments, (unsigned long long)sd.fragments);
    CHECK(want_predicted < 0 || (sa.predicted_batches == (want_predicted ? 2u : 0u) &&
                                 sa.host_waits == 0 && !oit_capture_short(c)),
          "%s, %s: %u batches predicted (want 2), %u host waits, short %d", name, what,
          sa.predicted_batches, sa.host_waits, oit_capture_short(c));
    oit_image_free(&a);
    oit_image_free(&d);
}

/* Counted batches of a view drawn again at the offsets its last frame
 * counted: the same scene (every fragment where it was: one pass), then
 * another under the same view (pixels that got more spill into the
 * second pass, those that got fewer leave holes), in one band a batch and
 * in bands past a small storage binding (not under a small slot budget,
 * which the store takes whole: nothing predicted, still exact); and
 * predicted from first-K's counts, its pass 1 counting every fragment. A spill lost or composited
 * twice changes the image and the fragment total. */
static void test_predicted(oit_capture_kind kind, uint64_t budget, uint64_t limit,
                           const char *name)
{
    oit_capture *c = new_capture(kind, 4, name);
    if (!c)
        return;
    CAPTURE_SET(c, slot_budget, budget);
    CAPTURE_SET(c, store_limit, limit);
    CAPTURE_SET(c, no_wait, 1);
    quad_spec a[24], b[24];
    deep_scene(a);
    moved_scene(b);
    /* bands under the slot budget leave no room for predictions: the
     * store takes it all */
    int bands = budget || limit, predicted = !budget;
    predicted_frame(c, name, "first frame", a, -1, 0);
    if (kind == OIT_CAPTURE_FIRSTK) { /* as the stream's auto switches */
        oit_capture_ready_counted(c);
        oit_capture_set_first_k(c, 0);
    }
    predicted_frame(c, name, "the same again", a, predicted, bands);
    predicted_frame(c, name, "another scene", b, predicted, bands);
    predicted_frame(c, name, "back again", a, predicted, bands);
    oit_capture_destroy(c);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    oit_capture *c = NULL;
    if (oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_ARRAY,
                                               .cut = OIT_RENDER_PACK_BUDGET, .K = 8},
                           &c, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: array capture: %s\n", err.message);
        return 1;
    }
    run_all(c, 8, "array K=8");
    oit_capture_destroy(c);

    oit_status s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_STENCIL,
                                                          .cut = OIT_RENDER_PACK_BUDGET, .K = 4},
                                      &c, &err);
    int stencil_ok = s == OIT_OK;
    if (s == OIT_ERR_GL) {
        printf("stencil K=4: refused by the driver: %s\n", err.message);
        CHECK(err.message[0] != '\0', "stencil refused without a reason");
    } else if (s == OIT_OK) {
        printf("stencil K=4: self-test passed\n");
        run_all(c, 4, "stencil K=4");
        oit_capture_destroy(c);
    } else {
        CHECK(0, "stencil capture: %s", err.message);
    }
    s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_STENCIL,
                                               .cut = OIT_RENDER_PACK_BUDGET, .K = 64 / 4},
        &c, &err);
    printf("stencil K=16: %s: %s\n", oit_status_name(s), s == OIT_OK ? "" : err.message);
    oit_capture_destroy(s == OIT_OK ? c : NULL);

    oit_capture *a = NULL;
    CHECK(oit_capture_create(&(oit_capture_desc){.cut = OIT_RENDER_PACK_BUDGET, .K = 4},
                             &a, &err) == OIT_OK, "auto: %s", err.message);
    if (a) {
        int chose_stencil = oit_capture_backend(a) == OIT_CAPTURE_STENCIL;
        printf("auto K=4 chose %s\n", chose_stencil ? "stencil" : "array");
        CHECK(chose_stencil == stencil_ok, "auto disagrees with the stencil self-test");
        run_all(a, 4, "auto K=4");
        oit_capture_destroy(a);
    }
    test_firstk_all();
    test_deep_pixels(0);
    test_deep_pixels(1);
    for (int kind = 0; kind < 2; kind++) {
        oit_capture *e = NULL;
        oit_capture_kind k = kind ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_COUNTED;
        CHECK(oit_capture_create(&(oit_capture_desc){.fill = capture_fill(k),
                                                     .cut = capture_cut(k), .K = 8},
                                 &e, &err) == OIT_OK, "%s", err.message);
        if (e)
            test_end_in_place(e, kind ? "first-k" : "counted");
        oit_capture_destroy(e);
    }
    test_store_limit(OIT_CAPTURE_COUNTED, "counted");
    test_store_limit(OIT_CAPTURE_FIRSTK, "first-k");
    test_epsilon_batches(OIT_CAPTURE_ARRAY, 16, 16, "array");
    test_epsilon_batches(OIT_CAPTURE_COUNTED, 8, 24, "counted");
    test_predicted(OIT_CAPTURE_COUNTED, 0, 0, "predicted");
    test_predicted(OIT_CAPTURE_COUNTED, 0, 48u * 40u * 16u * 3u, "predicted in bands");
    test_predicted(OIT_CAPTURE_COUNTED, 48u * 40u * 16u * 3u, 0, "bands under a budget");
    test_predicted(OIT_CAPTURE_FIRSTK, 0, 0, "predicted from first-k");
    return test_gl_verdict(gl);
}
