/* shade.h against hand-computed values: the fragment shading terms, the
 * front-to-back composite, Beer-Lambert absorption inside a medium and the
 * (t, prim) order. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/shade.h"
#include "tests/lib/test_check.h"

#define CHECK_NEAR(got, want, tol, what)                                                  \
    do {                                                                                  \
        double g_ = (got), w_ = (want);                                                   \
        if (!(fabs(g_ - w_) <= (tol))) {                                                  \
            fprintf(stderr, "FAIL %s:%d %s: got %.9g want %.9g\n", __FILE__, __LINE__,    \
                    (what), g_, w_);                                                      \
            test_failures++;                                                              \
        }                                                                                 \
    } while (0)

static oit_shading shading(oit_shading_mode mode)
{
    oit_shading s;
    memset(&s, 0, sizeof s);
    s.mode = mode;
    s.alpha = 0.35f;
    s.default_rgb[0] = 0.85f, s.default_rgb[1] = 0.55f, s.default_rgb[2] = 0.2f;
    s.background[0] = s.background[1] = s.background[2] = 1.0f;
    s.absorption = 4.0f;
    s.scene_scale = 2.0f;
    return s;
}

static oit_shaded_fragment frag(double t, uint32_t prim, float r, float g, float b, float a)
{
    oit_shaded_fragment f;
    memset(&f, 0, sizeof f);
    f.t = t;
    f.prim = prim;
    f.front = 1;
    f.colour[0] = r, f.colour[1] = g, f.colour[2] = b;
    f.alpha = a;
    return f;
}

static void test_composite(void)
{
    oit_shading s = shading(OIT_SHADING_TRANSPARENT);
    oit_shaded_fragment f[3] = {frag(1, 0, 1, 0, 0, 0.5f), frag(2, 1, 0, 0, 1, 0.5f),
                                frag(3, 2, 0, 1, 0, 0.25f)};
    oit_pixel_state st;
    oit_pixel_begin(&st);
    for (int i = 0; i < 3; i++)
        oit_pixel_add(&st, &s, &f[i]);
    float rgb[3];
    oit_pixel_end(&st, &s, rgb);
    /* C = .5 red + .25 blue + .0625 green, T = .1875 */
    double want[3] = {0.5 + 0.1875, 0.0625 + 0.1875, 0.25 + 0.1875};
    printf("composite: %.6f %.6f %.6f (want %.6f %.6f %.6f)\n", rgb[0], rgb[1], rgb[2],
           want[0], want[1], want[2]);
    for (int c = 0; c < 3; c++)
        CHECK_NEAR(rgb[c], want[c], 1e-7, "three-fragment composite");

    s.background[0] = s.background[1] = s.background[2] = -1.0f;
    oit_pixel_end(&st, &s, rgb);
    CHECK_NEAR(rgb[0], 0.5, 1e-7, "black background (negative) adds nothing");
}

static oit_triangle tri_z0(void)
{
    /* Counter-clockwise seen from +z: its normal is +z. */
    oit_triangle t;
    memset(&t, 0, sizeof t);
    float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    unsigned char c[3][4] = {{255, 0, 0, 255}, {0, 255, 0, 128}, {0, 0, 255, 0}};
    for (int v = 0; v < 3; v++) {
        memcpy(t.v[v].pos, p[v], sizeof p[v]);
        memcpy(t.v[v].rgba, c[v], 4);
    }
    return t;
}

static void test_shade_terms(void)
{
    oit_triangle t = tri_z0();
    float bary[3] = {0.2f, 0.3f, 0.5f}; /* point (0.3, 0.5, 0) */
    /* The eye sits 4 above and 3 beside the point: ndv = 4/5. */
    float eye[3] = {0.3f + 3.0f, 0.5f, 4.0f};
    oit_shading s = shading(OIT_SHADING_TRANSPARENT);
    oit_shaded_fragment f;
    oit_shade_fragment(&s, &t, 7, bary, eye, 5.0, &f);
    double light = 0.3 + 0.7 * 0.8;
    printf("transparent default colour: %.6f %.6f %.6f a %.3f front %d\n", f.colour[0],
           f.colour[1], f.colour[2], f.alpha, f.front);
    CHECK_NEAR(f.colour[0], 0.85 * light, 1e-6, "default r * light");
    CHECK_NEAR(f.colour[2], 0.2 * light, 1e-6, "default b * light");
    CHECK_NEAR(f.alpha, 0.35, 1e-7, "default alpha");
    if (!f.front || f.prim != 7 || f.t != 5.0) {
        fprintf(stderr, "FAIL front/prim/t not carried\n");
        test_failures++;
    }

    s.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    oit_shade_fragment(&s, &t, 7, bary, eye, 5.0, &f);
    CHECK_NEAR(f.colour[0], 0.2 * light, 1e-6, "interpolated r");
    CHECK_NEAR(f.colour[1], 0.3 * light, 1e-6, "interpolated g");
    CHECK_NEAR(f.colour[2], 0.5 * light, 1e-6, "interpolated b");
    CHECK_NEAR(f.alpha, (0.2 * 255 + 0.3 * 128) / 255.0, 1e-6, "interpolated alpha");

    float below[3] = {0.3f, 0.5f - 3.0f, -4.0f};
    oit_shade_fragment(&s, &t, 7, bary, below, 5.0, &f);
    if (f.front) {
        fprintf(stderr, "FAIL triangle seen from -z must be a back face\n");
        test_failures++;
    }
    CHECK_NEAR(f.colour[0], 0.2 * light, 1e-6, "back face lit by |n.v|");

    s = shading(OIT_SHADING_TRANSLUCENT);
    s.attributes = OIT_ATTR_COLOUR;
    oit_shade_fragment(&s, &t, 7, bary, eye, 5.0, &f);
    double fresnel = 0.04 + 0.96 * pow(1.0 - 0.8, 5.0);
    printf("translucent: colour %.6f alpha %.6f (want %.6f %.6f)\n", f.colour[0], f.alpha,
           light, fresnel);
    CHECK_NEAR(f.colour[1], light, 1e-6, "translucent white");
    CHECK_NEAR(f.alpha, fresnel, 1e-6, "Schlick alpha");
    CHECK_NEAR(f.base[2], 0.5, 1e-6, "medium colour");
}

static void test_absorption(void)
{
    oit_shading s = shading(OIT_SHADING_TRANSLUCENT);
    oit_shaded_fragment in = frag(1.5, 0, 0, 0, 0, 0.0f), out = frag(4.0, 1, 0, 0, 0, 0.0f),
                        later = frag(9.0, 2, 0, 0, 0, 0.0f);
    in.base[0] = 0.2f, in.base[1] = 0.5f, in.base[2] = 1.0f;
    out.front = 0;
    later.front = 0; /* a stray back face after the medium closed: no absorption */
    oit_pixel_state st;
    oit_pixel_begin(&st);
    oit_pixel_add(&st, &s, &in);
    oit_pixel_add(&st, &s, &out);
    oit_pixel_add(&st, &s, &later);
    double d = 2.5, per = 4.0 / 2.0;
    for (int c = 0; c < 3; c++) {
        double want = exp(-per * (1.0 - in.base[c]) * d);
        printf("absorption channel %d: T %.9f want %.9f\n", c, st.T[c], want);
        CHECK_NEAR(st.T[c], want, 1e-12, "exp(-sigma d)");
    }
    if (st.nest != 0) {
        fprintf(stderr, "FAIL nest %d after leaving the medium\n", st.nest);
        test_failures++;
    }
}

static void test_tie_order(void)
{
    oit_shaded_fragment f[5] = {frag(2, 9, 0, 0, 1, .5f), frag(1, 5, 1, 0, 0, .5f),
                                frag(1, 2, 0, 1, 0, .5f), frag(0.5, 40, 1, 1, 1, .5f),
                                frag(1, 3, 0, 0, 0, .5f)};
    qsort(f, 5, sizeof f[0], oit_shaded_fragment_cmp);
    uint32_t want[5] = {40, 2, 3, 5, 9};
    printf("sorted prims:");
    for (int i = 0; i < 5; i++) {
        printf(" %u", f[i].prim);
        if (f[i].prim != want[i])
            test_failures++;
    }
    printf("\n");

    /* Equal depth, different colour: order decides the pixel. */
    oit_shading s = shading(OIT_SHADING_TRANSPARENT);
    oit_pixel_state st;
    oit_pixel_begin(&st);
    oit_pixel_add(&st, &s, &f[1]); /* green, prim 2 */
    oit_pixel_add(&st, &s, &f[3]); /* red, prim 5 */
    float rgb[3];
    oit_pixel_end(&st, &s, rgb);
    CHECK_NEAR(rgb[1], 0.5 + 0.25, 1e-7, "lower prim composited first");
    CHECK_NEAR(rgb[0], 0.25 + 0.25, 1e-7, "higher prim behind");
}

static void set_tri(oit_triangle *t, const float p[3][3])
{
    memset(t, 0, sizeof *t);
    for (int v = 0; v < 3; v++)
        memcpy(t->v[v].pos, p[v], sizeof p[v]);
}

static float key_along(const oit_triangle *t, const float eye[3], const float dir[3])
{
    float n[3], d;
    oit_depth_plane(t, eye, n, &d);
    return oit_depth_key(n, d, dir, 1.0f);
}

/* The tie rule's depth (shade.h): triangles of one plane with different
 * vertices, either winding, give the same key along any ray, at scales
 * from 2^-20 to 2^13; a face 1e-5 of the scale in front of it does not; the key clears
 * exactly the low bits and keeps the order. */
static void test_depth_key(void)
{
    int ties = 0, rays = 0, decal_ties = 0;
    for (int si = 0; si < 3; si++) {
        const float sc = si == 0 ? 0x1p-20f : si == 1 ? 1.0f : 0x1p13f;
        /* Plane z = 0.5 x + 0.25 y - 0.25: every corner exact in float at
         * these power-of-two scales. */
        const float a[3][3] = {{-1, -1, -1}, {1, -1, 0}, {1, 1, 0.5f}};
        const float b[3][3] = {{0.5f, 0.5f, 0.125f}, {-0.75f, 0.25f, -0.5625f}, {0.25f, -1, -0.375f}};
        const float c[3][3] = {{0.5f, 0.5f, 0.125f}, {0.25f, -1, -0.375f}, {-0.75f, 0.25f, -0.5625f}};
        float pa[3][3], pb[3][3], pc[3][3], pd[3][3];
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                pa[v][k] = a[v][k] * sc, pb[v][k] = b[v][k] * sc, pc[v][k] = c[v][k] * sc;
                pd[v][k] = pb[v][k] + (k == 2 ? 1e-5f * sc : 0.0f);
            }
        oit_triangle ta, tb, tc, td;
        set_tri(&ta, pa), set_tri(&tb, pb), set_tri(&tc, pc), set_tri(&td, pd);
        const float eye[3] = {0.3f * sc, -0.2f * sc, 3.0f * sc};
        for (int i = 0; i < 200; i++) {
            float dir[3] = {-0.1f + 0.002f * (float)i, 0.05f - 0.001f * (float)i, -1.0f};
            float l = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int k = 0; k < 3; k++)
                dir[k] /= l;
            float ka = key_along(&ta, eye, dir), kb = key_along(&tb, eye, dir);
            float kc = key_along(&tc, eye, dir), kd = key_along(&td, eye, dir);
            rays++;
            ties += ka == kb && kb == kc;
            decal_ties += !(kd < kb);
        }
    }
    printf("depth key: %d of %d rays tie three coplanar triangles, decal in front on %d\n", ties,
           rays, rays - decal_ties);
    if (ties != rays || decal_ties) {
        fprintf(stderr, "FAIL %s:%d depth key: coplanar ties %d/%d, decal ties %d\n", __FILE__,
                __LINE__, ties, rays, decal_ties);
        test_failures++;
    }
    float t = 3.14159f, q = oit_depth_quantise(t);
    uint32_t tb_, qb;
    memcpy(&tb_, &t, 4), memcpy(&qb, &q, 4);
    CHECK_NEAR(qb, tb_ & ~(uint32_t)OIT_DEPTH_KEY_MASK, 0, "quantise clears the low bits");
    CHECK_NEAR(oit_depth_quantise(nextafterf(q, 10.0f)), q, 0, "a step up shares the key");
    CHECK_NEAR(OIT_DEPTH_KEY_MASK, (1u << OIT_DEPTH_KEY_DROP_BITS) - 1u, 0, "mask and bits agree");
}

static unsigned char to_8bit(float v)
{
    return v <= 0.0f ? 0 : v >= 1.0f ? 255 : (unsigned char)lrintf(v * 255.0f);
}

/* The colour space (shade.h): the exact sRGB transfer functions, and 50%
 * red (255,0,0,128) over white seen head-on (light 1): 255,127,127 on the
 * encoded values, encode(1 - 128/255) = 187.19 -> 255,187,187 in linear
 * light. The vertex colours are decoded per vertex, before interpolation. */
/* t shaded at bary, seen from eye (the fragment in *f), alone over s's
 * background: the pixel in rgb. */
static void shade_alone(const oit_shading *s, const oit_triangle *t, const float bary[3],
                        const float eye[3], oit_shaded_fragment *f, float rgb[3])
{
    oit_shade_fragment(s, t, 0, bary, eye, 5.0, f);
    oit_pixel_state st;
    oit_pixel_begin(&st);
    oit_pixel_add(&st, s, f);
    oit_pixel_end(&st, s, rgb);
}

static void test_colour_space(void)
{
    CHECK_NEAR(oit_srgb_decode(0.5), 0.214041140482232, 1e-12, "sRGB EOTF(0.5), not 0.5^2.2");
    CHECK_NEAR(oit_srgb_decode(0.04045), 0.04045 / 12.92, 1e-15, "EOTF linear segment");
    CHECK_NEAR(oit_srgb_decode(1.0), 1.0, 1e-15, "EOTF(1)");
    CHECK_NEAR(oit_srgb_encode(0.0031308), 0.0031308 * 12.92, 1e-15, "OETF linear segment");
    CHECK_NEAR(oit_srgb_encode(127.0 / 255.0) * 255.0, 187.186337819, 1e-6, "OETF(127/255)");
    CHECK_NEAR(oit_srgb_decode(-0.5), 0.0, 0.0, "EOTF of a negative");
    for (int i = 0; i <= 255; i++)
        CHECK_NEAR(oit_srgb_encode(oit_srgb_decode(i / 255.0)), i / 255.0, 1e-12,
                   "encode(decode(x)) = x");

    oit_triangle t;
    memset(&t, 0, sizeof t);
    float p[3][3] = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int v = 0; v < 3; v++) {
        memcpy(t.v[v].pos, p[v], sizeof p[v]);
        t.v[v].rgba[0] = 255, t.v[v].rgba[3] = 128;
    }
    float bary[3] = {0.25f, 0.25f, 0.5f}; /* (0, 0, 0) */
    float eye[3] = {0, 0, 5};
    const unsigned char want[2][3] = {{255, 127, 127}, {255, 187, 187}};
    for (int lin = 0; lin < 2; lin++) {
        oit_shading s = shading(OIT_SHADING_TRANSPARENT);
        s.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
        s.colour_space = lin ? OIT_COLOUR_LINEAR : OIT_COLOUR_SRGB;
        oit_shaded_fragment f;
        float rgb[3];
        shade_alone(&s, &t, bary, eye, &f, rgb);
        printf("50%% red over white, %s: %.6f %.6f %.6f -> %d,%d,%d\n", lin ? "linear" : "srgb",
               rgb[0], rgb[1], rgb[2], to_8bit(rgb[0]), to_8bit(rgb[1]), to_8bit(rgb[2]));
        for (int c = 0; c < 3; c++)
            if (to_8bit(rgb[c]) != want[lin][c]) {
                fprintf(stderr, "FAIL 50%% red over white (%s) channel %d: %d, want %d\n",
                        lin ? "linear" : "srgb", c, to_8bit(rgb[c]), want[lin][c]);
                test_failures++;
            }
    }

    /* Per-vertex decoding: halfway between black and white vertices is
     * decode(1) / 2 = 0.5 linear (encoded 0.735), not decode(0.5) = 0.214. */
    t.v[0].rgba[0] = t.v[0].rgba[1] = t.v[0].rgba[2] = 0;
    t.v[1].rgba[0] = t.v[1].rgba[1] = t.v[1].rgba[2] = 0;
    t.v[2].rgba[0] = t.v[2].rgba[1] = t.v[2].rgba[2] = 255;
    oit_shading s = shading(OIT_SHADING_TRANSPARENT);
    s.attributes = OIT_ATTR_COLOUR;
    s.colour_space = OIT_COLOUR_LINEAR;
    oit_shaded_fragment f;
    oit_shade_fragment(&s, &t, 0, bary, eye, 5.0, &f);
    CHECK_NEAR(f.colour[1], 0.5, 1e-6, "linear: vertex colours decoded before interpolation");

    /* Default colour and background decoded, the result encoded: alpha
     * .35 of default_rgb over a background of 0.5 grey. */
    s.attributes = 0;
    s.background[0] = s.background[1] = s.background[2] = 0.5f;
    float rgb[3];
    shade_alone(&s, &t, bary, eye, &f, rgb);
    for (int c = 0; c < 3; c++) {
        double d = oit_srgb_decode(s.default_rgb[c]);
        CHECK_NEAR(f.colour[c], d, 1e-6, "linear: default_rgb decoded");
        CHECK_NEAR(rgb[c], oit_srgb_encode(0.35 * d + 0.65 * oit_srgb_decode(0.5)), 1e-6,
                   "linear: default colour over a decoded background, encoded");
    }
    s.colour_space = OIT_COLOUR_SRGB;
    shade_alone(&s, &t, bary, eye, &f, rgb);
    CHECK_NEAR(rgb[0], 0.35 * 0.85 + 0.65 * 0.5, 1e-6, "srgb: the encoded values as given");
}

int main(void)
{
    test_composite();
    test_shade_terms();
    test_absorption();
    test_tie_order();
    test_depth_key();
    test_colour_space();
    return test_verdict();
}
