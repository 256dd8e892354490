/* The baseline methods against DFB (the exact in-core method, itself tested
 * against hand results in test_dfb.c) and against the hand result of
 * gl_test_scene.h: PLL and depth peeling must match within 1/255; unsorted
 * blending must be right only when the order happens to be back to front;
 * WBOIT's error is printed and bounded loosely. Every figure is printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "gl_test_scene.h"
#include "render/depth_peel.h"
#include "render/dfb.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/ppll.h"
#include "render/unsorted.h"
#include "render/wboit.h"
#include "test_check.h"

#define TOL (1.0 / 255)
/* WBOIT's error against DFB, measured on llvmpipe: quads12 max 0.089 rmse
 * 0.0141, shapes max 0.161 rmse 0.0103. The bounds (about 2x) only catch a
 * broken method (NaN or inf from overflow, a frame far from DFB). */
#define WBOIT_MAX_BOUND 0.3
#define WBOIT_RMSE_BOUND 0.03

enum method { M_DFB, M_PLL, M_DP, M_WBOIT, M_UNSORTED, M_N };
static const char *const method_names[M_N] = {"dfb", "pll", "dp", "wboit", "unsorted"};

typedef struct methods {
    oit_dfb *dfb;
    oit_pll *pll;
    oit_depth_peel *dp;
    oit_wboit *wb;
    oit_unsorted *un;
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
    const oit_gpu_mesh *list[1] = {mesh};
    if (s == OIT_OK) {
        switch (which) {
        case M_DFB: s = oit_dfb_render(m->dfb, list, 1, v, &r.img, NULL, &r.st, &err); break;
        case M_PLL: s = oit_pll_render(m->pll, list, 1, v, &r.img, &r.st, &err); break;
        case M_DP: s = oit_depth_peel_render(m->dp, list, 1, v, &r.img, &r.st, &err); break;
        case M_WBOIT: s = oit_wboit_render(m->wb, list, 1, v, &r.img, &r.st, &err); break;
        default: s = oit_unsorted_render(m->un, list, 1, v, &r.img, &r.st, &err); break;
        }
    }
    oit_gpu_mesh_destroy(mesh);
    r.ok = s == OIT_OK;
    CHECK(r.ok, "%s: %s", method_names[which], err.message);
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
           method_names[which], scene, v->width, v->height, d.max_abs, d.rmse,
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
    CHECK(d.max_abs <= TOL, "%s on %s: differs from DFB by %.6f", method_names[which], scene,
          d.max_abs);
    CHECK(st.fragments == ref.fragments, "%s on %s: %llu fragments, DFB %llu",
          method_names[which], scene, (unsigned long long)st.fragments,
          (unsigned long long)ref.fragments);
    CHECK(st.max_layers == ref.max_layers, "%s on %s: max_layers %u, DFB %u",
          method_names[which], scene, st.max_layers, ref.max_layers);
    CHECK(st.gpu_bytes_peak > 0, "%s: no gpu_bytes_peak", method_names[which]);
    if (!q)
        return;
    result r = render(m, which, tris, count, v);
    double hand = r.ok ? hand_max_diff(&r.img, v, q, nq) : INFINITY;
    printf("%-9s %-26s vs hand max_abs=%.6f\n", method_names[which], scene, hand);
    CHECK(hand <= TOL, "%s on %s: differs from the hand result by %.6f", method_names[which],
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

static void test_exact_quads(methods *m)
{
    const int n = 12;
    quad_spec *q = quad_stack(n, -2.0f, 0.7f);
    shuffle_quads(q, n, 0x2545f491u);
    oit_triangle *tris = scene_tris(q, n);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    check_exact(m, M_PLL, "quads12 shuffled", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_DP, "quads12 shuffled", tris, 2 * (size_t)n, &v, q, n);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSLUCENT);
    check_exact(m, M_PLL, "quads12 translucent", tris, 2 * (size_t)n, &v, q, n);
    check_exact(m, M_DP, "quads12 translucent", tris, 2 * (size_t)n, &v, q, n);
    free(tris);
    free(q);
}

static void test_exact_shapes(methods *m)
{
    oit_triangle tris[48];
    size_t n = shapes_scene(tris);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    check_exact(m, M_PLL, "shapes", tris, n, &v, NULL, 0);
    check_exact(m, M_DP, "shapes", tris, n, &v, NULL, 0);
    scene_view(&v, 96, 64, OIT_SHADING_TRANSLUCENT);
    check_exact(m, M_PLL, "shapes translucent", tris, n, &v, NULL, 0);
    check_exact(m, M_DP, "shapes translucent", tris, n, &v, NULL, 0);
    /* Different shapes must actually overlap, or the test shows nothing. */
    oit_frame_stats st;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    versus_dfb(m, M_DFB, "shapes (dfb itself)", tris, n, &v, &st, NULL);
    CHECK(st.max_layers >= 6, "shapes: only %u layers", st.max_layers);
}

/* Frame 1 has one layer and fits the initial node buffer; frame 2 has 40
 * and must overflow it, grow it and be drawn again, still exact. */
static void test_pll_growth(void)
{
    oit_error err = {0};
    methods m = {0};
    if (oit_pll_create(&m.pll, &err) != OIT_OK || oit_dfb_create(&m.dfb, &err) != OIT_OK) {
        CHECK(0, "create: %s", err.message);
        oit_pll_destroy(m.pll);
        oit_dfb_destroy(m.dfb);
        return;
    }
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    quad_spec one = {-3.0f, 10.0f, {200, 100, 50, 128}, 1};
    oit_triangle tris1[2];
    quad_tris(&one, tris1);
    oit_frame_stats st1, st2;
    check_exact(&m, M_PLL, "growth frame 1", tris1, 2, &v, &one, 1);
    result r1 = render(&m, M_PLL, tris1, 2, &v);
    st1 = r1.st;
    uint64_t cap1 = oit_pll_capacity(m.pll);
    oit_image_free(&r1.img);
    const int n = 40;
    quad_spec *q = quad_stack(n, -1.0f, 0.25f);
    for (int i = 0; i < n; i++)
        q[i].half = 30.0f; /* every quad covers the frame: 40 layers everywhere */
    shuffle_quads(q, n, 77u);
    oit_triangle *tris2 = scene_tris(q, n);
    result r2 = render(&m, M_PLL, tris2, 2 * (size_t)n, &v);
    st2 = r2.st;
    uint64_t cap2 = oit_pll_capacity(m.pll);
    double hand = r2.ok ? hand_max_diff(&r2.img, &v, q, n) : INFINITY;
    printf("pll growth: frame 1 fragments=%llu passes=%u capacity=%llu bytes=%llu; "
           "frame 2 fragments=%llu passes=%u capacity=%llu bytes=%llu vs hand max_abs=%.6f\n",
           (unsigned long long)st1.fragments, st1.batches, (unsigned long long)cap1,
           (unsigned long long)st1.gpu_bytes_peak, (unsigned long long)st2.fragments,
           st2.batches, (unsigned long long)cap2, (unsigned long long)st2.gpu_bytes_peak, hand);
    CHECK(st1.batches == 1, "frame 1 should fit the first node buffer");
    CHECK(st2.batches == 2, "frame 2 should have overflowed and been drawn again");
    CHECK(st2.fragments == 40ull * 96 * 64, "frame 2: %llu fragments",
          (unsigned long long)st2.fragments);
    CHECK(cap2 >= st2.fragments && cap2 > cap1, "node buffer did not grow");
    CHECK(hand <= TOL, "frame 2 differs from the hand result by %.6f", hand);
    oit_image_free(&r2.img);
    /* The next frame of that size fits at once. */
    result r3 = render(&m, M_PLL, tris2, 2 * (size_t)n, &v);
    CHECK(r3.st.batches == 1, "frame 3 drew %u passes", r3.st.batches);
    oit_image_free(&r3.img);
    free(tris2);
    free(q);
    oit_pll_destroy(m.pll);
    oit_dfb_destroy(m.dfb);
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
    const int n = 12;
    quad_spec *q = quad_stack(n, -2.0f, 0.7f);
    shuffle_quads(q, n, 99u);
    oit_triangle *tris = scene_tris(q, n);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    check_wboit(m, "quads12 shuffled", tris, 2 * (size_t)n, &v);
    oit_triangle shapes[48];
    size_t ns = shapes_scene(shapes);
    check_wboit(m, "shapes", shapes, ns, &v);
    free(tris);
    free(q);
}

/* 100 layers: PLL (long lists, past the 32 sorted in registers) and DP
 * exact; PLL's and DFB's storage grows with the depth, DP's does not. */
static void test_deep(void)
{
    oit_error err = {0};
    methods m = {0};
    if (oit_pll_create(&m.pll, &err) != OIT_OK || oit_dfb_create(&m.dfb, &err) != OIT_OK ||
        oit_depth_peel_create(&m.dp, &err) != OIT_OK) {
        CHECK(0, "create: %s", err.message);
    } else {
        oit_view v;
        scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
        quad_spec *shallow = quad_stack(3, -2.0f, 1.0f), *deep = quad_stack(100, -1.0f, 0.1f);
        for (int i = 0; i < 3; i++)
            shallow[i].half = 30.0f;
        for (int i = 0; i < 100; i++)
            deep[i].half = 30.0f;
        shuffle_quads(deep, 100, 4242u);
        oit_triangle *ts = scene_tris(shallow, 3), *td = scene_tris(deep, 100);
        oit_frame_stats pll_s, dfb_s, pll_d, dfb_d, dp_s, dp_d;
        versus_dfb(&m, M_PLL, "3 layers", ts, 6, &v, &pll_s, &dfb_s);
        versus_dfb(&m, M_DP, "3 layers", ts, 6, &v, &dp_s, NULL);
        check_exact(&m, M_PLL, "100 layers", td, 200, &v, deep, 100);
        check_exact(&m, M_DP, "100 layers", td, 200, &v, deep, 100);
        versus_dfb(&m, M_PLL, "100 layers (bytes)", td, 200, &v, &pll_d, &dfb_d);
        versus_dfb(&m, M_DP, "100 layers (bytes)", td, 200, &v, &dp_d, NULL);
        printf("gpu_bytes_peak 3 -> 100 layers: pll %llu -> %llu, dfb %llu -> %llu, "
               "dp %llu -> %llu (dp passes %u)\n", (unsigned long long)pll_s.gpu_bytes_peak,
               (unsigned long long)pll_d.gpu_bytes_peak, (unsigned long long)dfb_s.gpu_bytes_peak,
               (unsigned long long)dfb_d.gpu_bytes_peak, (unsigned long long)dp_s.gpu_bytes_peak,
               (unsigned long long)dp_d.gpu_bytes_peak, dp_d.batches);
        CHECK(pll_d.gpu_bytes_peak >= pll_s.gpu_bytes_peak + 90ull * 96 * 64 * 20,
              "pll bytes did not grow with depth");
        CHECK(dfb_d.gpu_bytes_peak >= dfb_s.gpu_bytes_peak + 90ull * 96 * 64 * 16,
              "dfb bytes did not grow with depth");
        CHECK(dp_d.gpu_bytes_peak == dp_s.gpu_bytes_peak, "dp bytes grew with depth");
        CHECK(dp_d.batches == 101, "dp drew %u passes for 100 layers", dp_d.batches);
        free(ts);
        free(td);
        free(shallow);
        free(deep);
    }
    oit_pll_destroy(m.pll);
    oit_dfb_destroy(m.dfb);
    oit_depth_peel_destroy(m.dp);
}

/* Coplanar quads: DP keeps one fragment of each tie and loses the rest,
 * exactly the pixels both cover; PLL keeps them all. */
static void test_ties(methods *m)
{
    quad_spec q[3] = {{-3.0f, 1.2f, {200, 40, 40, 120}, 1},
                      {-3.0f, 0.6f, {40, 200, 40, 120}, 1},
                      {-5.0f, 3.0f, {40, 40, 200, 120}, 0}};
    oit_triangle *tris = scene_tris(q, 3);
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    check_exact(m, M_PLL, "coplanar ties", tris, 6, &v, q, 3);
    oit_frame_stats st, ref;
    oit_image_diff d = versus_dfb(m, M_DP, "coplanar ties", tris, 6, &v, &st, &ref);
    /* Pixels inside the smaller quad see both coplanar ones. */
    uint64_t tied = 0;
    for (int y = 0; y < v.height; y++)
        for (int x = 0; x < v.width; x++) {
            double dx = ((x + 0.5) / v.width * 2 - 1) * v.width / v.height;
            double dy = 1 - (y + 0.5) / v.height * 2;
            tied += fabs(dx * 3.0) < 0.6 && fabs(dy * 3.0) < 0.6;
        }
    printf("dp on ties: lost %llu fragments (expect %llu), max_abs=%.6f\n",
           (unsigned long long)(ref.fragments - st.fragments), (unsigned long long)tied, d.max_abs);
    CHECK(ref.fragments - st.fragments == tied, "dp should lose exactly the tied fragments");
    CHECK(d.max_abs > 0.05, "dp should differ where fragments tie: %.6f", d.max_abs);
    free(tris);
}

int main(void)
{
    oit_error err = {0};
    oit_gl *gl = NULL;
    if (oit_gl_create(NULL, &gl, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: context: %s\n", err.message);
        return 1;
    }
    printf("renderer: %s\n", oit_gl_renderer(gl));
    methods m = {0};
    oit_status s = oit_dfb_create(&m.dfb, &err);
    if (s == OIT_OK)
        s = oit_pll_create(&m.pll, &err);
    if (s == OIT_OK)
        s = oit_depth_peel_create(&m.dp, &err);
    if (s == OIT_OK)
        s = oit_wboit_create(&m.wb, &err);
    if (s == OIT_OK)
        s = oit_unsorted_create(&m.un, &err);
    CHECK(s == OIT_OK, "create: %s", err.message);
    if (s == OIT_OK) {
        test_exact_quads(&m);
        test_exact_shapes(&m);
        test_ties(&m);
        test_unsorted(&m);
        test_wboit(&m);
        test_pll_growth();
        test_deep();
    }
    oit_dfb_destroy(m.dfb);
    oit_pll_destroy(m.pll);
    oit_depth_peel_destroy(m.dp);
    oit_wboit_destroy(m.wb);
    oit_unsorted_destroy(m.un);
    oit_gl_destroy(gl);
    printf("%s\n", test_failures ? "FAILED" : "ok");
    return test_failures != 0;
}
