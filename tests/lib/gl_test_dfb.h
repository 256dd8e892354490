/* What the capture tests compare against: DFB on a quad scene
 * (gl_test_scene.h), the worst channel difference of two images, and a quad
 * spelled in one call. Needs a current GL context. */
#ifndef OIT_TESTS_GL_TEST_DFB_H
#define OIT_TESTS_GL_TEST_DFB_H

#include <math.h>
#include <stdio.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "tests/lib/gl_test_scene.h"

/* DFB's image and figures of the n quads q (one mesh), into img and st;
 * 1 on success, else 0 after a FAIL line. */
static inline int dfb_scene(const oit_view *v, const quad_spec *q, int n, oit_image *img,
                            oit_frame_stats *st)
{
    oit_error err = {0};
    oit_dfb *d = NULL;
    oit_gpu_mesh *m = NULL;
    oit_triangle *tris = scene_tris(q, n);
    oit_status s = oit_dfb_create(&d, &err);
    if (s == OIT_OK)
        s = oit_gpu_mesh_create(tris, 2 * (size_t)n, 0, &m, &err);
    const oit_gpu_mesh *list[1] = {m};
    if (s == OIT_OK)
        s = oit_dfb_render(d, list, 1, v, img, NULL, st, &err);
    oit_gpu_mesh_destroy(m);
    oit_dfb_destroy(d);
    free(tris);
    if (s != OIT_OK)
        fprintf(stderr, "FAIL: DFB: %s\n", err.message);
    return s == OIT_OK;
}

/* Captures q in batches [start[i], start[i+1]), batch i within rects[i]
 * (rects or rects[i] NULL: the frame), one mesh a batch, into img and st. */
static inline oit_status capture_quads(oit_capture *c, const oit_view *v, const quad_spec *q,
                                       const int *start, int nb, const int (*rects)[4],
                                       oit_image *img, oit_frame_stats *st, oit_error *err)
{
    oit_triangle *tris = scene_tris(q, start[nb]);
    oit_status s = tris ? oit_capture_begin(c, v, err) : OIT_ERR_NOMEM;
    for (int b = 0; s == OIT_OK && b < nb; b++) {
        oit_gpu_mesh *m = NULL;
        int n = start[b + 1] - start[b];
        s = oit_gpu_mesh_create(tris + 2 * start[b], 2 * (size_t)n, 2u * (uint32_t)start[b], &m,
                                err);
        const oit_gpu_mesh *list[1] = {m};
        if (s == OIT_OK)
            s = oit_capture_batch(c, list, 1, rects ? rects[b] : NULL, err);
        oit_gpu_mesh_destroy(m);
    }
    if (s == OIT_OK)
        s = oit_capture_end(c, img, st, err);
    free(tris);
    return s;
}

/* The largest absolute difference of any channel of two images of one size. */
static inline double image_diff(const oit_image *a, const oit_image *b)
{
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)a->width * a->height * 4; i++)
        worst = fmax(worst, fabs(a->rgba[i] - b->rgba[i]));
    return worst;
}

static inline quad_spec mk(float z, float half, int r, int g, int b, int a, int front)
{
    return (quad_spec){z, half, {(uint8_t)r, (uint8_t)g, (uint8_t)b, (uint8_t)a}, front};
}

#endif
