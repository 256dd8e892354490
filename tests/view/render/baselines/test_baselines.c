/* The baseline methods against DFB (the exact in-core method, itself tested
 * against hand results in test_dfb.c) and against the hand result of
 * gl_test_scene.h: PLL, paged PLL, B3D, depth peeling and dual depth
 * peeling must match within 1/255 (the peelers only without depth ties);
 * guarded OIT and F2B must match at threshold 0 (F2B where its primitive
 * order is the depth order) and stay within what their thresholds promise
 * otherwise, while doing less work on deep, nearly opaque scenes; unsorted
 * blending must be right only when the order happens to be back to front;
 * WBOIT's error is printed and bounded loosely. Every figure is printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/lib/gl_test_scene.h"
#include "view/render/capture/dfb.h"
#include "view/render/baselines/methods.h"
#include "view/render/baselines/f2b.h"
#include "view/render/gl/gl_context.h"
#include "view/render/reference/reference.h"
#include "view/render/baselines/guarded.h"
#include "view/render/image/image.h"
#include "view/render/baselines/ppll.h"
#include "view/render/baselines/ppll4.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

#define TOL (1.0 / 255)
/* WBOIT's error against DFB, measured on llvmpipe: quads12 max 0.089 rmse
 * 0.0141, shapes max 0.161 rmse 0.0103. The bounds (about 2x) only catch a
 * broken method (NaN or inf from overflow, a frame far from DFB). */
#define WBOIT_MAX_BOUND 0.3
#define WBOIT_RMSE_BOUND 0.03

enum method {
    M_DFB, M_PLL, M_PPLL4, M_B3D, M_DP, M_DDP, M_GUARDED, M_F2B, M_WBOIT, M_UNSORTED, M_N
};
/* Every method through its table (view/render/method.h), each made once and
 * kept across frames as the tools keep them. */
static const oit_method *const tables[M_N] = {
    &oit_method_dfb, &oit_method_pll,     &oit_method_ppll4, &oit_method_b3d,
    &oit_method_dp,  &oit_method_ddp,     &oit_method_guarded, &oit_method_f2b,
    &oit_method_wboit, &oit_method_unsorted};
static const char *method_name(enum method which) { return tables[which]->name; }

typedef struct methods {
    void *impl[M_N];
} methods;

typedef struct result {
    oit_image img;
    oit_frame_stats st;
    int ok;
} result;

static result render(methods *m, enum method which, const oit_triangle *tris, size_t count,
                     const oit_view *v)
{
    result r = {0};
    oit_error err = {0};
    oit_gpu_mesh *mesh = NULL;
    oit_status s = oit_gpu_mesh_create(tris, count, 0, &mesh, &err);
    if (s == OIT_OK) {
        oit_method_frame f = {.gpu = mesh, .view = v, .out = &r.img, .stats = &r.st};
        s = tables[which]->render(m->impl[which], &f, &err);
    }
    oit_gpu_mesh_destroy(mesh);
    r.ok = s == OIT_OK;
    CHECK(r.ok, "%s: %s", method_name(which), err.message);
    return r;
}

static oit_image_diff compare(const result *a, const result *b)
{
    oit_image_diff d = {0};
    oit_error err = {0};
    d.max_abs = INFINITY;
    d.rmse = INFINITY;
    if (a->ok && b->ok && oit_image_compare(&a->img, &b->img, &d, NULL, 0, &err) != OIT_OK)
        CHECK(0, "compare: %s", err.message);
    return d;
}

/* Renders with 'which' and DFB; prints the difference and the figures and
 * returns it. Exact methods must also report DFB's fragment count. */
static oit_image_diff versus_dfb(methods *m, enum method which, const char *scene,
                                 const oit_triangle *tris, size_t count, const oit_view *v,
                                 oit_frame_stats *st_out, oit_frame_stats *dfb_out)
{
    result ref = render(m, M_DFB, tris, count, v);
    result r = render(m, which, tris, count, v);
    oit_image_diff d = compare(&r, &ref);
    printf("%-9s %-26s %dx%d max_abs=%.6f rmse=%.6f fragments=%llu (dfb %llu) "
           "max_layers=%u (dfb %u) passes=%u gpu_bytes=%llu (dfb %llu) ms=%.1f\n",
           method_name(which), scene, v->width, v->height, d.max_abs, d.rmse,
           (unsigned long long)r.st.fragments, (unsigned long long)ref.st.fragments,
           r.st.max_layers, ref.st.max_layers, r.st.batches,
           (unsigned long long)r.st.gpu_bytes_peak, (unsigned long long)ref.st.gpu_bytes_peak,
           r.st.ms);
    if (st_out)
        *st_out = r.st;
    if (dfb_out)
        *dfb_out = ref.st;
    oit_image_free(&r.img);
    oit_image_free(&ref.img);
    return d;
}

/* PLL and DP equal DFB, fragment for fragment, and the hand result where
 * the scene is quads. */
static void check_exact(methods *m, enum method which, const char *scene,
                        const oit_triangle *tris, size_t count, const oit_view *v,
                        const quad_spec *q, int nq)
{
    oit_frame_stats st, ref;
    oit_image_diff d = versus_dfb(m, which, scene, tris, count, v, &st, &ref);
    CHECK(d.max_abs <= TOL, "%s on %s: differs from DFB by %.6f", method_name(which), scene,
          d.max_abs);
    CHECK(st.fragments == ref.fragments, "%s on %s: %llu fragments, DFB %llu",
          method_name(which), scene, (unsigned long long)st.fragments,
          (unsigned long long)ref.fragments);
    CHECK(st.max_layers == ref.max_layers, "%s on %s: max_layers %u, DFB %u",
          method_name(which), scene, st.max_layers, ref.max_layers);
    CHECK(st.gpu_bytes_peak > 0, "%s: no gpu_bytes_peak", method_name(which));
    if (!q)
        return;
    result r = render(m, which, tris, count, v);
    double hand = r.ok ? hand_max_diff(&r.img, v, q, nq) : INFINITY;
    printf("%-9s %-26s vs hand max_abs=%.6f\n", method_name(which), scene, hand);
    CHECK(hand <= TOL, "%s on %s: differs from the hand result by %.6f", method_name(which),
          scene, hand);
    oit_image_free(&r.img);
}

/* n quads at distinct depths, shrinking to the back so that pixels see
 * 1..n layers; colours and alphas vary. */
static quad_spec *quad_stack(int n, float z0, float dz)
{
    quad_spec *q = calloc((size_t)n, sizeof *q);
    for (int i = 0; q && i < n; i++) {
        q[i].z = z0 - dz * (float)i;
        q[i].half = 0.3f + 4.0f * (float)i / (float)n * (-q[i].z) / 10.0f;
        q[i].rgba[0] = (uint8_t)(40 + 37 * i % 200);
        q[i].rgba[1] = (uint8_t)(220 - 53 * i % 180);
        q[i].rgba[2] = (uint8_t)(60 + 91 * i % 190);
        q[i].rgba[3] = (uint8_t)(50 + 29 * i % 120);
        q[i].front = i % 3 != 1;
    }
    return q;
}

/* ---- closed interlocking shapes ---- */

static void put_tri(oit_triangle *t, const float a[3], const float b[3], const float c[3],
                    const uint8_t rgba[4])
{
    const float *p[3] = {a, b, c};
    for (int k = 0; k < 3; k++) {
        memcpy(t->v[k].pos, p[k], sizeof t->v[k].pos);
        memcpy(t->v[k].rgba, rgba, 4);
    }
}

/* 12 triangles, counter-clockwise seen from outside. */
static int add_box(oit_triangle *t, const float c[3], const float h[3], const uint8_t rgba[4])
{
    int n = 0;
    for (int a = 0; a < 3; a++)
        for (int s = -1; s <= 1; s += 2) {
            int u = (a + 1) % 3, w = (a + 2) % 3;
            if (s < 0) {
                int tmp = u;
                u = w;
                w = tmp;
            }
            float q[4][3];
            const float su[4] = {-1, 1, 1, -1}, sw[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; k++) {
                memcpy(q[k], c, sizeof q[k]);
                q[k][a] += (float)s * h[a];
                q[k][u] += su[k] * h[u];
                q[k][w] += sw[k] * h[w];
            }
            put_tri(&t[n++], q[0], q[1], q[2], rgba);
            put_tri(&t[n++], q[0], q[2], q[3], rgba);
        }
    return n;
}

/* 8 triangles, counter-clockwise seen from outside. */
static int add_octahedron(oit_triangle *t, const float c[3], float r, const uint8_t rgba[4])
{
    int n = 0;
    for (int i = 0; i < 8; i++) {
        float s[3] = {i & 1 ? -1.0f : 1.0f, i & 2 ? -1.0f : 1.0f, i & 4 ? -1.0f : 1.0f};
        float p[3][3];
        for (int k = 0; k < 3; k++) {
            memcpy(p[k], c, sizeof p[k]);
            p[k][k] += s[k] * r;
        }
        if (s[0] * s[1] * s[2] > 0)
            put_tri(&t[n++], p[0], p[1], p[2], rgba);
        else
            put_tri(&t[n++], p[0], p[2], p[1], rgba);
    }
    return n;
}

/* Two boxes and two octahedra passing through each other, so that the
 * per-pixel order changes across the image (no painter's order exists).
 * No two faces are coplanar: that would be a depth tie, where depth
 * peeling rightly loses fragments (test_ties). */
static size_t shapes_scene(oit_triangle *t)
{
    static const uint8_t red[4] = {220, 60, 40, 110}, green[4] = {50, 200, 80, 140},
                         blue[4] = {40, 90, 230, 90}, gold[4] = {230, 190, 40, 160};
    size_t n = 0;
    n += (size_t)add_box(t + n, (const float[3]){0.0f, 0.0f, -6.0f},
                         (const float[3]){1.7f, 0.9f, 1.1f}, red);
    n += (size_t)add_box(t + n, (const float[3]){0.45f, 0.25f, -6.3f},
                         (const float[3]){0.6f, 1.65f, 0.75f}, green);
    n += (size_t)add_octahedron(t + n, (const float[3]){-0.7f, -0.15f, -5.8f}, 1.45f, blue);
    n += (size_t)add_octahedron(t + n, (const float[3]){1.1f, -0.35f, -6.9f}, 1.3f, gold);
    return n;
}

/* ---- tests ---- */

static oit_status methods_create(methods *m, oit_error *err)
{
    oit_status s = OIT_OK;
    for (int i = 0; i < M_N && s == OIT_OK; i++)
        s = tables[i]->create(NULL, NULL, &m->impl[i], err);
    return s;
}

static void methods_destroy(methods *m)
{
    for (int i = 0; i < M_N; i++)
        if (m->impl[i])
            tables[i]->destroy(m->impl[i]);
}

/* m: a fresh instance of every method; 0 after a failed check, m then
 * holding none. */
static int methods_open(methods *m)
{
    oit_error err = {0};
    *m = (methods){0};
    if (methods_create(m, &err) == OIT_OK)
        return 1;
    CHECK(0, "create: %s", err.message);
    methods_destroy(m);
    *m = (methods){0};
    return 0;
}

/* The scene most tests start from: 12 quads of quad_stack (z from -2, 0.7
 * apart) shuffled with seed, their triangles in *tris (free both) and the
 * 96x64 transparent view of them in *v. */
enum { QUADS12 = 12 };
static quad_spec *quads12(uint32_t seed, oit_triangle **tris, oit_view *v)
{
    quad_spec *q = quad_stack(QUADS12, -2.0f, 0.7f);
    shuffle_quads(q, QUADS12, seed);
    *tris = scene_tris(q, QUADS12);
    scene_view(v, 96, 64, OIT_SHADING_TRANSPARENT);
    return q;
}

/* The methods that store every fragment, and so are exact with ties too
 * and with translucent shading. */
static const enum method storing[] = {M_PLL, M_PPLL4, M_B3D};
#define N_STORING (int)(sizeof storing / sizeof storing[0])

/* n full-frame quads at distinct depths, shuffled: n layers on every
 * pixel. alpha 0 keeps quad_stack's varied alphas. */
static quad_spec *full_stack(int n, float dz, uint8_t alpha, uint32_t seed)
{
    quad_spec *q = quad_stack(n, -1.0f, dz);
    for (int i = 0; q && i < n; i++) {
        q[i].half = 30.0f;
        if (alpha)
            q[i].rgba[3] = alpha;
    }
    if (q)
        shuffle_quads(q, n, seed);
    return q;
}

static void test_exact_quads(methods *m)
{
    const int n = QUADS12;
    oit_triangle *tris;
    oit_view v;
    quad_spec *q = quads12(0x2545f491u, &tris, &v);
    for (int i = 0; i < N_STORING; i++)
        check_exact(m, storing[i], "quads12 shuffled", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_DP, "quads12 shuffled", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_DDP, "quads12 shuffled", tris, 2 * (size_t)n, &v, q, n);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSLUCENT);
    for (int i = 0; i < N_STORING; i++)
        check_exact(m, storing[i], "quads12 translucent", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_DP, "quads12 translucent", tris, 2 * (size_t)n, &v, q, n);
    free(tris);
    free(q);
}

/* Dual peeling composites the back half back to front, where translucent
 * absorption is not defined: it must refuse, not draw something else. */
static void test_ddp_translucent(methods *m)
{
    quad_spec q = {-3.0f, 1.0f, {200, 100, 50, 128}, 1};
    oit_triangle tris[2];
    quad_tris(&q, tris);
    oit_view v;
    scene_view(&v, 32, 32, OIT_SHADING_TRANSLUCENT);
    oit_error err = {0};
    oit_gpu_mesh *mesh = NULL;
    oit_image img = {0};
    oit_status s = oit_gpu_mesh_create(tris, 2, 0, &mesh, &err);
    oit_method_frame f = {.gpu = mesh, .view = &v, .out = &img};
    if (s == OIT_OK)
        s = oit_method_ddp.render(m->impl[M_DDP], &f, &err);
    printf("ddp translucent: status %d: %s\n", (int)s, err.message);
    CHECK(s == OIT_ERR_UNSUPPORTED, "ddp should refuse translucent shading, got %d", (int)s);
    oit_image_free(&img);
    oit_gpu_mesh_destroy(mesh);
}

/* Dual depth peeling cannot order fragments whose keys tie (dual_peel.h):
 * it must equal DFB on every pixel where the Embree reference finds no tie
 * or near tie (reference.h), and lose no more than those fragments. */
static void check_loses_only_ties(methods *m, enum method which, const char *scene,
                                  const oit_triangle *tris, size_t count, const oit_view *v)
{
    size_t np = (size_t)v->width * v->height;
    uint32_t *ties = calloc(np, sizeof *ties);
    oit_mesh mesh = {(oit_triangle *)tris, count, count, {0}};
    oit_reference_desc rd = {0};
    rd.ties = ties;
    oit_image ref_img = {0};
    oit_error err = {0};
    CHECK(ties && oit_reference_render(&mesh, v, &rd, &ref_img, NULL, NULL, &err) == OIT_OK,
          "reference on %s: %s", scene, err.message);
    result ref = render(m, M_DFB, tris, count, v), r = render(m, which, tris, count, v);
    uint64_t tied = 0, tie_pixels = 0;
    double worst = 0.0;
    for (size_t p = 0; ties && p < np; p++) {
        tied += ties[p];
        tie_pixels += ties[p] > 0;
        for (int c = 0; c < 3 && !ties[p] && r.ok && ref.ok; c++)
            worst = fmax(worst, fabs(r.img.rgba[p * 4 + c] - ref.img.rgba[p * 4 + c]));
    }
    uint64_t lost = ref.st.fragments - r.st.fragments;
    printf("%-9s %-26s ties: %llu fragments on %llu pixels, lost %llu, max_abs elsewhere %.6f\n",
           method_name(which), scene, (unsigned long long)tied, (unsigned long long)tie_pixels,
           (unsigned long long)lost, worst);
    CHECK(worst <= TOL, "%s on %s: differs from DFB by %.6f where nothing ties",
          method_name(which), scene, worst);
    CHECK(lost <= tied, "%s on %s: lost %llu fragments, only %llu tie", method_name(which),
          scene, (unsigned long long)lost, (unsigned long long)tied);
    oit_image_free(&r.img);
    oit_image_free(&ref.img);
    oit_image_free(&ref_img);
    free(ties);
}

static void test_exact_shapes(methods *m)
{
    oit_triangle tris[48];
    size_t n = shapes_scene(tris);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    for (int i = 0; i < N_STORING; i++)
        check_exact(m, storing[i], "shapes", tris, n, &v, NULL, 0);
    check_exact(m, M_DP, "shapes", tris, n, &v, NULL, 0);
    check_loses_only_ties(m, M_DDP, "shapes", tris, n, &v);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSLUCENT);
    for (int i = 0; i < N_STORING; i++)
        check_exact(m, storing[i], "shapes translucent", tris, n, &v, NULL, 0);
    check_exact(m, M_DP, "shapes translucent", tris, n, &v, NULL, 0);
    /* Different shapes must actually overlap, or the test shows nothing. */
    oit_frame_stats st;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    versus_dfb(m, M_DFB, "shapes (dfb itself)", tris, n, &v, &st, NULL);
    CHECK(st.max_layers >= 6, "shapes: only %u layers", st.max_layers);
}

static uint64_t capacity(const methods *m, enum method which)
{
    return which == M_PLL ? oit_pll_capacity(m->impl[M_PLL]) : oit_ppll4_capacity(m->impl[M_PPLL4]);
}

/* PLL's nodes or PPLL4's pages, on a fresh instance: frame 1 has one layer
 * over a sixth of the frame and fits the initial pool (one fragment slot per
 * pixel: a page per four pixels for PPLL4); frame 2 has 40 and must overflow
 * it, grow it and be drawn again, still exact. */
static void test_growth(enum method which)
{
    const char *name = method_name(which);
    methods m;
    if (!methods_open(&m))
        return;
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    quad_spec one = {-3.0f, 1.5f, {200, 100, 50, 128}, 1};
    oit_triangle tris1[2];
    quad_tris(&one, tris1);
    check_exact(&m, which, "growth frame 1", tris1, 2, &v, &one, 1);
    result r1 = render(&m, which, tris1, 2, &v);
    oit_frame_stats st1 = r1.st;
    uint64_t cap1 = capacity(&m, which);
    oit_image_free(&r1.img);
    const int n = 40;
    quad_spec *q = full_stack(n, 0.25f, 0, 77u);
    oit_triangle *tris2 = scene_tris(q, n);
    result r2 = render(&m, which, tris2, 2 * (size_t)n, &v);
    oit_frame_stats st2 = r2.st;
    uint64_t cap2 = capacity(&m, which);
    double hand = r2.ok ? hand_max_diff(&r2.img, &v, q, n) : INFINITY;
    printf("%s growth: frame 1 fragments=%llu passes=%u capacity=%llu bytes=%llu; frame 2 "
           "fragments=%llu layers=%u passes=%u capacity=%llu bytes=%llu vs hand max_abs=%.6f\n",
           name, (unsigned long long)st1.fragments, st1.batches, (unsigned long long)cap1,
           (unsigned long long)st1.gpu_bytes_peak, (unsigned long long)st2.fragments,
           st2.max_layers, st2.batches, (unsigned long long)cap2,
           (unsigned long long)st2.gpu_bytes_peak, hand);
    CHECK(st1.batches == 1, "%s: frame 1 should fit the first pool", name);
    CHECK(st2.batches == 2, "%s: frame 2 should have overflowed and been drawn again", name);
    CHECK(st2.fragments == 40ull * 96 * 64, "%s: frame 2: %llu fragments", name,
          (unsigned long long)st2.fragments);
    CHECK(st2.max_layers == 40, "%s: frame 2: max_layers %u", name, st2.max_layers);
    CHECK(cap2 >= st2.fragments && cap2 > cap1, "%s: pool did not grow", name);
    CHECK(hand <= TOL, "%s: frame 2 differs from the hand result by %.6f", name, hand);
    oit_image_free(&r2.img);
    /* The next frame of that size fits at once. */
    result r3 = render(&m, which, tris2, 2 * (size_t)n, &v);
    CHECK(r3.st.batches == 1, "%s: frame 3 drew %u passes", name, r3.st.batches);
    oit_image_free(&r3.img);
    free(tris2);
    free(q);
    methods_destroy(&m);
}

static void test_unsorted(methods *m)
{
    const int n = 10;
    quad_spec *q = quad_stack(n, -2.0f, 0.8f);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    /* quad_stack is front to back; reversed it is the painter's order. */
    quad_spec *back = malloc(sizeof *back * (size_t)n);
    for (int i = 0; i < n; i++)
        back[i] = q[n - 1 - i];
    oit_triangle *t_front = scene_tris(q, n), *t_back = scene_tris(back, n);
    shuffle_quads(back, n, 1234u);
    oit_triangle *t_shuf = scene_tris(back, n);
    oit_image_diff d_back = versus_dfb(m, M_UNSORTED, "quads10 back-to-front", t_back,
                                       2 * (size_t)n, &v, NULL, NULL);
    oit_image_diff d_front = versus_dfb(m, M_UNSORTED, "quads10 front-to-back", t_front,
                                        2 * (size_t)n, &v, NULL, NULL);
    oit_image_diff d_shuf = versus_dfb(m, M_UNSORTED, "quads10 shuffled", t_shuf,
                                       2 * (size_t)n, &v, NULL, NULL);
    CHECK(d_back.max_abs <= TOL, "painter's order should be right: %.6f", d_back.max_abs);
    CHECK(d_front.max_abs > 0.1, "front-to-back should be wrong by > 0.1: %.6f",
          d_front.max_abs);
    CHECK(d_shuf.max_abs > 0.05, "shuffled should be wrong by > 0.05: %.6f", d_shuf.max_abs);
    quad_spec single = {-3.0f, 1.5f, {30, 160, 220, 150}, 1};
    oit_triangle t1[2];
    quad_tris(&single, t1);
    oit_image_diff d1 = versus_dfb(m, M_UNSORTED, "single layer", t1, 2, &v, NULL, NULL);
    CHECK(d1.max_abs <= TOL, "single layer should be right: %.6f", d1.max_abs);
    free(t_front);
    free(t_back);
    free(t_shuf);
    free(back);
    free(q);
}

static void check_wboit(methods *m, const char *scene, const oit_triangle *tris, size_t n,
                        const oit_view *v)
{
    oit_frame_stats st, ref;
    oit_image_diff d = versus_dfb(m, M_WBOIT, scene, tris, n, v, &st, &ref);
    CHECK(isfinite(d.max_abs) && d.max_abs < WBOIT_MAX_BOUND, "wboit on %s: max %.6f",
          scene, d.max_abs);
    CHECK(isfinite(d.rmse) && d.rmse < WBOIT_RMSE_BOUND, "wboit on %s: rmse %.6f", scene,
          d.rmse);
    CHECK(st.fragments == ref.fragments, "wboit on %s: %llu fragments, DFB %llu", scene,
          (unsigned long long)st.fragments, (unsigned long long)ref.fragments);
}

static void test_wboit(methods *m)
{
    const int n = QUADS12;
    oit_triangle *tris;
    oit_view v;
    quad_spec *q = quads12(99u, &tris, &v);
    check_wboit(m, "quads12 shuffled", tris, 2 * (size_t)n, &v);
    oit_triangle shapes[48];
    size_t ns = shapes_scene(shapes);
    check_wboit(m, "shapes", shapes, ns, &v);
    free(tris);
    free(q);
}

/* 100 layers: PLL (long lists, past the 32 sorted in registers) and DP
 * exact; PLL's and DFB's storage grows with the depth, DP's does not. */
/* 100 layers on every pixel: the storing methods (long lists, past the 32
 * sorted in registers), DP and DDP exact, with max_layers 100 and every
 * fragment counted; the storing methods' and DFB's memory grows with the
 * depth, the peelers' does not, and DDP needs half DP's passes. */
static void test_deep(void)
{
    enum { SHALLOW, DEEP };
    static const enum method all[] = {M_DFB, M_PLL, M_PPLL4, M_B3D, M_DP, M_DDP};
    enum { N_ALL = sizeof all / sizeof all[0] };
    methods m;
    if (!methods_open(&m))
        return;
    const uint64_t px = 96 * 64;
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    quad_spec *q[2] = {full_stack(3, 1.0f, 0, 1u), full_stack(100, 0.1f, 0, 4242u)};
    oit_triangle *t[2] = {scene_tris(q[0], 3), scene_tris(q[1], 100)};
    oit_frame_stats st[2][N_ALL];
    for (int i = 0; i < N_ALL; i++)
        versus_dfb(&m, all[i], "3 layers (bytes)", t[SHALLOW], 6, &v, &st[SHALLOW][i], NULL);
    for (int i = 1; i < N_ALL; i++)
        check_exact(&m, all[i], "100 layers", t[DEEP], 200, &v, q[DEEP], 100);
    for (int i = 0; i < N_ALL; i++) {
        versus_dfb(&m, all[i], "100 layers (bytes)", t[DEEP], 200, &v, &st[DEEP][i], NULL);
        printf("gpu_bytes_peak 3 -> 100 layers: %-8s %llu -> %llu (passes %u)\n",
               method_name(all[i]), (unsigned long long)st[SHALLOW][i].gpu_bytes_peak,
               (unsigned long long)st[DEEP][i].gpu_bytes_peak, st[DEEP][i].batches);
        CHECK(st[DEEP][i].max_layers == 100 && st[DEEP][i].fragments == 100 * px,
              "%s: 100 full-frame quads gave max_layers %u, %llu fragments",
              method_name(all[i]), st[DEEP][i].max_layers,
              (unsigned long long)st[DEEP][i].fragments);
    }
    /* Per fragment: DFB 16 bytes, PLL 20, PPLL4 17, B3D 16 per pixel-layer. */
    static const unsigned growth[N_ALL] = {16, 20, 17, 16, 0, 0};
    for (int i = 0; i < N_ALL; i++) {
        uint64_t lo = st[SHALLOW][i].gpu_bytes_peak, hi = st[DEEP][i].gpu_bytes_peak;
        if (growth[i])
            CHECK(hi >= lo + 90ull * px * growth[i], "%s bytes did not grow with depth",
                  method_name(all[i]));
        else
            CHECK(hi == lo, "%s bytes grew with depth", method_name(all[i]));
    }
    CHECK(st[DEEP][4].batches == 101, "dp drew %u passes for 100 layers", st[DEEP][4].batches);
    CHECK(st[DEEP][5].batches == 51, "ddp drew %u passes for 100 layers", st[DEEP][5].batches);
    for (int k = 0; k < 2; k++) {
        free(t[k]);
        free(q[k]);
    }
    methods_destroy(&m);
}

/* Pixels inside the smaller of test_ties' coplanar quads. */
static uint64_t tied_pixels(const oit_view *v)
{
    uint64_t tied = 0;
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * v->width / v->height;
            double dy = 1 - (y + 0.5) / v->height * 2;
            tied += fabs(dx * 3.0) < 0.6 && fabs(dy * 3.0) < 0.6;
        }
    return tied;
}

/* Coplanar quads: dual depth peeling keeps one fragment of each tie and
 * loses the rest, exactly the pixels both cover; the storing methods and
 * depth peeling (which peels in (key, prim) order) keep them all. */
static void test_ties(methods *m)
{
    quad_spec q[3] = {{-3.0f, 1.2f, {200, 40, 40, 120}, 1},
                      {-3.0f, 0.6f, {40, 200, 40, 120}, 1},
                      {-5.0f, 3.0f, {40, 40, 200, 120}, 0}};
    oit_triangle *tris = scene_tris(q, 3);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    for (int i = 0; i < N_STORING; i++)
        check_exact(m, storing[i], "coplanar ties", tris, 6, &v, q, 3);
    check_exact(m, M_DP, "coplanar ties", tris, 6, &v, q, 3);
    uint64_t tied = tied_pixels(&v);
    static const enum method peelers[] = {M_DDP};
    for (int i = 0; i < 1; i++) {
        const char *name = method_name(peelers[i]);
        oit_frame_stats st, ref;
        oit_image_diff d = versus_dfb(m, peelers[i], "coplanar ties", tris, 6, &v, &st, &ref);
        printf("%s on ties: lost %llu fragments (expect %llu), max_abs=%.6f\n", name,
               (unsigned long long)(ref.fragments - st.fragments), (unsigned long long)tied,
               d.max_abs);
        CHECK(ref.fragments - st.fragments == tied, "%s should lose exactly the tied "
              "fragments", name);
        CHECK(d.max_abs > 0.05, "%s should differ where fragments tie: %.6f", name, d.max_abs);
    }
    free(tris);
}

/* ---- the approximate methods ---- */

static void check_threshold_range(methods *m)
{
    oit_error err = {0};
    static const float bad[] = {-0.01f, 1.0f, NAN};
    for (int i = 0; i < 3; i++) {
        CHECK(oit_guarded_set_threshold(m->impl[M_GUARDED], bad[i], &err) == OIT_ERR_ARGUMENT,
              "guarded accepted threshold %g", (double)bad[i]);
        CHECK(oit_f2b_set_threshold(m->impl[M_F2B], bad[i], &err) == OIT_ERR_ARGUMENT,
              "f2b accepted threshold %g", (double)bad[i]);
    }
    printf("threshold range: %s\n", err.message);
}

static void set_threshold(methods *m, enum method which, float threshold)
{
    oit_error err = {0};
    oit_status s = which == M_GUARDED ? oit_guarded_set_threshold(m->impl[M_GUARDED], threshold, &err)
                                      : oit_f2b_set_threshold(m->impl[M_F2B], threshold, &err);
    CHECK(s == OIT_OK, "%s: threshold %g: %s", method_name(which), (double)threshold,
          err.message);
}

/* Guarded OIT. Threshold 0 culls nothing: PLL, exact, every fragment. At
 * the default, on 40 nearly opaque full-frame layers in shuffled order, it
 * must cull (store fewer fragments, a shorter longest list) and each culled
 * fragment may move its pixel by less than the threshold: at most
 * (layers - 1) culled per pixel, since the first fragment drawn is always
 * stored. Where no guard can fall below the threshold it must cull
 * nothing. */
static void test_guarded(methods *m)
{
    const int n = QUADS12;
    oit_triangle *tris, shapes[48];
    oit_view v;
    quad_spec *q = quads12(0x2545f491u, &tris, &v);
    size_t ns = shapes_scene(shapes);
    quad_spec *deep = full_stack(40, 0.25f, 247, 99u);
    oit_triangle *td = scene_tris(deep, 40);
    set_threshold(m, M_GUARDED, 0.0f);
    check_exact(m, M_GUARDED, "quads12 threshold 0", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_GUARDED, "shapes threshold 0", shapes, ns, &v, NULL, 0);
    check_exact(m, M_GUARDED, "opaque40 threshold 0", td, 80, &v, deep, 40);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSLUCENT);
    check_exact(m, M_GUARDED, "quads12 translucent thr 0", tris, 2 * (size_t)n, &v, q, n);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    set_threshold(m, M_GUARDED, OIT_GUARDED_DEFAULT_THRESHOLD);
    oit_frame_stats st, ref;
    oit_image_diff d = versus_dfb(m, M_GUARDED, "quads12 default", tris, 2 * (size_t)n, &v,
                                  &st, &ref);
    CHECK(d.max_abs <= (ref.max_layers - 1) * OIT_GUARDED_DEFAULT_THRESHOLD + TOL,
          "guarded on quads12: max_abs %.6f", d.max_abs);
    d = versus_dfb(m, M_GUARDED, "opaque40 default", td, 80, &v, &st, &ref);
    double bound = (ref.max_layers - 1) * OIT_GUARDED_DEFAULT_THRESHOLD + TOL;
    printf("guarded opaque40: stored %.1f%% of %llu fragments, error bound %.4f\n",
           100.0 * (double)st.fragments / (double)ref.fragments,
           (unsigned long long)ref.fragments, bound);
    CHECK(ref.max_layers == 40, "opaque40: dfb max_layers %u", ref.max_layers);
    CHECK(d.max_abs <= bound, "guarded on opaque40: max_abs %.6f above %.6f", d.max_abs,
          bound);
    CHECK(st.fragments < ref.fragments / 2, "guarded culled too little: %llu of %llu stored",
          (unsigned long long)st.fragments, (unsigned long long)ref.fragments);
    CHECK(st.max_layers < ref.max_layers, "guarded: longest list %u", st.max_layers);
    /* At alpha 230/255 the least importance a guard can see is
     * a (1 - a)^2 = 0.0087, above the default: nothing may be culled. */
    quad_spec *mid = full_stack(40, 0.25f, 230, 5u);
    oit_triangle *tm = scene_tris(mid, 40);
    d = versus_dfb(m, M_GUARDED, "alpha0.9 x40 default", tm, 80, &v, &st, &ref);
    CHECK(st.fragments == ref.fragments && d.max_abs <= TOL, "guarded culled fragments of "
          "importance above the threshold: %llu of %llu stored, max_abs %.6f",
          (unsigned long long)st.fragments, (unsigned long long)ref.fragments, d.max_abs);
    /* Drawn nearest, farthest, middle: the newest stored node is then
     * behind the middle one and must not guard it. */
    quad_spec hks[3] = {{-2.0f, 30.0f, {200, 60, 40, 77}, 1},
                        {-4.0f, 30.0f, {40, 60, 200, 255}, 1},
                        {-3.0f, 30.0f, {60, 200, 40, 128}, 1}};
    oit_triangle t3[6];
    for (int i = 0; i < 3; i++)
        quad_tris(&hks[i], &t3[2 * i]);
    d = versus_dfb(m, M_GUARDED, "guard behind default", t3, 6, &v, &st, &ref);
    CHECK(st.fragments == ref.fragments && d.max_abs <= TOL, "guarded culled a fragment "
          "with a node behind it as its guard: max_abs %.6f", d.max_abs);
    free(tm);
    free(mid);
    free(tris);
    free(q);
    free(td);
    free(deep);
}

/* Fresh instances, so the pools are what this scene makes them: on 40
 * nearly opaque layers guarded OIT's pool must end smaller than PLL's
 * (the paper's point: culled fragments take no memory). */
static void test_guarded_memory(void)
{
    methods m;
    quad_spec *deep = full_stack(40, 0.25f, 247, 99u);
    oit_triangle *td = scene_tris(deep, 40);
    if (methods_open(&m)) {
        oit_view v;
        scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
        oit_frame_stats g, p;
        versus_dfb(&m, M_GUARDED, "opaque40 fresh pool", td, 80, &v, &g, NULL);
        versus_dfb(&m, M_PLL, "opaque40 fresh pool", td, 80, &v, &p, NULL);
        printf("opaque40 pools: guarded %llu bytes (%u passes), pll %llu bytes\n",
               (unsigned long long)g.gpu_bytes_peak, g.batches,
               (unsigned long long)p.gpu_bytes_peak);
        CHECK(g.gpu_bytes_peak < p.gpu_bytes_peak * 3 / 4, "guarded's pool (%llu bytes) is "
              "not smaller than PLL's (%llu)", (unsigned long long)g.gpu_bytes_peak,
              (unsigned long long)p.gpu_bytes_peak);
    }
    methods_destroy(&m);
    free(td);
    free(deep);
}

/* Per pixel, F2B (threshold thr) against DFB: where the hand result's
 * final transmittance stays at or above thr nothing can have been
 * discarded, so those pixels are exact; elsewhere the error is below thr. */
static void check_f2b_pixels(methods *m, const char *scene, const quad_spec *q, int n,
                             const oit_view *v, float thr)
{
    oit_triangle *tris = scene_tris(q, n);
    result a = render(m, M_F2B, tris, 2 * (size_t)n, v), ref = render(m, M_DFB, tris,
                                                                        2 * (size_t)n, v);
    double worst[2] = {0.0, 0.0}; /* pixels kept exact, pixels that may discard */
    uint64_t count[2] = {0, 0};
    for (int y = 0; a.ok && ref.ok && y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            hand_state h;
            hand_begin(&h);
            hand_add(&h, v, q, n, x, y);
            int k = h.T[0] < thr;
            const float *p = &a.img.rgba[4 * ((size_t)y * v->width + x)];
            const float *r = &ref.img.rgba[4 * ((size_t)y * v->width + x)];
            for (int c = 0; c < 3; c++)
                worst[k] = fmax(worst[k], fabs(p[c] - r[c]));
            count[k]++;
        }
    printf("f2b %-22s thr=%.3f exact pixels %llu max_abs=%.6f, discarding pixels %llu "
           "max_abs=%.6f, fragments %llu (dfb %llu)\n", scene, (double)thr,
           (unsigned long long)count[0], worst[0], (unsigned long long)count[1], worst[1],
           (unsigned long long)a.st.fragments, (unsigned long long)ref.st.fragments);
    CHECK(count[0] > 0 && worst[0] <= TOL, "f2b %s: pixels above the threshold differ by "
          "%.6f", scene, worst[0]);
    CHECK(worst[1] <= thr + TOL, "f2b %s: error %.6f above the threshold", scene, worst[1]);
    if (thr == 0.0f)
        CHECK(a.st.fragments == ref.st.fragments, "f2b %s: threshold 0 discarded", scene);
    else
        CHECK(count[1] > 0 && a.st.fragments < ref.st.fragments,
              "f2b %s: nothing discarded", scene);
    oit_image_free(&a.img);
    oit_image_free(&ref.img);
    free(tris);
}

/* F2B's termination in chunks (f2b.h, "Chunks"), against a CPU model of
 * the defined behaviour: on N full-frame layers of one alpha, chunk c's
 * fragments are discarded when the transmittance the chunks before c left
 * is below the threshold. Alpha 128/255 falls below 0.02 after 6 layers; the
 * chunks hold 4 or 8 layers here, so the model blends 8 a pixel. A shader
 * that sees its own draw's writes blends 6 (llvmpipe) and one that sees
 * none all N (NVIDIA): both are reads GL leaves undefined. */
static void check_f2b_chunks(methods *m)
{
    enum { N = 256 };
    const double a = 128.0 / 255.0;
    quad_spec *q = full_stack(N, 0.05f, 128, 7u);
    oit_triangle *tris = scene_tris(q, N);
    oit_view v;
    scene_view(&v, 48, 32, OIT_SHADING_TRANSPARENT);
    set_threshold(m, M_F2B, OIT_F2B_DEFAULT_THRESHOLD);
    uint64_t chunk = oit_f2b_chunk_triangles(2 * N);
    /* Quads facing the camera sort by depth, a quad's two triangles
     * together: whole quads a chunk when chunk is even. */
    double T = 1.0, seen = 1.0;
    uint64_t layers = 0;
    for (uint64_t j = 0; j < N; j++) {
        if (2 * j % chunk == 0)
            seen = T;
        if (seen >= OIT_F2B_DEFAULT_THRESHOLD) {
            layers++;
            T *= 1.0 - a;
        }
    }
    uint64_t want = layers * (uint64_t)v.width * v.height;
    oit_frame_stats st, ref;
    oit_image_diff d = versus_dfb(m, M_F2B, "full256 chunks", tris, 2 * N, &v, &st, &ref);
    printf("f2b chunks of %llu triangles: blended %llu fragments, the model %llu (%llu layers "
           "a pixel), max_abs %.6f\n", (unsigned long long)chunk,
           (unsigned long long)st.fragments, (unsigned long long)want,
           (unsigned long long)layers, d.max_abs);
    CHECK(chunk % 2 == 0 && chunk < 2 * N, "f2b chunks: %llu triangles a chunk of %d: not "
          "whole quads, or one chunk", (unsigned long long)chunk, 2 * N);
    CHECK(st.fragments == want, "f2b chunks: blended %llu fragments, not the %llu (%llu a "
          "pixel) of chunk c reading what the chunks before c left",
          (unsigned long long)st.fragments, (unsigned long long)want, (unsigned long long)layers);
    CHECK(ref.fragments == (uint64_t)N * v.width * v.height && d.max_abs <=
          OIT_F2B_DEFAULT_THRESHOLD + TOL, "f2b chunks: DFB %llu fragments, max_abs %.6f",
          (unsigned long long)ref.fragments, d.max_abs);
    free(tris);
    free(q);
}

/* F2B. Its order (view depth of triangle centroids) is exact for quads
 * facing the camera, so at threshold 0 it must equal DFB there; on the
 * interlocking shapes it need not (printed). At the default threshold, on
 * quads dense enough that some pixels fall below it, the per-pixel promise
 * of check_f2b_pixels; on 40 nearly opaque layers it must blend far fewer
 * fragments. */
static void test_f2b(methods *m)
{
    const int n = QUADS12;
    oit_triangle *tris, shapes[48];
    oit_view v;
    quad_spec *q = quads12(0x2545f491u, &tris, &v);
    set_threshold(m, M_F2B, 0.0f);
    check_f2b_pixels(m, "quads12", q, n, &v, 0.0f);
    double hand = INFINITY;
    result r = render(m, M_F2B, tris, 2 * (size_t)n, &v);
    if (r.ok)
        hand = hand_max_diff(&r.img, &v, q, n);
    oit_image_free(&r.img);
    printf("f2b quads12 threshold 0 vs hand max_abs=%.6f\n", hand);
    CHECK(hand <= TOL, "f2b quads12 threshold 0: differs from the hand result by %.6f", hand);
    size_t ns = shapes_scene(shapes);
    oit_image_diff d = versus_dfb(m, M_F2B, "shapes thr 0 (unordered)", shapes, ns, &v, NULL,
                                  NULL);
    CHECK(isfinite(d.max_abs), "f2b shapes: max_abs %.6f", d.max_abs);
    quad_spec *dense = quad_stack(24, -2.0f, 0.3f);
    for (int i = 0; i < 24; i++)
        dense[i].rgba[3] = 200;
    shuffle_quads(dense, 24, 31u);
    check_f2b_pixels(m, "dense24", dense, 24, &v, 0.0f);
    set_threshold(m, M_F2B, OIT_F2B_DEFAULT_THRESHOLD);
    check_f2b_pixels(m, "dense24", dense, 24, &v, OIT_F2B_DEFAULT_THRESHOLD);
    quad_spec *deep = full_stack(40, 0.25f, 247, 99u);
    oit_triangle *td = scene_tris(deep, 40);
    oit_frame_stats st, ref;
    d = versus_dfb(m, M_F2B, "opaque40 default", td, 80, &v, &st, &ref);
    CHECK(d.max_abs <= OIT_F2B_DEFAULT_THRESHOLD + TOL, "f2b opaque40: max_abs %.6f",
          d.max_abs);
    CHECK(st.fragments < ref.fragments / 4, "f2b opaque40 blended %llu of %llu fragments",
          (unsigned long long)st.fragments, (unsigned long long)ref.fragments);
    free(td);
    free(deep);
    free(dense);
    free(tris);
    free(q);
    check_f2b_chunks(m);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    methods m;
    if (methods_open(&m)) {
        test_exact_quads(&m);
        test_exact_shapes(&m);
        test_ddp_translucent(&m);
        test_ties(&m);
        test_unsorted(&m);
        test_wboit(&m);
        check_threshold_range(&m);
        test_guarded(&m);
        test_guarded_memory();
        test_f2b(&m);
        test_growth(M_PLL);
        test_growth(M_PPLL4);
        test_deep();
    }
    methods_destroy(&m);
    return test_gl_verdict(gl);
}
