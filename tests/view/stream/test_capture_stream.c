/* --capture through the streamer (streamer.h, oit_streamer_desc.capture)
 * over test_streamer's grid part file (parts of at most 4 layers), K=4
 * where llvmpipe offers 4 samples:
 *  - auto with the self-test standing in for a routing driver
 *    (OIT_CAPTURE_TEST_ROUTE_BY_COPY) picks stencil for first-k packs and
 *    for K-slot packs, and renders each byte for byte as array slots do;
 *  - first-k at K=8 where the driver has 4 samples takes 4 (the largest
 *    that passes), the reason for not taking 8 kept, the same image;
 *  - without the stand-in on llvmpipe: auto takes array slots with the
 *    self-test's reason in the figures, and stencil is refused with it;
 *  - stencil with counted packs is refused (they have no K-slot fill).
 * usage: test_capture_stream GRID.oitp */
#include <stdio.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/image.h"
#include "view/stream/streamer.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 96, H = 72 };

typedef struct run {
    oit_status s;
    oit_image img;
    oit_frame_stats fs;
    oit_stream_frame_stats ss;
    oit_error err;
} run;

static void render(oit_partfile *pf, const oit_view *v, oit_render_pack pack, int K,
                   oit_render_capture capture, unsigned faults, run *r)
{
    memset(r, 0, sizeof *r);
    oit_streamer_desc d = {.K = K, .capture = capture, .capture_faults = faults, .pack = pack};
    oit_streamer *st = NULL;
    r->s = oit_streamer_create(pf, &d, &st, &r->err);
    if (r->s == OIT_OK)
        r->s = oit_streamer_render(st, v, &r->img, &r->fs, &r->ss, &r->err);
    oit_streamer_destroy(st);
}

static int same(const oit_image *a, const oit_image *b)
{
    return a->rgba && b->rgba && a->width == b->width && a->height == b->height &&
           !memcmp(a->rgba, b->rgba, sizeof *a->rgba * (size_t)a->width * a->height * 4);
}

static const char *str(const char *s)
{
    return s ? s : "(null)";
}

/* pack with capture auto through the stand-in: stencil slots of `samples`,
 * the array image. */
static void routed_like_array(oit_partfile *pf, const oit_view *v, oit_render_pack pack,
                              const char *what, int K, int samples)
{
    run a, b;
    render(pf, v, pack, K, OIT_RENDER_CAPTURE_ARRAY, 0, &a);
    render(pf, v, pack, K, OIT_RENDER_CAPTURE_AUTO, OIT_CAPTURE_TEST_ROUTE_BY_COPY, &b);
    CHECK(a.s == OIT_OK && b.s == OIT_OK, "%s: %s / %s", what, a.err.message, b.err.message);
    if (a.s == OIT_OK && b.s == OIT_OK) {
        printf("%s K=%d: auto ran %s x%u (fallback '%s'), %llu fragments, %llu second-pass "
               "pixels; array %llu, %llu\n", what, K, str(b.fs.capture_slots),
               b.fs.capture_slots_k, str(b.ss.capture_fallback),
               (unsigned long long)b.fs.fragments, (unsigned long long)b.fs.second_pass_pixels,
               (unsigned long long)a.fs.fragments, (unsigned long long)a.fs.second_pass_pixels);
        CHECK(same(&a.img, &b.img), "%s: the stencil-routed image is not the array image",
              what);
        CHECK(b.fs.fragments == a.fs.fragments && b.fs.overflow_pixels == 0,
              "%s: %llu fragments (array %llu), %llu overflowed", what,
              (unsigned long long)b.fs.fragments, (unsigned long long)a.fs.fragments,
              (unsigned long long)b.fs.overflow_pixels);
        CHECK(b.fs.capture_slots && !strcmp(b.fs.capture_slots, "stencil") &&
                  b.fs.capture_slots_k == (uint32_t)samples && a.fs.capture_slots &&
                  !strcmp(a.fs.capture_slots, "array"),
              "%s: auto ran %s x%u, array %s: not stencil x%d and array", what,
              str(b.fs.capture_slots), b.fs.capture_slots_k, str(a.fs.capture_slots), samples);
        CHECK(!strcmp(str(b.ss.capture_asked), "auto") && !strcmp(str(a.ss.capture_asked), "array"),
              "%s: asked %s and %s", what, str(b.ss.capture_asked), str(a.ss.capture_asked));
        CHECK((samples < K) == (b.ss.capture_fallback[0] != 0),
              "%s: fallback reason '%s' with %d of K=%d samples", what,
              str(b.ss.capture_fallback), samples, K);
    }
    oit_image_free(&a.img);
    oit_image_free(&b.img);
}

static void driver_verdict(oit_partfile *pf, const oit_view *v)
{
    run a, s, c;
    render(pf, v, OIT_RENDER_PACK_FIRSTK, 4, OIT_RENDER_CAPTURE_AUTO, 0, &a);
    render(pf, v, OIT_RENDER_PACK_FIRSTK, 4, OIT_RENDER_CAPTURE_STENCIL, 0, &s);
    printf("llvmpipe auto: %s, fallback '%s'\nllvmpipe stencil: %s\n",
           str(a.fs.capture_slots), str(a.ss.capture_fallback), s.err.message);
    CHECK(a.s == OIT_OK && a.fs.capture_slots && !strcmp(a.fs.capture_slots, "array") &&
              strstr(a.ss.capture_fallback, "self-test failed"),
          "llvmpipe, auto: ran %s, fallback '%s': not array with the self-test's reason",
          str(a.fs.capture_slots), str(a.ss.capture_fallback));
    CHECK(s.s == OIT_ERR_GL && strstr(s.err.message, "oit_streamer_desc.capture = stencil") &&
              strstr(s.err.message, "self-test failed"),
          "llvmpipe, stencil: %s '%s', not refused with the self-test's reason",
          oit_status_name(s.s), s.err.message);
    render(pf, v, OIT_RENDER_PACK_COUNTED, 4, OIT_RENDER_CAPTURE_STENCIL,
           OIT_CAPTURE_TEST_ROUTE_BY_COPY, &c);
    CHECK(c.s == OIT_ERR_ARGUMENT && strstr(c.err.message, "counted"),
          "stencil with counted packs: %s '%s'", oit_status_name(c.s), c.err.message);
    oit_image_free(&a.img);
    oit_image_free(&s.img);
    oit_image_free(&c.img);
}

int main(int argc, char **argv)
{
    oit_partfile *pf = test_partfile_arg(argc, argv);
    oit_gl *gl = test_gl_open();
    int llvmpipe = strstr(oit_gl_renderer(gl), "llvmpipe") != NULL;
    GLint most = 0;
    glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &most);
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    oit_view v;
    memset(&v, 0, sizeof v);
    oit_camera_default(&v.camera, sum.bounds_min, sum.bounds_max, 30.0f, 20.0f);
    v.width = W;
    v.height = H;
    v.shading.attributes = sum.attributes;
    if (most >= 4) {
        routed_like_array(pf, &v, OIT_RENDER_PACK_FIRSTK, "first-k", 4, 4);
        routed_like_array(pf, &v, OIT_RENDER_PACK_BUDGET, "budget", 4, 4);
        routed_like_array(pf, &v, OIT_RENDER_PACK_DISJOINT, "disjoint", 4, 4);
        routed_like_array(pf, &v, OIT_RENDER_PACK_FIRSTK, "first-k, fewer samples", 16,
                          most >= 16 ? 16 : most >= 8 ? 8 : 4);
    }
    if (llvmpipe)
        driver_verdict(pf, &v);
    oit_partfile_close(pf);
    return test_gl_verdict(gl);
}
