/* Opaque triangles (view/render/image/shade.h, "Opaque triangles"): screen-aligned
 * quads, some of alpha 255, through DFB, the capture in batches (array and
 * counted backends) and the Embree reference. Checked against the hand
 * result of shade.h (an opaque quad composites with a = 1, so nothing
 * behind it shows) and, for the GL methods, against the exact number of
 * fragments stored: per pixel, the quads in front of the nearest opaque
 * one and that one, never one behind it. Batches are captured front to
 * back with the opaque quad and one behind it in the same batch, so both
 * the pre-pass of a batch and of the batches before it are exercised.
 * --see-through (oit_shading.see_through) stores every fragment again. */
#include <stdio.h>
#include <stdlib.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "view/render/reference/reference.h"
#include "view/render/image/shade.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/capture_set.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "tests/view/render/opaque_scene.h"

/* QUADS in batches: [0, 1), [1, 3) with [5] first, [3, 5) */

static oit_gpu_mesh *upload(const quad_spec *q, int n, uint32_t first_prim)
{
    oit_error err = {0};
    oit_triangle *t = scene_tris(q, n);
    oit_gpu_mesh *m = NULL;
    if (oit_gpu_mesh_create(t, 2 * (size_t)n, first_prim, &m, &err) != OIT_OK)
        fprintf(stderr, "FAIL: upload: %s\n", err.message);
    free(t);
    return m;
}

static void check_dfb(const oit_view *v, int see_through)
{
    oit_error err = {0};
    oit_dfb *d = NULL;
    oit_gpu_mesh *m = upload(QUADS, NQ, 0);
    oit_image img = {0};
    oit_frame_stats st = {0};
    oit_view vv = *v;
    vv.shading.see_through = see_through;
    const oit_gpu_mesh *list[1] = {m};
    oit_status s = m ? oit_dfb_create(&d, &err) : OIT_ERR_GL;
    if (s == OIT_OK)
        s = oit_dfb_render(d, list, 1, &vv, &img, NULL, &st, &err);
    CHECK(s == OIT_OK, "dfb: %s", err.message);
    if (s == OIT_OK) {
        uint64_t want = expect_stored(&vv, see_through);
        printf("dfb%s: fragments %llu (expect %llu)", see_through ? " see-through" : "",
               (unsigned long long)st.fragments, (unsigned long long)want);
        CHECK(st.fragments == want, "dfb: %llu fragments stored, expected %llu",
              (unsigned long long)st.fragments, (unsigned long long)want);
        if (!see_through) {
            double diff = hand_max_diff(&img, &vv, QUADS, NQ);
            printf(", max_abs_diff %.6f", diff);
            CHECK(diff <= 1.0 / 255, "dfb: image differs from the hand result by %.6f", diff);
        }
        printf("\n");
    }
    oit_image_free(&img);
    oit_gpu_mesh_destroy(m);
    oit_dfb_destroy(d);
}

static void check_capture(oit_capture_kind kind, const oit_view *v)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    /* prims as in one mesh: quad i is prims 2i, 2i+1 */
    const quad_spec b1[3] = {QUADS[5], QUADS[1], QUADS[2]};
    oit_gpu_mesh *m[3] = {upload(&QUADS[0], 1, 0), upload(b1, 3, 0), upload(&QUADS[3], 2, 6)};
    oit_image img = {0};
    oit_frame_stats st = {0};
    oit_capture_desc d = {.fill = capture_fill(kind), .cut = capture_cut(kind), .K = 8};
    oit_status s = m[0] && m[1] && m[2] ? oit_capture_create(&d, &c, &err) : OIT_ERR_GL;
    if (s == OIT_OK)
        s = oit_capture_begin(c, v, &err);
    for (int b = 0; b < 3 && s == OIT_OK; b++) {
        const oit_gpu_mesh *list[1] = {m[b]};
        s = oit_capture_batch(c, list, 1, NULL, &err);
    }
    if (s == OIT_OK)
        s = oit_capture_end(c, &img, &st, &err);
    CHECK(s == OIT_OK, "capture %s: %s", oit_capture_kind_name(kind), err.message);
    if (s == OIT_OK) {
        uint64_t want = expect_stored(v, 0);
        double diff = hand_max_diff(&img, v, QUADS, NQ);
        printf("capture %s, 3 batches: fragments %llu (expect %llu), max_abs_diff %.6f\n",
               oit_capture_kind_name(kind), (unsigned long long)st.fragments,
               (unsigned long long)want, diff);
        CHECK(st.fragments == want, "capture %s: %llu fragments stored, expected %llu",
              oit_capture_kind_name(kind), (unsigned long long)st.fragments,
              (unsigned long long)want);
        CHECK(diff <= 1.0 / 255, "capture %s: image differs by %.6f", oit_capture_kind_name(kind),
              diff);
    }
    oit_image_free(&img);
    for (int i = 0; i < 3; i++)
        oit_gpu_mesh_destroy(m[i]);
    oit_capture_destroy(c);
}

/* The reference against the hand result outside the pixels it flags as
 * ambiguous (a centre on the quads' diagonals meets both triangles). */
static void check_reference(const oit_view *v)
{
    oit_error err = {0};
    oit_mesh mesh = {0};
    mesh.tris = scene_tris(QUADS, NQ);
    mesh.count = mesh.capacity = 2 * (size_t)NQ;
    oit_mesh_info_init(&mesh.info);
    oit_mesh_info_add(&mesh.info, mesh.tris, mesh.count);
    uint8_t *amb = calloc((size_t)v->width * v->height, 1);
    oit_reference_desc desc = {.ambiguous = amb};
    oit_image img = {0};
    oit_status s = amb ? oit_reference_render(&mesh, v, &desc, &img, NULL, NULL, &err) : OIT_ERR_NOMEM;
    CHECK(s == OIT_OK, "reference: %s", err.message);
    if (s == OIT_OK) {
        double worst = 0.0;
        int masked = 0;
        for (int y = 0; y < v->height; y++)
            for (int x = 0; x < v->width; x++) {
                double rgb[3];
                hand_pixel(v, QUADS, NQ, x, y, rgb);
                const float *p = &img.rgba[4 * ((size_t)y * img.width + x)];
                masked += amb[(size_t)y * v->width + x];
                for (int c = 0; c < 3 && !amb[(size_t)y * v->width + x]; c++)
                    worst = fmax(worst, fabs(p[c] - rgb[c]));
            }
        printf("reference: max_abs_diff %.6f outside %d ambiguous pixels\n", worst, masked);
        CHECK(worst <= 1.0 / 255, "reference: image differs by %.6f", worst);
        CHECK(masked < v->width * v->height / 10, "reference: %d ambiguous pixels", masked);
    }
    oit_image_free(&img);
    free(amb);
    free(mesh.tris);
}

/* Which triangles are opaque, and when. */
static void check_rule(void)
{
    oit_view v;
    scene_view(&v, 8, 8, OIT_SHADING_TRANSPARENT);
    oit_triangle t[2];
    quad_tris(&QUADS[1], t);
    CHECK(oit_triangle_opaque(&v.shading, &t[0]), "alpha 255 with OIT_ATTR_ALPHA is opaque");
    t[0].v[2].rgba[3] = 254;
    CHECK(!oit_triangle_opaque(&v.shading, &t[0]), "one vertex below 255: not opaque");
    v.shading.see_through = 1;
    CHECK(!oit_triangle_opaque(&v.shading, &t[1]), "see-through: nothing opaque");
    v.shading.see_through = 0;
    v.shading.attributes = OIT_ATTR_COLOUR;
    CHECK(!oit_triangle_opaque(&v.shading, &t[1]), "no alpha in the file: default alpha");
    v.shading.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    v.shading.mode = OIT_SHADING_TRANSLUCENT;
    CHECK(!oit_triangle_opaque(&v.shading, &t[1]), "translucent shading: not opaque");
    CHECK(!oit_shading_opaque(&v.shading), "translucent shading: no pre-pass");
    v.shading.mode = OIT_SHADING_TRANSPARENT;
    CHECK(!oit_shading_opaque(&v.shading), "no OIT_ATTR_OPAQUE: no pre-pass");
    v.shading.attributes |= OIT_ATTR_OPAQUE;
    CHECK(oit_shading_opaque(&v.shading), "OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE: the pre-pass");
}

int main(void)
{
    check_rule();
    oit_gl *gl = test_gl_open();
    oit_view v;
    scene_view(&v, 96, 64, OIT_SHADING_TRANSPARENT);
    v.shading.attributes |= OIT_ATTR_OPAQUE;
    check_dfb(&v, 0);
    check_dfb(&v, 1);
    check_capture(OIT_CAPTURE_ARRAY, &v);
    check_capture(OIT_CAPTURE_COUNTED, &v);
    check_capture(OIT_CAPTURE_FIRSTK, &v);
    check_reference(&v);
    return test_gl_verdict(gl);
}
