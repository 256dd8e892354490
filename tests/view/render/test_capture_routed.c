/* The stencil-routed paths of the capture (capture.h,
 * oit_capture_desc.stencil_k) everywhere but the routing draw itself: with
 * OIT_CAPTURE_TEST_ROUTE_BY_COPY each fragment is put in the sample stencil
 * routing would give it, so on llvmpipe, which does not route, the
 * self-test must pass and the routed captures must give the array
 * captures' images byte for byte, over a random scene of partly
 * overlapping triangles deeper than the samples:
 *  - STENCIL at K: the image of ARRAY at K (no pixel over K there: the
 *    scene's depth is checked first);
 *  - FIRSTK with its first pass routed into 2..K samples: DFB's image, and
 *    the second pass taken by exactly the pixels whose DFB count exceeds
 *    the samples (overflow found from the exact count, none lost); the
 *    figures say "stencil" and the samples.
 * Without the stand-in, llvmpipe's own verdict refuses both. */
#include <stdio.h>
#include <string.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/image.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "tests/lib/test_rng.h"

enum { W = 40, H = 32, TRIS = 10 };

/* Triangles over the view's centre, each at its own depth, so that pixels
 * get from 0 to several fragments and edges cross pixels partly. */
static void random_scene(oit_triangle *t, int n, uint64_t seed)
{
    rng r = {seed};
    for (int i = 0; i < n; i++) {
        float z = -2.0f - 0.1f * (float)i;
        for (int k = 0; k < 3; k++) {
            oit_vertex *v = &t[i].v[k];
            v->pos[0] = ((float)rnd(&r, 2000) / 1000.0f - 1.0f) * 1.6f;
            v->pos[1] = ((float)rnd(&r, 2000) / 1000.0f - 1.0f) * 1.6f;
            v->pos[2] = z;
            v->rgba[0] = (uint8_t)rnd(&r, 256);
            v->rgba[1] = (uint8_t)rnd(&r, 256);
            v->rgba[2] = (uint8_t)rnd(&r, 256);
            v->rgba[3] = (uint8_t)(60 + rnd(&r, 150));
        }
    }
}

static oit_status render(oit_capture *c, const oit_gpu_mesh *m, const oit_view *v,
                         oit_image *out, oit_frame_stats *st, oit_error *err)
{
    const oit_gpu_mesh *list[1] = {m};
    oit_status s = oit_capture_begin(c, v, err);
    if (s == OIT_OK)
        s = oit_capture_batch(c, list, 1, NULL, err);
    if (s == OIT_OK)
        s = oit_capture_end(c, out, st, err);
    return s;
}

static int same(const oit_image *a, const oit_image *b)
{
    return a->width == b->width && a->height == b->height &&
           !memcmp(a->rgba, b->rgba, sizeof *a->rgba * (size_t)a->width * a->height * 4);
}

typedef struct truth {
    oit_image img;
    uint32_t counts[W * H];
    uint32_t deepest;
} truth;

static void stencil_vs_array(const oit_gpu_mesh *m, const oit_view *v, const truth *t, int K)
{
    oit_error err = {0};
    oit_capture *routed = NULL, *array = NULL;
    oit_image a = {0}, b = {0};
    oit_frame_stats sa = {0}, sb = {0};
    oit_status s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_STENCIL,
                                                          .cut = OIT_RENDER_PACK_BUDGET,
                                                          .K = K, .stencil_k = K,
                                                          .faults = OIT_CAPTURE_TEST_ROUTE_BY_COPY},
                                      &routed, &err);
    CHECK(s == OIT_OK, "stencil K=%d routed by copies: the self-test refused it: %s", K,
          err.message);
    if (s != OIT_OK)
        return;
    s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_ARRAY,
                                               .cut = OIT_RENDER_PACK_BUDGET, .K = K},
        &array, &err);
    if (s == OIT_OK)
        s = render(routed, m, v, &a, &sa, &err);
    if (s == OIT_OK)
        s = render(array, m, v, &b, &sb, &err);
    CHECK(s == OIT_OK, "stencil K=%d: %s", K, err.message);
    if (s == OIT_OK) {
        printf("stencil K=%d: %llu fragments, %llu overflow; slots %s %u\n", K,
               (unsigned long long)sa.fragments, (unsigned long long)sa.overflow_pixels,
               sa.capture_slots ? sa.capture_slots : "-", sa.capture_slots_k);
        CHECK(same(&a, &b) && same(&a, &t->img), "stencil K=%d: not the array capture's and "
              "DFB's image", K);
        CHECK(sa.overflow_pixels == 0 && sa.fragments == sb.fragments,
              "stencil K=%d: %llu fragments, %llu overflowed; array %llu", K,
              (unsigned long long)sa.fragments, (unsigned long long)sa.overflow_pixels,
              (unsigned long long)sb.fragments);
        CHECK(sa.capture_slots && !strcmp(sa.capture_slots, "stencil") &&
              sa.capture_slots_k == (uint32_t)K && sb.capture_slots &&
              !strcmp(sb.capture_slots, "array"),
              "stencil K=%d: the figures say slots %s/%u and %s", K,
              sa.capture_slots ? sa.capture_slots : "-", sa.capture_slots_k,
              sb.capture_slots ? sb.capture_slots : "-");
    }
    oit_image_free(&a);
    oit_image_free(&b);
    oit_capture_destroy(routed);
    oit_capture_destroy(array);
}

static void firstk_routed(const oit_gpu_mesh *m, const oit_view *v, const truth *t, int K,
                          int samples)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    oit_image a = {0};
    oit_frame_stats st = {0};
    oit_status s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_STENCIL,
                                                          .cut = OIT_RENDER_PACK_FIRSTK,
                                                          .K = K, .stencil_k = samples,
                                                          .faults = OIT_CAPTURE_TEST_ROUTE_BY_COPY},
                                      &c, &err);
    CHECK(s == OIT_OK, "first-k K=%d routed into %d samples: %s", K, samples, err.message);
    if (s != OIT_OK)
        return;
    s = render(c, m, v, &a, &st, &err);
    CHECK(s == OIT_OK, "first-k routed %d: %s", samples, err.message);
    uint64_t deeper = 0;
    for (int i = 0; i < W * H; i++)
        deeper += t->counts[i] > (uint32_t)samples;
    if (s == OIT_OK) {
        printf("first-k K=%d routed into %d: second pass %llu pixels (DFB: %llu over %d), "
               "%u packs\n", K, samples, (unsigned long long)st.second_pass_pixels,
               (unsigned long long)deeper, samples, st.second_pass_packs);
        CHECK(deeper > 0, "the scene gives no pixel more than %d fragments", samples);
        CHECK(same(&a, &t->img), "first-k routed into %d samples: not DFB's image", samples);
        CHECK(st.second_pass_pixels == deeper && st.second_pass_packs == 1,
              "first-k routed into %d: %llu pixels took the second pass, %llu have more "
              "fragments", samples, (unsigned long long)st.second_pass_pixels,
              (unsigned long long)deeper);
        CHECK(st.overflow_pixels == 0, "first-k routed: %llu pixels flagged as lost",
              (unsigned long long)st.overflow_pixels);
        CHECK(st.capture_slots && !strcmp(st.capture_slots, "stencil") &&
              st.capture_slots_k == (uint32_t)samples,
              "first-k routed: the figures say slots %s/%u",
              st.capture_slots ? st.capture_slots : "-", st.capture_slots_k);
    }
    oit_image_free(&a);
    oit_capture_destroy(c);
}

/* Without the stand-in, this driver's own verdict: where it does not route
 * (llvmpipe), both routed captures are refused with a reason. */
static void plain(int K, int llvmpipe)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    oit_status s = oit_capture_create(&(oit_capture_desc){.fill = OIT_RENDER_CAPTURE_STENCIL,
                                                          .cut = OIT_RENDER_PACK_FIRSTK,
                                                          .K = K, .stencil_k = K}, &c, &err);
    printf("first-k K=%d routed, no stand-in: %s\n", K, s == OIT_OK ? "accepted" : err.message);
    if (llvmpipe)
        CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "self-test failed"),
              "llvmpipe: first-k routed without the stand-in was not refused by the "
              "self-test (%s)", s == OIT_OK ? "accepted" : err.message);
    oit_capture_destroy(s == OIT_OK ? c : NULL);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    int llvmpipe = strstr(oit_gl_renderer(gl), "llvmpipe") != NULL;
    GLint most = 0;
    glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &most);
    int K = most >= 8 ? 8 : 4;
    oit_view v;
    scene_view(&v, W, H, OIT_SHADING_TRANSPARENT);
    oit_triangle tris[TRIS];
    oit_error err = {0};
    oit_gpu_mesh *m = NULL;
    oit_dfb *d = NULL;
    static truth t;
    oit_frame_stats ds;
    oit_status s = OIT_OK;
    /* a scene deep enough for first-k's second pass, shallow enough for K */
    uint64_t seed = 7;
    for (int tries = 0; tries < 64; tries++, seed++) {
        random_scene(tris, TRIS, seed);
        s = oit_gpu_mesh_create(tris, TRIS, 0, &m, &err);
        if (s == OIT_OK && !d)
            s = oit_dfb_create(&d, &err);
        const oit_gpu_mesh *list[1] = {m};
        if (s == OIT_OK)
            s = oit_dfb_render(d, list, 1, &v, &t.img, t.counts, &ds, &err);
        if (s != OIT_OK)
            break;
        t.deepest = ds.max_layers;
        if (t.deepest == (uint32_t)K)
            break;
        oit_image_free(&t.img);
        oit_gpu_mesh_destroy(m);
        m = NULL;
    }
    CHECK(s == OIT_OK && m, "scene: %s", err.message);
    if (s == OIT_OK && m) {
        printf("scene seed %llu: deepest pixel %u fragments, K=%d\n",
               (unsigned long long)seed, t.deepest, K);
        stencil_vs_array(m, &v, &t, K);
        for (int samples = 2; samples <= K; samples *= 2)
            if (samples < (int)t.deepest)
                firstk_routed(m, &v, &t, K, samples);
        plain(K, llvmpipe);
    }
    oit_image_free(&t.img);
    oit_dfb_destroy(d);
    oit_gpu_mesh_destroy(m);
    return test_gl_verdict(gl);
}
