/* liboit over shares of a part file (oit_scene_desc.share_count, issue 38):
 * the two shares of the grid file rendered apart as premultiplied C and
 * 1 - T (OIT_PIXELS_PREMUL32F), composited by hand with the over operator
 * in the order oit_scene_share_order gives, then over the background, must
 * equal the whole file's render within 1/255 in every view along the six
 * axes and an orthographic one, in both colour spaces. The order must
 * matter: the reversed order must miss by more than 1/255 in some view
 * (else the test could not catch a wrong order), and both orders must
 * occur. The shares hold every triangle, none empty; bad share numbers, a
 * short order buffer and translucent shading over shares are refused.
 * usage: test_liboit_shares FILE.oitp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/offscreen.h"

enum { W = 64, H = 48, PX = W * H };

static int failures;

#define CHECK(cond, ...)                                                                    \
    do {                                                                                    \
        if (!(cond)) {                                                                      \
            failures++;                                                                     \
            fprintf(stderr, "FAIL: " __VA_ARGS__);                                          \
            fputc('\n', stderr);                                                            \
        }                                                                                   \
    } while (0)

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalise(double v[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= n;
}

/* gluLookAt and gluPerspective / glOrtho, column-major. */
static void frame_for(const oit_scene_info *info, int axis, int sign, int ortho, oit_frame *f)
{
    double c[3], r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)info->bounds_min[k] + info->bounds_max[k]);
        double h = 0.5 * ((double)info->bounds_max[k] - info->bounds_min[k]);
        r2 += h * h;
    }
    double r = sqrt(r2), eye[3] = {c[0], c[1], c[2]};
    /* A little off the axis, so that no split plane is seen edge-on. */
    double dir[3] = {0.05, 0.08, 0.03};
    dir[axis] = sign;
    normalise(dir);
    for (int k = 0; k < 3; k++)
        eye[k] += 3.0 * r * dir[k];
    double fw[3] = {-dir[0], -dir[1], -dir[2]}, up[3] = {0, 0, 0}, s[3], u[3];
    up[axis == 1 ? 2 : 1] = 1.0;
    cross(fw, up, s);
    normalise(s);
    cross(s, fw, u);
    memset(f, 0, sizeof *f);
    float *m = f->view;
    for (int k = 0; k < 3; k++) {
        m[4 * k] = (float)s[k];
        m[4 * k + 1] = (float)u[k];
        m[4 * k + 2] = (float)-fw[k];
    }
    m[12] = (float)-(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    m[13] = (float)-(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    m[14] = (float)(fw[0] * eye[0] + fw[1] * eye[1] + fw[2] * eye[2]);
    m[15] = 1.0f;
    double n = r, fa = 5.0 * r, aspect = (double)W / H;
    float *p = f->projection;
    if (ortho) {
        p[0] = (float)(1.0 / (1.1 * r * aspect));
        p[5] = (float)(1.0 / (1.1 * r));
        p[10] = (float)(-2.0 / (fa - n));
        p[14] = (float)(-(fa + n) / (fa - n));
        p[15] = 1.0f;
    } else {
        double t = 1.0 / tan(0.5 * 45.0 * 3.14159265358979 / 180.0);
        p[0] = (float)(t / aspect);
        p[5] = (float)t;
        p[10] = (float)((fa + n) / (n - fa));
        p[11] = -1.0f;
        p[14] = (float)(2.0 * fa * n / (n - fa));
    }
    f->viewport_width = W;
    f->viewport_height = H;
}

static oit_scene *open_share(const char *path, uint32_t count, uint32_t index)
{
    oit_scene_desc d = {.share_count = count, .share_index = index};
    oit_scene *s = NULL;
    oit_error err = {0};
    if (oit_scene_open(path, &d, &s, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: share %u of %u: %s\n", index, count, err.message);
        exit(1);
    }
    return s;
}

static int render(oit_offscreen *o, oit_scene *s, const oit_frame *f, oit_pixel_format fmt,
                  float *px)
{
    oit_offscreen_view v = {.width = W, .height = H, .format = fmt, .use_matrices = 1};
    memcpy(v.view, f->view, sizeof v.view);
    memcpy(v.projection, f->projection, sizeof v.projection);
    oit_error err = {0};
    if (oit_offscreen_render(o, s, &v, px, (size_t)PX * 4 * sizeof(float), NULL, &err) !=
        OIT_OK) {
        fprintf(stderr, "FAIL: render: %s\n", err.message);
        failures++;
        return 0;
    }
    return 1;
}

static double srgb_encode(double v)
{
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* front over back, then over the opaque white background (1 in both
 * spaces), encoded when composited in linear light; the largest
 * difference from whole. */
static double composite_diff(const float *front, const float *back, const float *whole,
                             int linear)
{
    double worst = 0.0;
    for (int i = 0; i < PX; i++) {
        const float *a = &front[4 * i], *b = &back[4 * i];
        double alpha = a[3] + (1.0 - a[3]) * b[3];
        for (int k = 0; k < 3; k++) {
            double v = a[k] + (1.0 - a[3]) * b[k] + (1.0 - alpha);
            v = linear ? srgb_encode(v) : v;
            double d = fabs(v - whole[4 * i + k]);
            worst = d > worst ? d : worst;
        }
    }
    return worst;
}

static void check_views(const char *path, oit_scene *whole, oit_scene *sh[2], int linear)
{
    oit_offscreen_desc od = {0};
    od.renderer.shading.colour_space = linear ? OIT_RENDER_COLOUR_LINEAR : OIT_RENDER_COLOUR_SRGB;
    oit_offscreen *o = NULL;
    oit_error err = {0};
    if (oit_offscreen_create(&od, &o, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: offscreen: %s\n", err.message);
        exit(1);
    }
    oit_scene_info info;
    oit_scene_get_info(whole, &info, &err);
    float *ref = malloc(sizeof(float) * 4 * PX), *p[2] = {malloc(sizeof(float) * 4 * PX),
                                                         malloc(sizeof(float) * 4 * PX)};
    double worst_reversed = 0.0;
    int first[2] = {0, 0};
    for (int view = 0; view < 7; view++) {
        oit_frame f;
        frame_for(&info, view % 3, view < 3 ? 1 : -1, view == 6, &f);
        uint32_t order[2] = {9, 9}, again[2] = {9, 9}, one[1] = {9};
        CHECK(oit_scene_share_order(sh[0], &f, order, 2, &err) == OIT_OK, "order: %s",
              err.message);
        CHECK(oit_scene_share_order(sh[1], &f, again, 2, &err) == OIT_OK, "order: %s",
              err.message);
        CHECK(oit_scene_share_order(whole, &f, one, 1, &err) == OIT_OK && one[0] == 0,
              "view %d: the whole scene's order is not {0}", view);
        CHECK(order[0] + order[1] == 1 && order[0] < 2 && order[0] == again[0] &&
                  order[1] == again[1],
              "view %d: share orders {%u, %u} and {%u, %u}: not one permutation of {0, 1}",
              view, order[0], order[1], again[0], again[1]);
        if (order[0] > 1)
            continue;
        first[order[0]]++;
        if (!render(o, whole, &f, OIT_PIXELS_RGBA32F, ref) ||
            !render(o, sh[0], &f, OIT_PIXELS_PREMUL32F, p[0]) ||
            !render(o, sh[1], &f, OIT_PIXELS_PREMUL32F, p[1]))
            continue;
        double d = composite_diff(p[order[0]], p[order[1]], ref, linear);
        double rev = composite_diff(p[order[1]], p[order[0]], ref, linear);
        CHECK(d <= 1.0 / 255.0, "%s view %d%s: shares %u over %u differ from the whole "
              "render by %g > 1/255", path, view, linear ? " linear" : "", order[0], order[1],
              d);
        worst_reversed = rev > worst_reversed ? rev : worst_reversed;
        printf("view %d%s: order %u %u, max diff %.2g (reversed %.2g)\n", view,
               linear ? " linear" : "", order[0], order[1], d, rev);
    }
    CHECK(worst_reversed > 1.0 / 255.0, "the reversed order never differs by more than 1/255: "
          "the views do not test the order");
    CHECK(first[0] > 0 && first[1] > 0, "share 0 came first in %d views, share 1 in %d: "
          "expected both", first[0], first[1]);
    /* Translucent over shares: refused, not a wrong image. */
    oit_offscreen_desc td = {0};
    td.renderer.shading.mode = OIT_RENDER_TRANSLUCENT;
    oit_offscreen *t = NULL;
    if (!linear && oit_offscreen_create(&td, &t, &err) == OIT_OK) {
        oit_frame f;
        frame_for(&info, 0, 1, 0, &f);
        oit_offscreen_view v = {.width = W, .height = H, .format = OIT_PIXELS_PREMUL32F,
                                .use_matrices = 1};
        memcpy(v.view, f.view, sizeof v.view);
        memcpy(v.projection, f.projection, sizeof v.projection);
        oit_status st = oit_offscreen_render(t, sh[0], &v, ref, sizeof(float) * 4 * PX, NULL,
                                             &err);
        CHECK(st == OIT_ERR_UNSUPPORTED && strstr(err.message, "translucent"),
              "translucent over a share: status %d, '%s'", (int)st, err.message);
        oit_offscreen_destroy(t);
    }
    free(ref);
    free(p[0]);
    free(p[1]);
    oit_offscreen_destroy(o);
}

static void check_refusals(const char *path, oit_scene *share)
{
    static const uint32_t bad[][2] = {{2, 2}, {1, 1}, {0, 3}, {5000, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        oit_scene_desc d = {.share_count = bad[i][0], .share_index = bad[i][1]};
        oit_scene *s = NULL;
        oit_error err = {0};
        oit_status st = oit_scene_open(path, &d, &s, &err);
        CHECK(st == OIT_ERR_ARGUMENT && s == NULL && strstr(err.message, "oit_scene_desc"),
              "share %u of %u: status %d, '%s'", bad[i][1], bad[i][0], (int)st, err.message);
        oit_scene_close(s);
    }
    oit_frame f = {.viewport_width = W, .viewport_height = H};
    uint32_t order[1];
    oit_error err = {0};
    CHECK(oit_scene_share_order(share, &f, order, 1, &err) == OIT_ERR_ARGUMENT &&
              strstr(err.message, "holds 1"),
          "a one-share order buffer for two shares: '%s'", err.message);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s FILE.oitp\n", argv[0]);
        return 2;
    }
    const char *path = argv[1];
    oit_scene *whole = open_share(path, 0, 0), *sh[2] = {open_share(path, 2, 0),
                                                         open_share(path, 2, 1)};
    oit_scene_info wi, si[2];
    oit_error err = {0};
    oit_scene_get_info(whole, &wi, &err);
    oit_scene_get_info(sh[0], &si[0], &err);
    oit_scene_get_info(sh[1], &si[1], &err);
    CHECK(wi.share_count == 1 && wi.share_triangles == wi.triangles,
          "whole scene: share_count %u, share_triangles %llu of %llu", wi.share_count,
          (unsigned long long)wi.share_triangles, (unsigned long long)wi.triangles);
    CHECK(si[0].share_count == 2 && si[1].share_index == 1 && si[0].share_triangles > 0 &&
              si[1].share_triangles > 0 &&
              si[0].share_triangles + si[1].share_triangles == wi.triangles &&
              si[0].share_parts + si[1].share_parts == wi.parts,
          "shares hold %llu + %llu triangles (%llu + %llu parts), the file %llu (%llu)",
          (unsigned long long)si[0].share_triangles, (unsigned long long)si[1].share_triangles,
          (unsigned long long)si[0].share_parts, (unsigned long long)si[1].share_parts,
          (unsigned long long)wi.triangles, (unsigned long long)wi.parts);
    check_views(path, whole, sh, 0);
    check_views(path, whole, sh, 1);
    check_refusals(path, sh[0]);
    oit_scene_close(whole);
    oit_scene_close(sh[0]);
    oit_scene_close(sh[1]);
    if (failures) {
        fprintf(stderr, "%d failure(s)\n", failures);
        return 1;
    }
    printf("ok: 2 shares of %s composited in the given order equal the whole render\n", path);
    return 0;
}
