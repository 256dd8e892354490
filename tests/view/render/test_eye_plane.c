/* Triangles that cross the eye plane (a vertex behind the camera, w <= 0)
 * and the near plane, through every exact GL path that takes a batch of
 * triangles here (DFB, array slots, the compute capture, which bins and
 * rasterizes in its own shaders), against the Embree reference, which
 * clips each hit to [znear, zfar] in view depth as GL does. Seeded random
 * scenes: each triangle has one or two vertices behind the eye, or
 * straddles the near plane, or lies in front, in random order, with random
 * colours and alphas; a triangle wholly behind the eye is mixed in too.
 * Compared outside the pixels the reference flags as ambiguous (a centre
 * on an edge), within 1/255. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "view/render/reference/reference.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 40, H = 30, TRIS = 12, CASES = 14, K = 16 };

static uint32_t rnd(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static float uni(uint32_t *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)(rnd(s) >> 8) / 16777216.0f;
}

/* A vertex in front (view depth 1..6), behind the eye (z 0.05..3), or
 * near the near plane (depth 0.3..0.8, znear 0.5). */
static void vertex(oit_vertex *v, int where, uint32_t *s)
{
    float z = where == 0 ? -uni(s, 1.0f, 6.0f) : where == 1 ? uni(s, 0.05f, 3.0f)
                                                            : -uni(s, 0.3f, 0.8f);
    float reach = where == 1 ? 3.0f : -z;
    v->pos[0] = uni(s, -1.2f, 1.2f) * reach;
    v->pos[1] = uni(s, -1.2f, 1.2f) * reach;
    v->pos[2] = z;
}

static void scene(oit_triangle *t, uint32_t *s)
{
    for (int i = 0; i < TRIS; i++) {
        int kind = (int)(rnd(s) % 5);
        /* 0: one vertex behind, 1: two behind, 2: across the near plane,
         * 3: in front, 4: one behind and one at the near plane */
        int where[3] = {0, 0, 0};
        if (kind == 0)
            where[rnd(s) % 3] = 1;
        else if (kind == 1) {
            where[0] = where[1] = where[2] = 1;
            where[rnd(s) % 3] = 0;
        } else if (kind == 2) {
            where[rnd(s) % 3] = 2;
        } else if (kind == 4) {
            int a = (int)(rnd(s) % 3);
            where[a] = 1;
            where[(a + 1) % 3] = 2;
        }
        if (i == TRIS - 1 && rnd(s) % 2)
            where[0] = where[1] = where[2] = 1; /* wholly behind */
        uint8_t rgba[4] = {(uint8_t)(rnd(s) % 256), (uint8_t)(rnd(s) % 256),
                           (uint8_t)(rnd(s) % 256), (uint8_t)(40 + rnd(s) % 180)};
        for (int k = 0; k < 3; k++) {
            vertex(&t[i].v[k], where[k], s);
            memcpy(t[i].v[k].rgba, rgba, 4);
        }
    }
}

typedef struct paths {
    oit_dfb *dfb;
    oit_capture *array, *compute;
} paths;

static double diff_outside(const oit_image *a, const oit_image *ref, const uint8_t *amb,
                           int *where)
{
    double worst = 0.0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3 && !amb[i]; c++) {
            double d = fabs((double)a->rgba[4 * i + c] - ref->rgba[4 * i + c]);
            if (d > worst) {
                worst = d;
                *where = i;
            }
        }
    return worst;
}

static oit_status capture(oit_capture *c, const oit_gpu_mesh *m, const oit_view *v,
                          oit_image *img, oit_error *err)
{
    oit_frame_stats st;
    const oit_gpu_mesh *list[1] = {m};
    oit_status s = oit_capture_begin(c, v, err);
    if (s == OIT_OK)
        s = oit_capture_batch(c, list, 1, NULL, err);
    return s == OIT_OK ? oit_capture_end(c, img, &st, err) : s;
}

static void check_case(paths *p, int n, uint32_t *seed, int *bad, int *ambiguous)
{
    oit_triangle t[TRIS];
    scene(t, seed);
    oit_view v;
    scene_view(&v, W, H, OIT_SHADING_TRANSPARENT);
    oit_error err = {0};
    oit_mesh mesh = {.tris = t, .count = TRIS, .capacity = TRIS};
    oit_mesh_info_init(&mesh.info);
    oit_mesh_info_add(&mesh.info, t, TRIS);
    uint8_t amb[W * H] = {0};
    oit_reference_desc desc = {.ambiguous = amb};
    oit_image ref = {0}, img[3] = {{0}};
    oit_status s = oit_reference_render(&mesh, &v, &desc, &ref, NULL, NULL, &err);
    CHECK(s == OIT_OK, "case %d: reference: %s", n, err.message);
    oit_gpu_mesh *gm = NULL;
    if (s == OIT_OK)
        s = oit_gpu_mesh_create(t, TRIS, 0, &gm, &err);
    const char *names[3] = {"dfb", "array", "compute"};
    oit_status got[3] = {OIT_ERR_GL, OIT_ERR_GL, OIT_ERR_GL};
    if (s == OIT_OK) {
        oit_frame_stats st;
        const oit_gpu_mesh *list[1] = {gm};
        got[0] = oit_dfb_render(p->dfb, list, 1, &v, &img[0], NULL, &st, &err);
        got[1] = capture(p->array, gm, &v, &img[1], &err);
        got[2] = capture(p->compute, gm, &v, &img[2], &err);
    }
    for (int i = 0; i < W * H; i++)
        *ambiguous += amb[i];
    for (int m = 0; m < 3 && s == OIT_OK; m++) {
        CHECK(got[m] == OIT_OK, "case %d: %s: %s", n, names[m], err.message);
        if (got[m] != OIT_OK)
            continue;
        int where = 0;
        double d = diff_outside(&img[m], &ref, amb, &where);
        if (!(d <= 1.0 / 255) && (*bad)++ < 6)
            CHECK(0, "case %d: %s differs from the reference by %.4f at pixel (%d, %d)", n,
                  names[m], d, where % W, where / W);
        oit_image_free(&img[m]);
    }
    oit_gpu_mesh_destroy(gm);
    oit_image_free(&ref);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    paths p = {0};
    oit_error err = {0};
    oit_status s = oit_dfb_create(&p.dfb, &err);
    if (s == OIT_OK)
        s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_ARRAY,
                                                   .cut = OIT_RENDER_PACK_BUDGET, .K = K},
                               &p.array, &err);
    if (s == OIT_OK)
        s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_COMPUTE, .K = K},
                               &p.compute, &err);
    CHECK(s == OIT_OK, "set-up: %s", err.message);
    uint32_t seed = 0x3c6ef372u;
    int bad = 0, ambiguous = 0;
    for (int c = 0; s == OIT_OK && c < CASES; c++)
        check_case(&p, c, &seed, &bad, &ambiguous);
    printf("%d scenes of %d triangles across the eye and near planes, %dx%d: %d wrong, "
           "%d ambiguous pixels left out (of %d)\n", CASES, TRIS, W, H, bad, ambiguous,
           CASES * W * H);
    CHECK(ambiguous < CASES * W * H / 4, "too many ambiguous pixels: %d", ambiguous);
    oit_capture_destroy(p.compute);
    oit_capture_destroy(p.array);
    oit_dfb_destroy(p.dfb);
    return test_gl_verdict(gl);
}
