/* The compute capture (view/render/capture/capture_compute.h) against DFB and against
 * compositing by hand (tests/lib/gl_test_scene.h): one batch of shuffled
 * quads (image, fragment total and deepest pixel); front-to-back batches
 * with tight rects, transparent and translucent (a closed slab split
 * across batches); a batch's rect cutting its quads (nothing outside it
 * touched); 300 and 1200 layers on most pixels, the latter past the 65535
 * loop iterations llvmpipe runs an invocation (every fragment composited,
 * in order: the count equals DFB's and the image the hand result); early termination
 * (the exact number of fragments a saturated pixel drops, and the image
 * within epsilon); a batch too large for one storage binding, its records
 * in several blocks, and one too large for all blocks, captured in halves
 * of its meshes or (one mesh) refused with the numbers. Again with tile lists one entry long (every tile takes the
 * overflowed list's path: all records swept), and with the driver taken
 * for one that runs loops to their end (no read-back: a shallow frame is
 * exact, a deep one fails at its end rather than render short, and the
 * frames after it resume). Every buffer starts poisoned (OIT_GL_POISON). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "tests/lib/gl_test_dfb.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/capture_set.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

/* Set while a failure is what the test wants: capture_scene stays quiet. */
static int expect_failure;

/* Captures q in batches [start[i], start[i+1]) (rects[i] or the frame). */
static int capture_scene(oit_capture *c, const oit_view *v, const quad_spec *q, const int *start,
                         int nb, const int (*rects)[4], oit_image *img, oit_frame_stats *st)
{
    oit_error err = {0};
    oit_status s = capture_quads(c, v, q, start, nb, rects, img, st, &err);
    if (s != OIT_OK && !expect_failure)
        fprintf(stderr, "FAIL: compute capture: %s\n", err.message);
    if (s != OIT_OK && expect_failure)
        printf("failed as expected: %s\n", err.message);
    return s == OIT_OK;
}

/* n quads front to back from z = -1.5, every 'big'-th covering the frame,
 * the others of 5 sizes, colours and alphas varying, facing either way. */
static void stack_scene(quad_spec *q, int n, float dz, int alpha)
{
    for (int i = 0; i < n; i++) {
        float z = -1.5f - dz * (float)i;
        float half = (i % 4 == 0 ? 3.0f : 0.3f + 0.15f * (float)(i % 5)) * -z;
        q[i] = mk(z, half, (i * 71) % 256, (i * 37 + 90) % 256, 255 - (i * 9) % 200,
                  alpha ? alpha : 40 + (i * 13) % 180, i % 3 != 2);
    }
}

/* One batch of shuffled quads: DFB's image, fragment total and deepest
 * pixel, and the hand result. */
static void test_one_batch(oit_capture *c)
{
    quad_spec q[12];
    stack_scene(q, 12, 0.6f, 0);
    shuffle_quads(q, 12, 777u);
    oit_view v;
    scene_view(&v, 64, 48, OIT_SHADING_TRANSPARENT);
    oit_image a = {0}, b = {0};
    oit_frame_stats sa, sb;
    int one[2] = {0, 12};
    if (capture_scene(c, &v, q, one, 1, NULL, &a, &sa) && dfb_scene(&v, q, 12, &b, &sb)) {
        double d = image_diff(&a, &b), h = hand_max_diff(&a, &v, q, 12);
        printf("one batch: vs DFB %.6f, vs hand %.6f, fragments %llu/%llu, layers %u/%u\n", d, h,
               (unsigned long long)sa.fragments, (unsigned long long)sb.fragments, sa.max_layers,
               sb.max_layers);
        CHECK(d <= 1.0 / 255 && h <= 1.0 / 255, "one batch: %.6f from DFB, %.6f from hand", d, h);
        CHECK(sa.fragments == sb.fragments && sa.max_layers == sb.max_layers,
              "one batch: %llu fragments, %u layers; DFB %llu, %u",
              (unsigned long long)sa.fragments, sa.max_layers, (unsigned long long)sb.fragments,
              sb.max_layers);
        CHECK(sa.capture && !strcmp(sa.capture, "compute") && sa.overflow_pixels == 0,
              "one batch: stats say %s, %llu overflow", sa.capture ? sa.capture : "(none)",
              (unsigned long long)sa.overflow_pixels);
    } else {
        test_failures++;
    }
    oit_image_free(&a);
    oit_image_free(&b);
}

/* The scene in batches front to back, each over its quads' footprint: the
 * state carried across batches gives the hand result. */
static void test_batches(oit_capture *c, oit_shading_mode mode, const quad_spec *q,
                         const int *start, int nb)
{
    const char *name = mode == OIT_SHADING_TRANSLUCENT ? "translucent" : "transparent";
    oit_view v;
    scene_view(&v, 48, 40, mode);
    int rects[8][4];
    for (int b = 0; b < nb; b++) {
        batch_rect(&v, q, start[b], start[b + 1], rects[b]);
    }
    oit_image img = {0};
    oit_frame_stats st;
    if (capture_scene(c, &v, q, start, nb, (const int(*)[4])rects, &img, &st)) {
        double h = hand_max_diff(&img, &v, q, start[nb]);
        printf("%s, %d batches in tight rects: vs hand %.6f, batches %u\n", name, nb, h,
               st.batches);
        CHECK(h <= 1.0 / 255 && st.batches == (uint32_t)nb, "%s batches: %.6f from hand", name, h);
    } else {
        test_failures++;
    }
    oit_image_free(&img);
}

/* A rect cutting the quads: inside it the hand result, outside the
 * background alone. */
static void test_rect_cut(oit_capture *c)
{
    quad_spec q[6];
    stack_scene(q, 6, 0.5f, 0);
    oit_view v;
    scene_view(&v, 40, 40, OIT_SHADING_TRANSPARENT);
    const int rect[1][4] = {{7, 5, 29, 33}};
    int one[2] = {0, 6};
    oit_image img = {0};
    oit_frame_stats st;
    if (!capture_scene(c, &v, q, one, 1, rect, &img, &st)) {
        test_failures++;
        return;
    }
    double worst = 0.0;
    for (int y = 0; y < v.height; y++)
        for (int x = 0; x < v.width; x++) {
            int in = x >= rect[0][0] && x < rect[0][2] && y >= rect[0][1] && y < rect[0][3];
            double rgb[3];
            hand_pixel(&v, q, in ? 6 : 0, x, y, rgb);
            for (int ch = 0; ch < 3; ch++)
                worst = fmax(worst, fabs(img.rgba[4 * ((size_t)y * v.width + x) + ch] - rgb[ch]));
        }
    printf("rect cutting the quads: %.6f from hand\n", worst);
    CHECK(worst <= 1.0 / 255, "rect: %.6f from hand (fragments outside the rect?)", worst);
    oit_image_free(&img);
}

/* N layers on most pixels of a w x h frame in nb batches (1, or 2: front
 * half, then back half), submitted shuffled within each. At 300 a pixel
 * needs 19 sweeps; at 1200 in one batch, 75 sweeps over 2400 triangles,
 * past the 65535 loop iterations llvmpipe runs an invocation (its pixels
 * are resumed: test_no_probe shows they are cut). */
static void test_deep(oit_capture *c, int N, int w, int h, int nb)
{
    quad_spec *q = malloc(sizeof *q * (size_t)N);
    if (!q) {
        test_failures++;
        return;
    }
    stack_scene(q, N, 0.01f, 0);
    for (int i = 0; i < N; i++)
        q[i].half = (i % 10 == 3 ? 0.2f : 3.0f) * -q[i].z; /* most cover the frame */
    for (int i = 0; i < N; i++)
        q[i].rgba[3] = (uint8_t)(3 + i % 5); /* the last layers still show */
    shuffle_quads(q, N / 2, 99u);
    shuffle_quads(q + N / 2, N / 2, 98u);
    oit_view v;
    scene_view(&v, w, h, OIT_SHADING_TRANSPARENT);
    int two[3] = {0, N / 2, N}, one[2] = {0, N};
    oit_image a = {0}, b = {0};
    oit_frame_stats sa, sb;
    if (capture_scene(c, &v, q, nb == 1 ? one : two, nb, NULL, &a, &sa) &&
        dfb_scene(&v, q, N, &b, &sb)) {
        double d = image_diff(&a, &b), h = hand_max_diff(&a, &v, q, N);
        printf("deep, %d batches: vs DFB %.6f, vs hand %.6f, fragments %llu/%llu, layers %u/%u\n", nb, d, h,
               (unsigned long long)sa.fragments, (unsigned long long)sb.fragments, sa.max_layers,
               sb.max_layers);
        CHECK(sb.max_layers == (uint32_t)N && sa.max_layers == (uint32_t)N, "deep: %u layers (DFB %u), want %d",
              sa.max_layers, sb.max_layers, N);
        CHECK(sa.fragments == sb.fragments, "deep: %llu fragments, DFB %llu: some lost",
              (unsigned long long)sa.fragments, (unsigned long long)sb.fragments);
        CHECK(d <= 1.0 / 255 && h <= 1.0 / 255, "deep: %.6f from DFB, %.6f from hand", d, h);
    } else {
        test_failures++;
    }
    free(q);
    oit_image_free(&a);
    oit_image_free(&b);
}

/* quads q[0..N) as M meshes of N/M quads captured in ONE batch (16x16,
 * transparent), against DFB: image, fragments and layers. */
static void meshes_vs_dfb(oit_capture *c, const quad_spec *q, int N, int M, const char *what)
{
    oit_triangle *tris = q ? scene_tris(q, N) : NULL;
    oit_view v;
    scene_view(&v, 16, 16, OIT_SHADING_TRANSPARENT);
    oit_error err = {0};
    oit_gpu_mesh **m = calloc((size_t)M, sizeof *m);
    oit_status s = tris && m ? OIT_OK : OIT_ERR_NOMEM;
    for (int i = 0; s == OIT_OK && i < M; i++)
        s = oit_gpu_mesh_create(tris + 2 * (N / M) * i, 2 * (N / M), 2u * (uint32_t)((N / M) * i),
                                &m[i], &err);
    oit_image a = {0}, b = {0};
    oit_frame_stats sa, sb;
    if (s == OIT_OK)
        s = oit_capture_begin(c, &v, &err);
    if (s == OIT_OK)
        s = oit_capture_batch(c, (const oit_gpu_mesh *const *)m, M, NULL, &err);
    if (s == OIT_OK)
        s = oit_capture_end(c, &a, &sa, &err);
    CHECK(s == OIT_OK, "%s: %s", what, err.message);
    if (s == OIT_OK && dfb_scene(&v, q, N, &b, &sb)) {
        double d = image_diff(&a, &b);
        printf("%s: vs DFB %.6f, fragments %llu/%llu, layers %u/%u\n", what, d,
               (unsigned long long)sa.fragments, (unsigned long long)sb.fragments,
               sa.max_layers, sb.max_layers);
        CHECK(d <= 1.0 / 255 && sa.fragments == sb.fragments && sa.max_layers == sb.max_layers,
              "%s: %.6f from DFB, %llu fragments (DFB %llu)", what, d,
              (unsigned long long)sa.fragments, (unsigned long long)sb.fragments);
    }
    for (int i = 0; m && i < M; i++)
        oit_gpu_mesh_destroy(m[i]);
    free(m);
    free(tris);
    oit_image_free(&a);
    oit_image_free(&b);
}

/* One batch of 300 layers in 10 meshes, front to back, with one storage
 * binding capped at 8 KiB (oit_capture_settings.store_limit): the 96 000
 * bytes of records exceed what 8 blocks of 8 KiB hold, so they go in
 * halves of the meshes (each in 6 blocks), and the image, fragment total
 * and depth stay DFB's. */
static void test_split(oit_capture *c)
{
    enum { N = 300, M = 10 };
    quad_spec *q = malloc(sizeof *q * N);
    if (q)
        stack_scene(q, N, 0.01f, 7);
    CAPTURE_SET(c, store_limit, 8 << 10);
    meshes_vs_dfb(c, q, N, M, "split under an 8 KiB binding");
    CAPTURE_SET(c, store_limit, 0);
    free(q);
}

/* One mesh whose records outgrow a binding capped at 32 KiB: its 600
 * triangles (96 000 bytes) span 3 record blocks, shuffled so that a
 * pixel's fragments come from all of them; every fragment composited in
 * order (test_deep's checks). Under 4 KiB, 8 blocks hold fewer than 600
 * records: refused, naming the numbers. */
static void test_blocks(oit_capture *c)
{
    printf("-- records in blocks of 32 KiB\n");
    CAPTURE_SET(c, store_limit, 32 << 10);
    test_deep(c, 300, 24, 20, 1);
    enum { N = 300 };
    quad_spec *q = malloc(sizeof *q * N);
    oit_triangle *tris = q ? scene_tris((stack_scene(q, N, 0.01f, 7), q), N) : NULL;
    oit_view v;
    scene_view(&v, 16, 16, OIT_SHADING_TRANSPARENT);
    oit_error err = {0};
    oit_gpu_mesh *m = NULL;
    oit_status s = tris ? oit_gpu_mesh_create(tris, 2 * N, 0, &m, &err) : OIT_ERR_NOMEM;
    CAPTURE_SET(c, store_limit, 4 << 10);
    if (s == OIT_OK)
        s = oit_capture_begin(c, &v, &err);
    const oit_gpu_mesh *list[1] = {m};
    if (s == OIT_OK)
        s = oit_capture_batch(c, list, 1, NULL, &err);
    printf("600 triangles under 4 KiB bindings: %s\n", err.message);
    CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "600 triangles take 96000 bytes"),
          "blocks: a batch past its blocks gave %d: %s", (int)s, err.message);
    CAPTURE_SET(c, store_limit, 0);
    oit_image img = {0};
    oit_frame_stats st;
    if (s == OIT_OK)
        oit_capture_end(c, &img, &st, &err);
    oit_image_free(&img);
    oit_gpu_mesh_destroy(m);
    free(tris);
    free(q);
}

/* Epsilon: a front batch of one near-opaque quad over the middle of
 * the frame (T = 5/255 < E behind it), then 8 quads covering everything.
 * The second batch must drop exactly its fragments on the saturated
 * pixels, keep all others, and stay within E of the exact image. */
/* Where the driver cuts long shader loops (llvmpipe), one sweep of a tile
 * whose list holds ~300K triangles cannot finish: a batch of several meshes
 * that large must be captured in halves (OIT_COMPUTE_CUT_BATCH), not
 * refused. 8 meshes of 40,000 quads, all in the frame's one tile: 8 large,
 * the rest tiny (covering no pixel centre), against DFB. */
static void test_cut_batch(oit_capture *c)
{
    enum { N = 160000, M = 8 };
    quad_spec *q = malloc(sizeof *q * N);
    if (q) {
        stack_scene(q, 8, 0.3f, 0);
        for (int i = 8; i < N; i++)
            q[i] = mk(-1.0f - (float)i / N, 1e-4f, i % 256, 80, 160, 100, i % 2);
    }
    meshes_vs_dfb(c, q, N, M, "320000 triangles in one tile, 8 meshes");
    free(q);
}

static void test_epsilon(oit_capture *c)
{
    quad_spec q[9];
    q[0] = mk(-1.5f, 1.5f, 250, 30, 30, 250, 1);
    for (int i = 1; i < 9; i++)
        q[i] = mk(-2.0f - 0.3f * (float)i, 3.0f * (2.0f + 0.3f * (float)i), 20 * i, 200, 90, 120,
                  i % 2);
    oit_view v;
    scene_view(&v, 40, 32, OIT_SHADING_TRANSPARENT);
    int two[3] = {0, 1, 9};
    int front[4];
    footprint(&v, &q[0], front);
    uint64_t covered = (uint64_t)(front[2] - front[0]) * (uint64_t)(front[3] - front[1]);
    uint64_t pixels = (uint64_t)v.width * v.height;
    oit_image ex = {0}, ep = {0};
    oit_frame_stats sx, se;
    int ok = capture_scene(c, &v, q, two, 2, NULL, &ex, &sx);
    CAPTURE_SET(c, epsilon, 0.05f);
    ok = ok && capture_scene(c, &v, q, two, 2, NULL, &ep, &se);
    CAPTURE_SET(c, epsilon, 0.0f);
    if (ok) {
        uint64_t want = covered + (pixels - covered) * 8;
        double d = image_diff(&ep, &ex);
        printf("epsilon 0.05: fragments %llu (exact %llu, expected %llu), %.6f from exact\n",
               (unsigned long long)se.fragments, (unsigned long long)sx.fragments,
               (unsigned long long)want, d);
        CHECK(sx.fragments == covered + pixels * 8, "epsilon: exact frame has %llu fragments",
              (unsigned long long)sx.fragments);
        CHECK(se.fragments == want, "epsilon: %llu fragments, want %llu",
              (unsigned long long)se.fragments, (unsigned long long)want);
        CHECK(d <= 0.05 + 1.0 / 255, "epsilon: %.6f from exact", d);
    } else {
        test_failures++;
    }
    oit_image_free(&ex);
    oit_image_free(&ep);
}

/* The scene of test_deep(N = 1200, 8 x 8) in one batch: its pixels need
 * more loop iterations than llvmpipe runs an invocation. */
static int deep_frame(oit_capture *c)
{
    enum { N = 1200 };
    quad_spec *q = malloc(sizeof *q * N);
    if (!q)
        return 0;
    stack_scene(q, N, 0.01f, 3);
    oit_view v;
    scene_view(&v, 8, 8, OIT_SHADING_TRANSPARENT);
    int one[2] = {0, N};
    oit_image img = {0};
    oit_frame_stats st;
    int ok = capture_scene(c, &v, q, one, 1, NULL, &img, &st);
    oit_image_free(&img);
    free(q);
    return ok;
}

/* The compute capture (K = 8) with the test faults given planted; NULL,
 * the failure counted and named (what: which capture), when it cannot be
 * made. */
static oit_capture *compute_capture(unsigned faults, const char *what)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    if (oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_COMPUTE, .K = 8,
                                               .faults = faults},
                           &c, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: compute capture%s: %s\n", what, err.message);
        test_failures++;
        return NULL;
    }
    return c;
}

/* Tile lists one entry long and never grown: every tile's list
 * overflows, so every tile finds its triangles among all the batch's
 * records; the images, counts and depths stay DFB's and the hand's. */
static void test_list_overflow(void)
{
    oit_capture *c = compute_capture(OIT_CAPTURE_TEST_COMPUTE_LIST_SHORT, ", short lists");
    if (!c)
        return;
    printf("-- tile lists one entry long\n");
    test_one_batch(c);
    quad_spec q[8];
    stack_scene(q, 8, 0.7f, 0);
    int start[4] = {0, 2, 5, 8};
    test_batches(c, OIT_SHADING_TRANSPARENT, q, start, 3);
    test_rect_cut(c);
    test_deep(c, 1200, 8, 8, 1);
    test_epsilon(c);
    test_blocks(c);
    test_cut_batch(c);
    oit_capture_destroy(c);
}

/* The driver taken for one that runs loops to their end: a shallow frame
 * reads nothing back and is exact; llvmpipe cuts the deep frame's loops
 * short, which its end must report (never an image short of fragments);
 * the frames after it read back and are exact again. */
static void test_no_probe(void)
{
    oit_capture *c = compute_capture(OIT_CAPTURE_TEST_COMPUTE_NO_PROBE, ", no probe");
    if (!c)
        return;
    printf("-- no loop probe\n");
    test_one_batch(c);
    expect_failure = 1;
    int ok = deep_frame(c);
    expect_failure = 0;
    CHECK(!ok, "no probe: the deep frame's cut loops went unreported");
    test_deep(c, 1200, 8, 8, 1);
    oit_capture_destroy(c);
}

int main(void)
{
    setenv("OIT_GL_POISON", "1", 1);
    oit_gl *gl = test_gl_open();
    oit_capture *c = compute_capture(0, "");
    if (!c)
        return 1;
    CHECK(oit_capture_backend(c) == OIT_CAPTURE_COMPUTE, "backend");
    test_one_batch(c);
    quad_spec q[8];
    stack_scene(q, 8, 0.7f, 0);
    int start[4] = {0, 2, 5, 8};
    test_batches(c, OIT_SHADING_TRANSPARENT, q, start, 3);
    /* Nested closed slabs, front to back; the outer slab's front and back
     * faces and the inner one's land in different batches. */
    quad_spec t[4] = {mk(-2.0f, 8.0f, 200, 120, 40, 255, 1), mk(-3.0f, 1.1f, 30, 90, 230, 255, 1),
                      mk(-4.5f, 1.7f, 30, 90, 230, 255, 0), mk(-6.0f, 20.0f, 200, 120, 40, 255, 0)};
    int tstart[4] = {0, 2, 3, 4};
    test_batches(c, OIT_SHADING_TRANSLUCENT, t, tstart, 3);
    test_rect_cut(c);
    test_deep(c, 300, 24, 20, 2);
    test_deep(c, 1200, 8, 8, 2);
    test_deep(c, 1200, 8, 8, 1);
    test_epsilon(c);
    test_split(c);
    test_blocks(c);
    test_cut_batch(c);
    oit_capture_destroy(c);
    test_list_overflow();
    test_no_probe();
    return test_gl_verdict(gl);
}
