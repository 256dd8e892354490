/* DFB against hand-composited expectations (shade.h): shuffled stacks of
 * quads, coplanar ties, 600 layers, translucency, and fragment-store growth.
 * Every figure is printed; images must agree within 1/255 everywhere. */
#include <stdio.h>
#include <stdlib.h>

#include "tests/lib/gl_test_dfb.h"
#include "tests/lib/gl_test_scene.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_context.h"
#include "view/render/image/image.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"


typedef struct frame {
    oit_image img;
    uint32_t *counts;
    oit_frame_stats st;
} frame;

static int render(oit_dfb *d, const quad_spec *q, int n, const oit_view *v, frame *f)
{
    oit_error err = {0};
    oit_triangle *tris = scene_tris(q, n);
    oit_gpu_mesh *mesh = NULL;
    f->counts = calloc((size_t)v->width * v->height, sizeof *f->counts);
    oit_status s = oit_gpu_mesh_create(tris, 2 * (size_t)n, 0, &mesh, &err);
    if (s == OIT_OK) {
        const oit_gpu_mesh *list[1] = {mesh};
        s = oit_dfb_render(d, list, 1, v, &f->img, f->counts, &f->st, &err);
    }
    oit_gpu_mesh_destroy(mesh);
    free(tris);
    if (s != OIT_OK) {
        fprintf(stderr, "FAIL: render: %s\n", err.message);
        free(f->counts);
    }
    return s == OIT_OK;
}

static void frame_free(frame *f)
{
    oit_image_free(&f->img);
    free(f->counts);
}

/* Checks image, per-pixel counts, fragments and max_layers against the hand
 * result; returns the peak GPU bytes. */
static uint64_t check_scene(oit_dfb *d, const char *name, const quad_spec *q, int n,
                            const oit_view *v)
{
    frame f = {0};
    if (!render(d, q, n, v, &f)) {
        test_failures++;
        return 0;
    }
    uint64_t expect_frags = 0;
    uint32_t expect_max = 0, bad_counts = 0;
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            uint32_t c = 0;
            for (int i = 0; i < n; i++) {
                double tanh = tan(0.5 * v->camera.fovy_deg * 3.14159265358979323846 / 180.0);
                double dx = ((x + 0.5) / v->width * 2 - 1) * tanh * v->width / v->height;
                double dy = (1 - (y + 0.5) / v->height * 2) * tanh;
                c += fabs(dx * q[i].z) < q[i].half && fabs(dy * q[i].z) < q[i].half;
            }
            expect_frags += c;
            expect_max = c > expect_max ? c : expect_max;
            bad_counts += f.counts[(size_t)y * v->width + x] != c;
        }
    double diff = hand_max_diff(&f.img, v, q, n);
    printf("%-22s %dx%d quads=%d fragments=%llu (expect %llu) max_layers=%u (expect %u) "
           "max_abs_diff=%.6f gpu_bytes=%llu ms=%.1f\n", name, v->width, v->height, n,
           (unsigned long long)f.st.fragments, (unsigned long long)expect_frags,
           f.st.max_layers, expect_max, diff, (unsigned long long)f.st.gpu_bytes_peak,
           f.st.ms);
    CHECK(diff <= 1.0 / 255, "%s: image differs by %.6f", name, diff);
    CHECK(f.st.fragments == expect_frags, "%s: fragments", name);
    CHECK(f.st.max_layers == expect_max, "%s: max_layers", name);
    CHECK(bad_counts == 0, "%s: %u pixels with a wrong count", name, bad_counts);
    CHECK(f.st.batches == 1, "%s: batches", name);
    uint64_t bytes = f.st.gpu_bytes_peak;
    frame_free(&f);
    return bytes;
}

static uint64_t test_shuffled(oit_dfb *d)
{
    quad_spec q[8];
    for (int i = 0; i < 8; i++) {
        float z = -1.5f - 0.75f * i;
        /* Two partial quads make per-pixel counts differ. */
        float half = i == 2 ? 0.37f * -z : i == 5 ? 0.61f * -z : 2.0f * -z;
        q[i] = mk(z, half, (i * 97) % 256, (i * 53 + 40) % 256, 255 - i * 30, 60 + 20 * i, i % 3 != 1);
    }
    shuffle_quads(q, 8, 12345u);
    oit_view v;
    scene_view(&v, 64, 48, OIT_SHADING_TRANSPARENT);
    return check_scene(d, "shuffled 8 quads", q, 8, &v);
}

static void test_ties(oit_dfb *d)
{
    /* Identical geometry, so t is bit-identical and only prim decides. */
    quad_spec q[2] = {mk(-3.0f, 10.0f, 255, 0, 0, 128, 1), mk(-3.0f, 10.0f, 0, 0, 255, 128, 1)};
    oit_view v;
    scene_view(&v, 32, 32, OIT_SHADING_TRANSPARENT);
    check_scene(d, "coplanar tie red,blue", q, 2, &v);
    quad_spec swapped[2] = {q[1], q[0]};
    check_scene(d, "coplanar tie blue,red", swapped, 2, &v);
}

static uint64_t test_600(oit_dfb *d)
{
    enum { N = 600 };
    quad_spec *q = malloc(sizeof *q * N);
    for (int i = 0; i < N; i++)
        q[i] = mk(-1.0f - 0.1f * i, 200.0f, i % 2 ? 255 : 20, (i * 7) % 256, i % 2 ? 10 : 240, 3, i % 2);
    shuffle_quads(q, N, 777u);
    oit_view v;
    scene_view(&v, 24, 24, OIT_SHADING_TRANSPARENT);
    uint64_t bytes = check_scene(d, "600 layers", q, N, &v);
    free(q);
    return bytes;
}

static void test_translucent(oit_dfb *d)
{
    /* Two nested closed slabs seen through their front and back faces. */
    quad_spec q[4] = {mk(-2.0f, 8.0f, 200, 120, 40, 255, 1), mk(-6.0f, 20.0f, 200, 120, 40, 255, 0),
                      mk(-3.0f, 1.1f, 30, 90, 230, 255, 1), mk(-4.5f, 1.7f, 30, 90, 230, 255, 0)};
    shuffle_quads(q, 4, 99u);
    oit_view v;
    scene_view(&v, 48, 48, OIT_SHADING_TRANSLUCENT);
    check_scene(d, "translucent nested", q, 4, &v);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    oit_dfb *d = NULL;
    if (oit_dfb_create(&d, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: DFB: %s\n", err.message);
        oit_gl_destroy(gl);
        return 1;
    }
    uint64_t small = test_shuffled(d);
    test_ties(d);
    test_translucent(d);
    uint64_t big = test_600(d);
    /* The store must have grown to hold 600 * 24 * 24 fragments. */
    printf("fragment store growth: %llu -> %llu bytes\n", (unsigned long long)small,
           (unsigned long long)big);
    CHECK(big > small && big >= 600ull * 24 * 24 * 16, "fragment store did not grow");
    uint64_t again = test_shuffled(d);
    CHECK(again == big, "a smaller frame changed the held bytes (%llu)", (unsigned long long)again);
    oit_dfb_destroy(d);
    return test_gl_verdict(gl);
}
