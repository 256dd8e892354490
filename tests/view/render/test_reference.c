/* The Embree reference on analytic scenes: big triangles facing a camera at
 * the origin that looks down -z, so every pixel's expected colour follows
 * from the ray direction alone (n.v = |dir.z|). Checks depth order, ties by
 * prim, 600 layers, near/far/behind clipping, translucent absorption and
 * that the thread count does not change a pixel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "view/render/reference/reference.h"
#include "view/render/image/shade.h"
#include "tests/lib/test_check.h"


enum { W = 7, H = 5 };

typedef struct layer {
    float z;          /* plane z (camera looks down -z from the origin) */
    int facing_eye;   /* 1: counter-clockwise seen from the eye         */
    unsigned char rgba[4];
} layer;

/* A triangle spanning the whole view at depth -z. */
static oit_triangle big_triangle(const layer *l)
{
    float s = fabsf(l->z) * 4.0f + 1.0f;
    float p[3][3] = {{-s, -s, l->z}, {s, -s, l->z}, {0, s, l->z}};
    if (!l->facing_eye) {
        float tmp[3];
        memcpy(tmp, p[1], sizeof tmp);
        memcpy(p[1], p[2], sizeof tmp);
        memcpy(p[2], tmp, sizeof tmp);
    }
    oit_triangle t;
    for (int v = 0; v < 3; v++) {
        memcpy(t.v[v].pos, p[v], sizeof p[v]);
        memcpy(t.v[v].rgba, l->rgba, 4);
    }
    return t;
}

static void make_mesh(oit_mesh *m, const layer *layers, size_t n)
{
    memset(m, 0, sizeof *m);
    for (size_t i = 0; i < n; i++) {
        oit_triangle t = big_triangle(&layers[i]);
        oit_mesh_append(m, &t, 1, NULL);
    }
}

static oit_view make_view(oit_shading_mode mode)
{
    oit_view v;
    memset(&v, 0, sizeof v);
    v.camera.target[2] = -1.0f;
    v.camera.up[1] = 1.0f;
    v.camera.fovy_deg = 60.0f;
    v.camera.znear = 0.5f;
    v.camera.zfar = 100.0f;
    v.width = W;
    v.height = H;
    v.shading.mode = mode;
    v.shading.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    v.shading.background[0] = v.shading.background[1] = v.shading.background[2] = 1.0f;
    v.shading.absorption = 3.0f;
    v.shading.scene_scale = 2.0f;
    return v;
}

/* |dir.z| of the pixel-centre ray, computed independently of reference.c. */
static double pixel_cos(int x, int y)
{
    double th = tan(30.0 * 3.14159265358979323846 / 180.0);
    double dx = ((x + 0.5) / W * 2 - 1) * th * W / H, dy = (1 - (y + 0.5) / H * 2) * th;
    return 1.0 / sqrt(dx * dx + dy * dy + 1.0);
}

/* Transparent composite of layers sorted near to far (index order = prim). */
static void expected_transparent(const layer *l, size_t n, const size_t *order, double ndv,
                                 double out[3])
{
    double C[3] = {0, 0, 0}, T = 1.0;
    for (size_t k = 0; k < n; k++) {
        const layer *f = &l[order[k]];
        double a = f->rgba[3] / 255.0;
        for (int c = 0; c < 3; c++)
            C[c] += T * a * f->rgba[c] / 255.0 * (0.3 + 0.7 * ndv);
        T *= 1.0 - a;
    }
    for (int c = 0; c < 3; c++)
        out[c] = C[c] + T;
}

static double max_pixel_error(const oit_image *img, int x, int y, const double want[3])
{
    const float *p = img->rgba + ((size_t)y * img->width + x) * 4;
    double e = 0;
    for (int c = 0; c < 3; c++)
        e = fmax(e, fabs(p[c] - want[c]));
    return e;
}

/* The layers through the reference (desc: NULL for its defaults),
 * transparent, into img, counts (layers per pixel) and st; returns the
 * largest error of any pixel against the composite of layers order[0..k)
 * computed by hand. */
static double render_layers(const layer *l, size_t n, const oit_reference_desc *desc,
                            const size_t *order, size_t k, oit_image *img, uint32_t *counts,
                            oit_frame_stats *st)
{
    oit_mesh m;
    make_mesh(&m, l, n);
    oit_view v = make_view(OIT_SHADING_TRANSPARENT);
    oit_error err;
    oit_status s = oit_reference_render(&m, &v, desc, img, counts, st, &err);
    CHECK(s == OIT_OK, "%s", err.message);
    oit_mesh_free(&m);
    if (s != OIT_OK) {
        *img = (oit_image){0};
        *st = (oit_frame_stats){0};
        memset(counts, 0, sizeof *counts * W * H);
        return INFINITY;
    }
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double want[3];
            expected_transparent(l, k, order, pixel_cos(x, y), want);
            worst = fmax(worst, max_pixel_error(img, x, y, want));
        }
    return worst;
}

static void test_order_and_ties(void)
{
    /* Prims listed far first; two coplanar layers at z=-3 tie. */
    layer l[4] = {{-6, 1, {0, 0, 255, 128}}, {-3, 1, {255, 0, 0, 100}},
                  {-3, 1, {0, 255, 0, 100}}, {-2, 0, {255, 255, 0, 60}}};
    size_t order[4] = {3, 1, 2, 0}; /* by depth, tie 1 before 2 */
    oit_image img;
    uint32_t counts[W * H];
    oit_frame_stats st;
    oit_reference_desc desc = {.threads = 2};
    double worst = render_layers(l, 4, &desc, order, 4, &img, counts, &st);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            CHECK(counts[y * W + x] == 4, "pixel %d,%d has %u layers", x, y, counts[y * W + x]);
    const float *c = img.rgba + ((size_t)(H / 2) * W + W / 2) * 4;
    printf("order/ties: centre %.6f %.6f %.6f, max error %.3g, fragments %llu, max layers %u, %.2f ms\n",
           c[0], c[1], c[2], worst, (unsigned long long)st.fragments, st.max_layers, st.ms);
    CHECK(worst < 1e-6, "order/ties: error %g", worst);
    CHECK(st.fragments == 4 * W * H && st.max_layers == 4, "stats");

    /* Swapping the tie order must be visible, or the check above proves nothing. */
    size_t swapped[4] = {3, 2, 1, 0};
    double want[3];
    expected_transparent(l, 4, swapped, pixel_cos(W / 2, H / 2), want);
    CHECK(max_pixel_error(&img, W / 2, H / 2, want) > 1e-3, "tie order not observable");
    oit_image_free(&img);
}

static void test_many_layers(void)
{
    enum { N = 600 };
    static layer l[N];
    static size_t order[N];
    for (int i = 0; i < N; i++) {
        /* Listed back to front with mixed winding. */
        l[i] = (layer){-1.0f - 0.01f * (float)(N - 1 - i), i % 3 != 0,
                       {(unsigned char)(i % 256), 200, (unsigned char)(255 - i % 256), 3}};
        order[i] = (size_t)(N - 1 - i);
    }
    oit_image img;
    static uint32_t counts[W * H];
    oit_frame_stats st;
    double worst = render_layers(l, N, NULL, order, N, &img, counts, &st);
    uint32_t min_count = UINT32_MAX;
    for (int i = 0; i < W * H; i++)
        if (counts[i] < min_count)
            min_count = counts[i];
    printf("600 layers: min count %u, max layers %u, fragments %llu, max error %.3g, %.2f ms\n",
           min_count, st.max_layers, (unsigned long long)st.fragments, worst, st.ms);
    CHECK(min_count == N && st.max_layers == N, "lost layers");
    CHECK(st.fragments == (uint64_t)N * W * H, "fragment count");
    CHECK(worst < 1e-5, "600-layer composite error %g", worst);
    oit_image_free(&img);
}

static void test_clipping(void)
{
    /* Behind the eye, nearer than znear (0.5), beyond zfar (100), and one
     * kept layer. */
    layer l[4] = {{2, 1, {255, 0, 0, 255}}, {-0.3f, 1, {0, 255, 0, 255}},
                  {-150, 1, {0, 0, 255, 255}}, {-5, 1, {255, 0, 255, 128}}};
    size_t order[1] = {3};
    oit_image img;
    uint32_t counts[W * H];
    oit_frame_stats st;
    double worst = render_layers(l, 4, NULL, order, 1, &img, counts, &st);
    int bad_counts = 0;
    for (int i = 0; i < W * H; i++)
        bad_counts += counts[i] != 1;
    printf("clipping: max error %.3g, pixels with count != 1: %d, fragments %llu\n", worst,
           bad_counts, (unsigned long long)st.fragments);
    CHECK(worst < 1e-6 && bad_counts == 0 && st.fragments == W * H, "clipped layers leaked in");
    oit_image_free(&img);
}

static void test_translucent(void)
{
    /* A slab: front face at z=-2 facing the eye, back face at z=-4.5. */
    layer l[2] = {{-4.5f, 0, {51, 128, 255, 255}}, {-2, 1, {51, 128, 255, 255}}};
    oit_mesh m;
    make_mesh(&m, l, 2);
    oit_view v = make_view(OIT_SHADING_TRANSLUCENT);
    oit_image img;
    oit_error err;
    CHECK(oit_reference_render(&m, &v, NULL, &img, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double ndv = pixel_cos(x, y), light = 0.3 + 0.7 * ndv;
            double a = 0.04 + 0.96 * pow(1 - ndv, 5), d = 2.5 / ndv; /* path length in slab */
            double want[3];
            for (int c = 0; c < 3; c++) {
                double base = l[1].rgba[c] / 255.0;
                double absorb = exp(-3.0 / 2.0 * (1 - base) * d);
                double T1 = 1 - a, C = a * light;
                C += T1 * absorb * a * light;
                want[c] = C + T1 * absorb * (1 - a);
            }
            worst = fmax(worst, max_pixel_error(&img, x, y, want));
        }
    const float *c = img.rgba + ((size_t)(H / 2) * W + W / 2) * 4;
    printf("translucent slab: centre %.6f %.6f %.6f, max error %.3g\n", c[0], c[1], c[2], worst);
    CHECK(worst < 1e-5, "translucent error %g", worst);
    oit_image_free(&img);
    oit_mesh_free(&m);
}

static void test_threads_agree(void)
{
    enum { N = 40 };
    layer l[N];
    for (int i = 0; i < N; i++)
        l[i] = (layer){-1.5f - 0.37f * (float)((i * 7) % N), i % 2,
                       {(unsigned char)(i * 6), 90, 40, (unsigned char)(30 + i)}};
    oit_mesh m;
    make_mesh(&m, l, N);
    oit_view v = make_view(OIT_SHADING_TRANSPARENT);
    oit_image a, b;
    oit_error err;
    oit_reference_desc one = {.threads = 1}, many = {.threads = 4};
    CHECK(oit_reference_render(&m, &v, &one, &a, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    CHECK(oit_reference_render(&m, &v, &many, &b, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    int same = a.rgba && b.rgba &&
               memcmp(a.rgba, b.rgba, sizeof(float) * 4 * W * H) == 0;
    printf("threads 1 vs 4: %s\n", same ? "identical" : "DIFFERENT");
    CHECK(same, "thread count changed the image");
    oit_image_free(&a);
    oit_image_free(&b);
    oit_mesh_free(&m);
}

/* ---- an independent oracle: brute-force double-precision ray casting ---- */

typedef struct bf_hit {
    double t, u, v;
    uint32_t prim;
} bf_hit;

static int bf_cmp(const void *a, const void *b)
{
    const bf_hit *x = a, *y = b;
    if (x->t != y->t) return x->t < y->t ? -1 : 1;
    return (x->prim > y->prim) - (x->prim < y->prim);
}

/* Moller-Trumbore in double; returns 1 and fills t,u,v on a hit. */
static int bf_intersect(const oit_triangle *tri, const double o[3], const double d[3],
                        double *t, double *u, double *v)
{
    double e1[3], e2[3], p[3], q[3], s[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)tri->v[1].pos[k] - tri->v[0].pos[k];
        e2[k] = (double)tri->v[2].pos[k] - tri->v[0].pos[k];
        s[k] = o[k] - tri->v[0].pos[k];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1], p[1] = d[2] * e2[0] - d[0] * e2[2], p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabs(det) < 1e-300)
        return 0;
    *u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    *v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return *u >= 0 && *v >= 0 && *u + *v <= 1 && *t > 0;
}

/* 1 when the pixel is decidable: no hit within eps of a triangle edge and
 * no two hits closer in t than eps (where float and double may disagree). */
static int bf_pixel(const oit_mesh *m, const oit_view *view, int x, int y, bf_hit *hits,
                    float rgb[3])
{
    const double eps = 1e-4;
    double th = tan(view->camera.fovy_deg * 3.14159265358979323846 / 360.0);
    int w = view->width, h = view->height;
    double d[3] = {((x + 0.5) / w * 2 - 1) * th * w / h, (1 - (y + 0.5) / h * 2) * th, -1.0};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + 1.0), o[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
        d[k] /= len;
    size_t n = 0;
    for (size_t i = 0; i < m->count; i++) {
        bf_hit h;
        if (!bf_intersect(&m->tris[i], o, d, &h.t, &h.u, &h.v))
            continue;
        if (fmin(fmin(h.u, h.v), 1 - h.u - h.v) < eps)
            return 0;
        h.prim = (uint32_t)i;
        double depth = h.t * -d[2];
        if (depth >= view->camera.znear && depth <= view->camera.zfar)
            hits[n++] = h;
    }
    qsort(hits, n, sizeof *hits, bf_cmp);
    oit_shading s = view->shading;
    oit_pixel_state st;
    oit_pixel_begin(&st);
    float eye[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && hits[i].t - hits[i - 1].t < eps)
            return 0;
        float bary[3] = {(float)(1 - hits[i].u - hits[i].v), (float)hits[i].u, (float)hits[i].v};
        oit_shaded_fragment f;
        oit_shade_fragment(&s, &m->tris[hits[i].prim], hits[i].prim, bary, eye, hits[i].t, &f);
        oit_pixel_add(&st, &s, &f);
    }
    oit_pixel_end(&st, &s, rgb);
    return 1;
}

static void test_brute_force(oit_shading_mode mode)
{
    enum { N = 300 };
    oit_mesh m;
    memset(&m, 0, sizeof m);
    uint32_t seed = 7;
    for (int i = 0; i < N; i++) {
        oit_triangle t;
        float c[3];
        for (int k = 0; k < 3; k++) {
            seed = seed * 1664525u + 1013904223u;
            c[k] = (float)(seed >> 8) / 16777216.0f * 2.0f - 1.0f;
        }
        for (int v = 0; v < 3; v++) {
            for (int k = 0; k < 3; k++) {
                seed = seed * 1664525u + 1013904223u;
                t.v[v].pos[k] = c[k] * (k == 2 ? 1.5f : 1.2f) + ((float)(seed >> 8) / 16777216.0f - 0.5f);
                t.v[v].rgba[k] = (unsigned char)(seed >> 13);
            }
            t.v[v].pos[2] -= 4.0f;
            t.v[v].rgba[3] = (unsigned char)(60 + (seed >> 24) % 140);
        }
        oit_mesh_append(&m, &t, 1, NULL);
    }
    oit_view v = make_view(mode);
    v.width = 48;
    v.height = 36;
    oit_shading_resolve_defaults(&v.shading);
    oit_image img;
    oit_error err;
    CHECK(oit_reference_render(&m, &v, NULL, &img, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    static bf_hit hits[N];
    int decided = 0;
    double worst = 0;
    for (int y = 0; y < v.height && img.rgba; y++)
        for (int x = 0; x < v.width; x++) {
            float rgb[3];
            if (!bf_pixel(&m, &v, x, y, hits, rgb))
                continue;
            decided++;
            double want[3] = {rgb[0], rgb[1], rgb[2]};
            worst = fmax(worst, max_pixel_error(&img, x, y, want));
        }
    printf("brute force (%s, %d random triangles): %d of %d pixels decidable, max error %.3g\n",
           mode == OIT_SHADING_TRANSLUCENT ? "translucent" : "transparent", N, decided,
           v.width * v.height, worst);
    CHECK(decided >= v.width * v.height * 3 / 4, "too few decidable pixels");
    CHECK(worst < 1e-4, "reference differs from brute force by %g", worst);
    oit_image_free(&img);
    oit_mesh_free(&m);
}

/* Two triangles share an edge on the plane x = 0, which the centre column's
 * rays graze; a third lies behind them away from every edge. Only that
 * column may be flagged ambiguous. */
static void test_ambiguity(void)
{
    oit_triangle t[3];
    float p[3][3][3] = {{{0, -20, -3}, {0, 20, -3}, {-20, 0, -3}},
                        {{0, -20, -3}, {20, 0, -3}, {0, 20, -3}},
                        {{-30, -30, -6}, {30, -30, -6}, {0, 30, -6}}};
    for (int i = 0; i < 3; i++)
        for (int v = 0; v < 3; v++) {
            memcpy(t[i].v[v].pos, p[i][v], sizeof p[i][v]);
            memset(t[i].v[v].rgba, 128, 4);
        }
    oit_mesh m;
    memset(&m, 0, sizeof m);
    oit_mesh_append(&m, t, 3, NULL);
    oit_view v = make_view(OIT_SHADING_TRANSPARENT);
    uint8_t amb[W * H];
    oit_reference_desc desc = {.threads = 2, .ambiguous = amb};
    oit_image img;
    oit_error err;
    CHECK(oit_reference_render(&m, &v, &desc, &img, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    int wrong = 0, flagged = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            flagged += amb[y * W + x];
            wrong += amb[y * W + x] != (x == W / 2);
        }
    printf("ambiguity: %d pixels flagged (want the %d of the centre column), %d wrong\n", flagged,
           H, wrong);
    CHECK(wrong == 0, "ambiguity mask wrong on %d pixels", wrong);
    oit_image_free(&img);

    /* A duplicate of the back triangle in another colour: every pixel holds
     * a tie, which the tie rule orders by source index (shade.h), so the
     * mask still flags only the centre column and swapping the two
     * colours changes the image. */
    oit_triangle dup = t[2];
    for (int k = 0; k < 3; k++)
        dup.v[k].rgba[0] = 250, dup.v[k].rgba[1] = 10;
    oit_mesh_append(&m, &dup, 1, NULL);
    uint32_t ties[W * H];
    desc.ties = ties;
    v.shading.attributes = OIT_ATTR_COLOUR;
    CHECK(oit_reference_render(&m, &v, &desc, &img, NULL, NULL, &err) == OIT_OK, "%s", err.message);
    flagged = 0;
    int tie_px = 0;
    for (int i = 0; i < W * H; i++)
        flagged += amb[i], tie_px += ties[i] >= 1;
    printf("ambiguity with a coplanar duplicate: %d of %d pixels flagged, %d hold a tie\n",
           flagged, W * H, tie_px);
    CHECK(flagged == H, "depth ties flagged ambiguous (%d pixels)", flagged);
    CHECK(tie_px == W * H, "ties counted on %d of %d pixels", tie_px, W * H);
    m.tris[2] = dup;
    m.tris[3] = t[2];
    oit_image swapped;
    CHECK(oit_reference_render(&m, &v, &desc, &swapped, NULL, NULL, &err) == OIT_OK, "%s",
          err.message);
    /* Behind the front pair the red copy, first in order, keeps more red. */
    const float *a = img.rgba, *b = swapped.rgba;
    printf("tie order: red %.4f (grey first) vs %.4f (red first)\n", (double)a[0], (double)b[0]);
    CHECK(b[0] > a[0] + 0.02f, "the tie is not ordered by source index");
    oit_image_free(&swapped);
    oit_image_free(&img);
    oit_mesh_free(&m);
}

static void test_bad_camera(void)
{
    oit_mesh m;
    layer l = {-2, 1, {255, 255, 255, 255}};
    make_mesh(&m, &l, 1);
    oit_view v = make_view(OIT_SHADING_TRANSPARENT);
    v.camera.znear = 0;
    oit_image img;
    oit_error err = {0};
    oit_status s = oit_reference_render(&m, &v, NULL, &img, NULL, NULL, &err);
    printf("bad camera: %s \"%s\"\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_ARGUMENT && img.rgba == NULL, "znear 0 accepted");
    oit_mesh_free(&m);
}

int main(void)
{
    test_order_and_ties();
    test_many_layers();
    test_clipping();
    test_translucent();
    test_threads_agree();
    test_brute_force(OIT_SHADING_TRANSPARENT);
    test_brute_force(OIT_SHADING_TRANSLUCENT);
    test_ambiguity();
    test_bad_camera();
    return test_verdict();
}
