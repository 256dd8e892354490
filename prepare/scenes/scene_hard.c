/* hard: small deterministic scenes that break naive OIT pipelines, one per
 * numerical or topological trap (the cases of oit_scene_hard_cases). Unlike
 * the other scenes they are not all closed or well formed: degenerate,
 * coincident, non-manifold and single-sided input is the point. */
#include "prepare/scenes/scene.h"

#include <math.h>
#include <string.h>

#include "prepare/scenes/rng.h"
#include "prepare/scenes/shapes.h"

typedef void (*hard_fn)(oit_emit *e, uint64_t seed);

/* Box with centre c and half-axes a, b, d (a right-handed frame). */
static void hard_box(oit_emit *e, oit_v3 c, oit_v3 a, oit_v3 b, oit_v3 d)
{
    oit_v3 v[8];
    for (int i = 0; i < 8; i++) {
        v[i] = oit_v3_add(c, oit_v3_scale(a, i & 1 ? 1.0f : -1.0f));
        v[i] = oit_v3_add(v[i], oit_v3_scale(b, i & 2 ? 1.0f : -1.0f));
        v[i] = oit_v3_add(v[i], oit_v3_scale(d, i & 4 ? 1.0f : -1.0f));
    }
    oit_shape_hexahedron(e, v);
}

/* Quad from corner o spanned by u and v, one-sided (front along u x v). */
static void hard_quad(oit_emit *e, oit_v3 o, oit_v3 u, oit_v3 v)
{
    uint32_t a = oit_emit_vertex(e, o), b = oit_emit_vertex(e, oit_v3_add(o, u));
    uint32_t c = oit_emit_vertex(e, oit_v3_add(oit_v3_add(o, u), v));
    uint32_t d = oit_emit_vertex(e, oit_v3_add(o, v));
    oit_emit_quad(e, a, b, c, d);
}

static void hard_color(oit_emit *e, float hue, uint8_t alpha)
{
    uint8_t rgb[3];
    oit_scene_hsv(hue, 0.8f, 0.95f, rgb);
    oit_emit_color(e, rgb[0], rgb[1], rgb[2], alpha);
}

static void coplanar_set(oit_emit *e, float s);

/* Coincident faces of opposite orientation, a box duplicated exactly (as
 * CAD exports repeat parts), three quads overlapping in one plane, and
 * coplanar_set's faces. */
static void case_coplanar(oit_emit *e, uint64_t seed)
{
    (void)seed;
    const oit_v3 x = {2, 0, 0}, y = {0, 2, 0};
    hard_color(e, 0.0f, 120);
    hard_quad(e, oit_v3_make(-1, -1, 0), x, y);
    hard_color(e, 0.6f, 120);
    hard_quad(e, oit_v3_make(-1, -1, 0), y, x);
    for (int i = 0; i < 2; i++) {
        hard_color(e, 0.3f + 0.1f * i, 100);
        oit_shape_box(e, oit_v3_make(-0.5f, -0.5f, -0.8f), oit_v3_make(0.5f, 0.5f, 0.8f));
    }
    for (int i = 0; i < 3; i++) {
        hard_color(e, 0.15f + 0.25f * i, 130);
        hard_quad(e, oit_v3_make(-1.2f + 0.5f * i, -1.2f + 0.3f * i, 0.5f),
                  oit_v3_make(1.4f, 0, 0), oit_v3_make(0, 1.4f, 0));
    }
    coplanar_set(e, 1.0f);
}

/* Overlapping coplanar faces at scale s: three quads in z = 0.3 s, three in
 * the tilted plane z = (0.5 x + 0.25 y - 0.25) s (exact in float at s = 1,
 * every corner a multiple of 1/16; at s = 1e-6 rounded), one quad drawn three times (colours
 * differ, the middle copy wound the other way), and three quads in a plane
 * turned 30 degrees about x, whose rounded corners lie only within float
 * rounding of one plane. */
static void coplanar_set(oit_emit *e, float s)
{
    for (int i = 0; i < 3; i++) {
        hard_color(e, 0.15f + 0.25f * (float)i, 130);
        hard_quad(e, oit_v3_make((-1.25f + 0.5f * (float)i) * s, (-1.25f + 0.25f * (float)i) * s, 0.3f * s),
                  oit_v3_make(1.5f * s, 0, 0), oit_v3_make(0, 1.5f * s, 0));
    }
    for (int i = 0; i < 3; i++) {
        float x = -1.0f + 0.5f * (float)i, y = -0.75f + 0.25f * (float)i;
        hard_color(e, 0.05f + 0.3f * (float)i, 120);
        hard_quad(e, oit_v3_make(x * s, y * s, (0.5f * x + 0.25f * y - 0.25f) * s),
                  oit_v3_make(1.0f * s, 0, 0.5f * s), oit_v3_make(0, 1.0f * s, 0.25f * s));
    }
    for (int i = 0; i < 3; i++) {
        hard_color(e, 0.7f + 0.1f * (float)i, 110);
        oit_v3 o = oit_v3_make(-0.5f * s, 0.9f * s, -0.75f * s);
        oit_v3 u = oit_v3_make(1.25f * s, 0, 0), v = oit_v3_make(0, 0, 1.0f * s);
        if (i == 1)
            hard_quad(e, o, v, u);
        else
            hard_quad(e, o, u, v);
    }
    const float c = 0.8660254f, sn = 0.5f; /* 30 degrees */
    for (int i = 0; i < 3; i++) {
        float a = -1.0f + 0.45f * (float)i, b = -0.9f + 0.35f * (float)i, l = 1.1f;
        hard_color(e, 0.45f + 0.12f * (float)i, 125);
        oit_v3 o = oit_v3_make(a * s, -1.4f * s + b * c * s, -1.0f * s + b * sn * s);
        hard_quad(e, o, oit_v3_make(l * s, 0, 0), oit_v3_make(0, l * c * s, l * sn * s));
    }
}

static void case_coplanar_tiny(oit_emit *e, uint64_t seed)
{
    (void)seed;
    coplanar_set(e, 1e-6f);
}

static void case_coplanar_far(oit_emit *e, uint64_t seed)
{
    (void)seed;
    coplanar_set(e, 1.0f); /* oitgen writes doubles offset by 1e7 */
}

/* A red surface and a blue decal 1e-5 above it (+y, the tools' up) with the
 * same outline, emitted after it (so a depth tie would put the surface in
 * front: ties go to the lower source index): once in y = 0, once in a plane
 * tilted 20 degrees about z, the decal moved 1e-5 along the normal. Seen
 * from above the decal must win on every pixel, from below the surface:
 * 1e-5 of a unit model is no tie (shade.h). */
static void case_decal(oit_emit *e, uint64_t seed)
{
    (void)seed;
    const float gap = 1e-5f, c = 0.9396926f, sn = 0.3420201f; /* 20 degrees */
    oit_v3 back = {0, 0, -1.2f};
    oit_v3 u[2] = {{1.2f, 0, 0}, {1.2f * c, 1.2f * sn, 0}}, n[2] = {{0, 1, 0}, {-sn, c, 0}};
    oit_v3 o[2] = {{-1.4f, 0, 0.6f}, {0.2f, -0.1f, 0.6f}};
    for (int k = 0; k < 2; k++) {
        oit_emit_color(e, 230, 20, 20, 200);
        hard_quad(e, o[k], u[k], back);
        oit_emit_color(e, 20, 20, 230, 200);
        hard_quad(e, oit_v3_add(o[k], oit_v3_scale(n[k], gap)), u[k], back);
    }
}

/* A 3 x 3 x 2 block of unit boxes touching face to face (each shared face
 * twice, wound opposite ways, in different colours) and one box resting on
 * top, half over an edge. */
static void case_touching(oit_emit *e, uint64_t seed)
{
    (void)seed;
    for (int z = 0; z < 2; z++)
        for (int y = 0; y < 3; y++)
            for (int x = 0; x < 3; x++) {
                hard_color(e, (float)((x + 3 * y + 9 * z) % 7) / 7.0f, 90);
                oit_v3 lo = oit_v3_make(0.5f * (float)x - 0.75f, 0.5f * (float)y - 0.75f, 0.5f * (float)z - 0.5f);
                oit_shape_box(e, lo, oit_v3_add(lo, oit_v3_make(0.5f, 0.5f, 0.5f)));
            }
    hard_color(e, 0.95f, 120);
    oit_shape_box(e, oit_v3_make(0.5f, -0.25f, 0.5f), oit_v3_make(1.0f, 0.25f, 1.0f));
}

/* A tube along the closed curve f (n samples), frames carried by parallel
 * transport so the tube does not twist where the curve turns. */
static void tube_loop(oit_emit *e, oit_v3 (*f)(float), int n, float r, int seg)
{
    oit_sweep s;
    oit_sweep_begin(&s, e, seg);
    oit_v3 u = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        float t = 2.0f * (float)OIT_PI * (float)i / (float)n, h = 1e-3f;
        oit_v3 tan = oit_v3_normalize(oit_v3_sub(f(t + h), f(t - h)));
        u = i == 0 ? oit_v3_perpendicular(tan)
                   : oit_v3_normalize(oit_v3_sub(u, oit_v3_scale(tan, oit_v3_dot(u, tan))));
        oit_sweep_ring(&s, f(t), u, oit_v3_cross(tan, u), r, r);
    }
    oit_sweep_close_loop(&s);
}

static oit_v3 trefoil(float t)
{
    return oit_v3_make(0.4f * (sinf(t) + 2 * sinf(2 * t)), 0.4f * (cosf(t) - 2 * cosf(2 * t)) - 3.5f,
                       -0.4f * sinf(3 * t));
}

/* A chain of five interlocking rings and a trefoil knot below it. */
static void case_rings(oit_emit *e, uint64_t seed)
{
    (void)seed;
    const oit_v3 z = {0, 0, 1}, y = {0, 1, 0};
    for (int i = 0; i < 5; i++) {
        hard_color(e, 0.2f * (float)i, 140);
        oit_shape_torus(e, oit_v3_make(-3.6f + 1.8f * (float)i, 0, 0), i & 1 ? y : z, 1.2f, 0.2f,
                        1.0f, 0, 64, 16);
    }
    hard_color(e, 0.55f, 150);
    tube_loop(e, trefoil, 192, 0.18f, 12);
}

/* Three sticks, each lying over the next one where they cross: no order of
 * the three is right from above, so a valid order needs a split. */
static void case_sticks(oit_emit *e, uint64_t seed)
{
    (void)seed;
    for (int i = 0; i < 3; i++) {
        float a0 = (float)OIT_PI * (0.5f + 2.0f * (float)i / 3.0f);
        float a1 = a0 + 2.0f * (float)OIT_PI / 3.0f;
        oit_v3 p0 = oit_v3_make(cosf(a0), sinf(a0), -0.25f), p1 = oit_v3_make(cosf(a1), sinf(a1), 0.25f);
        oit_v3 d = oit_v3_sub(p1, p0);
        oit_v3 c = oit_v3_add(p0, oit_v3_scale(d, 0.5f));
        oit_v3 ax = oit_v3_scale(d, 0.8f); /* half length: 1.6x the side */
        oit_v3 side = oit_v3_scale(oit_v3_normalize(oit_v3_cross(oit_v3_make(0, 0, 1), d)), 0.12f);
        oit_v3 up = oit_v3_scale(oit_v3_normalize(oit_v3_cross(ax, side)), 0.05f);
        hard_color(e, (float)i / 3.0f, 150);
        hard_box(e, c, ax, side, up);
    }
}

/* A grid surface p(u, v) over [0, 2pi) x [v0, v1], closed in u by joining
 * the last column to the first: straight (glue 0) or flipped in v (glue 1,
 * a Moebius seam). */
static void param_grid(oit_emit *e, oit_v3 (*p)(float, float), float v0, float v1, int nu, int nv,
                       int flip)
{
    uint32_t first = 0, prev = 0;
    for (int i = 0; i <= nu; i++) {
        uint32_t row = 0;
        for (int j = 0; j <= nv; j++) {
            float u = 2.0f * (float)OIT_PI * (float)(i % nu) / (float)nu;
            float v = v0 + (v1 - v0) * (float)j / (float)nv;
            uint32_t k = i < nu ? oit_emit_vertex(e, p(u, v)) : first + (uint32_t)(flip ? nv - j : j);
            if (j == 0)
                row = k;
        }
        if (i == 0)
            first = row;
        if (i > 0)
            for (int j = 0; j < nv; j++) {
                uint32_t a = prev + (uint32_t)j, b = prev + (uint32_t)j + 1;
                uint32_t c = i < nu ? row + (uint32_t)j : first + (uint32_t)(flip ? nv - j : j);
                uint32_t d = i < nu ? row + (uint32_t)j + 1 : first + (uint32_t)(flip ? nv - j - 1 : j + 1);
                oit_emit_quad(e, a, c, d, b);
            }
        prev = row;
    }
}

static oit_v3 moebius(float u, float v)
{
    float r = 1.0f + 0.5f * v * cosf(0.5f * u);
    return oit_v3_make(r * cosf(u) - 1.6f, r * sinf(u), 0.5f * v * sinf(0.5f * u));
}

/* The figure-8 immersion of the Klein bottle: it passes through itself
 * along a circle. */
static oit_v3 klein8(float u, float v)
{
    float w = 0.5f * (float)OIT_PI + v, r = 1.0f + 0.35f * (cosf(0.5f * u) * sinf(w) - sinf(0.5f * u) * sinf(2 * w));
    return oit_v3_make(r * cosf(u) + 1.6f, r * sinf(u),
                       0.35f * (sinf(0.5f * u) * sinf(w) + cosf(0.5f * u) * sinf(2 * w)));
}

static void case_moebius(oit_emit *e, uint64_t seed)
{
    (void)seed;
    hard_color(e, 0.08f, 140);
    param_grid(e, moebius, -0.8f, 0.8f, 96, 8, 1);
    hard_color(e, 0.6f, 120);
    /* v spans one full turn, so the figure-8 section closes on itself; its
     * u seam needs the flip (the bottle is not orientable). */
    param_grid(e, klein8, 0.0f, 2.0f * (float)OIT_PI, 64, 24, 1);
}

/* Slivers (aspect 1e6), zero-area, collinear and repeated-vertex triangles,
 * laid over a sphere so they matter for the order. */
static void case_degenerate(oit_emit *e, uint64_t seed)
{
    oit_rng r = oit_rng_make(seed, 0x4a5d);
    hard_color(e, 0.55f, 110);
    oit_shape_sphere(e, oit_v3_make(0, 0, 0), 1.0f, 48);
    hard_color(e, 0.05f, 160);
    for (int i = 0; i < 200; i++) {
        oit_v3 a = oit_v3_make(oit_rng_range(&r, -1.2f, 1.2f), oit_rng_range(&r, -1.2f, 1.2f),
                               oit_rng_range(&r, -1.2f, 1.2f));
        oit_v3 d = oit_v3_make(oit_rng_range(&r, -1, 1), oit_rng_range(&r, -1, 1), oit_rng_range(&r, -1, 1));
        oit_v3 b = oit_v3_add(a, d);
        oit_v3 mid = oit_v3_add(a, oit_v3_scale(d, 0.5f));
        uint32_t ia = oit_emit_vertex(e, a), ib = oit_emit_vertex(e, b);
        switch (i % 4) {
        case 0: /* sliver: apex 1e-6 off the base's midpoint */
            oit_emit_tri(e, ia, ib, oit_emit_vertex(e, oit_v3_add(mid, oit_v3_scale(oit_v3_perpendicular(oit_v3_normalize(d)), 1e-6f))));
            break;
        case 1: /* zero area: a vertex used twice */
            oit_emit_tri(e, ia, ib, ib);
            break;
        case 2: /* zero area through a repeated position; then three distinct
                 * points on a line of constant y and z, exactly collinear */
            oit_emit_tri(e, ia, oit_emit_vertex(e, a), ib);
            oit_emit_tri(e, ia, oit_emit_vertex(e, oit_v3_add(a, oit_v3_make(0.25f, 0, 0))),
                         oit_emit_vertex(e, oit_v3_add(a, oit_v3_make(0.75f, 0, 0))));
            break;
        default: /* a repeated vertex: same position, two indices, real area */
            oit_emit_tri(e, ia, ib, oit_emit_vertex(e, oit_v3_add(mid, oit_v3_scale(oit_v3_perpendicular(oit_v3_normalize(d)), 0.2f))));
            oit_emit_tri(e, oit_emit_vertex(e, a), ib, oit_emit_vertex(e, oit_v3_add(mid, oit_v3_scale(oit_v3_perpendicular(oit_v3_normalize(d)), -0.2f))));
            break;
        }
    }
}

/* Three sheets through the origin (z = 0, x = 0, y = 0), each a grid whose
 * vertices leave the plane by +-1e-11 in a checkerboard: neighbouring
 * triangles meet within about 1e-9 radians of flat. Near zero a float holds
 * such offsets exactly, so the input really is (barely) not planar. */
static void case_nearflat(oit_emit *e, uint64_t seed)
{
    (void)seed;
    const int n = 24;
    for (int axis = 0; axis < 3; axis++) {
        hard_color(e, (float)axis / 3.0f, 120);
        uint32_t base = 0;
        for (int i = 0; i <= n; i++)
            for (int j = 0; j <= n; j++) {
                float a = -1.0f + 2.0f * (float)i / (float)n, b = -1.0f + 2.0f * (float)j / (float)n;
                float h = (i + j) & 1 ? 1e-11f : -1e-11f;
                float c[3];
                c[axis] = h, c[(axis + 1) % 3] = a, c[(axis + 2) % 3] = b;
                uint32_t k = oit_emit_vertex(e, oit_v3_make(c[0], c[1], c[2]));
                if (i == 0 && j == 0)
                    base = k;
            }
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                uint32_t a = base + (uint32_t)(i * (n + 1) + j);
                oit_emit_quad(e, a, a + (uint32_t)(n + 1), a + (uint32_t)(n + 2), a + 1);
            }
    }
}

/* Centimetre features: plates 1e-2 apart, thin rings and a small box, about
 * 0.5 across in all; the far and tiny cases move or scale it. */
static void fine_features(oit_emit *e, float s)
{
    for (int i = 0; i < 5; i++) {
        hard_color(e, 0.12f * (float)i, 110);
        oit_shape_box(e, oit_v3_make(-0.1f * s, -0.1f * s, (0.01f * (float)i - 0.002f) * s),
                      oit_v3_make(0.1f * s, 0.1f * s, (0.01f * (float)i + 0.002f) * s));
    }
    const oit_v3 y = {0, 1, 0}, z = {0, 0, 1};
    for (int i = 0; i < 3; i++) {
        hard_color(e, 0.6f + 0.1f * (float)i, 140);
        oit_shape_torus(e, oit_v3_make((0.2f + 0.06f * (float)i) * s, 0, 0), i & 1 ? y : z, 0.04f * s,
                        0.01f * s, 1.0f, 0, 32, 8);
    }
    hard_color(e, 0.9f, 90);
    oit_shape_sphere(e, oit_v3_make(0, 0, 0.02f * s), 0.25f * s, 32);
}

static void case_far(oit_emit *e, uint64_t seed)
{
    (void)seed;
    fine_features(e, 1.0f); /* oitgen writes doubles offset by 1e7 */
}

static void case_tiny(oit_emit *e, uint64_t seed)
{
    (void)seed;
    fine_features(e, 1e-6f);
}

/* 64 slivers 1e-3 wide from one face of the [-1,1]^3 box to the opposite
 * one, crossing each other and a sphere: each crosses every grid cell on
 * its way. */
static void case_thin(oit_emit *e, uint64_t seed)
{
    oit_rng r = oit_rng_make(seed, 0x4a5d);
    hard_color(e, 0.5f, 100);
    oit_shape_sphere(e, oit_v3_make(0, 0, 0), 0.6f, 32);
    for (int i = 0; i < 64; i++) {
        int axis = i % 3;
        float p0[3], p1[3];
        for (int k = 0; k < 3; k++) {
            p0[k] = oit_rng_range(&r, -0.9f, 0.9f);
            p1[k] = oit_rng_range(&r, -0.9f, 0.9f);
        }
        p0[axis] = -1.0f, p1[axis] = 1.0f;
        oit_v3 a = oit_v3_make(p0[0], p0[1], p0[2]), b = oit_v3_make(p1[0], p1[1], p1[2]);
        oit_v3 w = oit_v3_scale(oit_v3_perpendicular(oit_v3_normalize(oit_v3_sub(b, a))), 1e-3f);
        hard_color(e, oit_rng_range(&r, 0, 1), 170);
        oit_emit_tri(e, oit_emit_vertex(e, a), oit_emit_vertex(e, b), oit_emit_vertex(e, oit_v3_add(a, w)));
    }
}

/* T-junctions (a grid whose every other cell is split in four with its
 * edge midpoints unshared by the neighbours), a book of six pages on one
 * edge, and two cubes sharing an edge and two sharing a corner. */
static void case_nonmanifold(oit_emit *e, uint64_t seed)
{
    (void)seed;
    hard_color(e, 0.1f, 130);
    const int n = 6;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            float x = -1.5f + 0.5f * (float)i, y = -1.5f + 0.5f * (float)j;
            if ((i + j) & 1) {
                hard_quad(e, oit_v3_make(x, y, 0), oit_v3_make(0.5f, 0, 0), oit_v3_make(0, 0.5f, 0));
                continue;
            }
            for (int q = 0; q < 4; q++)
                hard_quad(e, oit_v3_make(x + 0.25f * (float)(q & 1), y + 0.25f * (float)(q >> 1), 0),
                          oit_v3_make(0.25f, 0, 0), oit_v3_make(0, 0.25f, 0));
        }
    hard_color(e, 0.45f, 110);
    uint32_t s0 = oit_emit_vertex(e, oit_v3_make(-1, -1, 0.4f)), s1 = oit_emit_vertex(e, oit_v3_make(-1, 1, 0.4f));
    for (int p = 0; p < 6; p++) {
        float a = (float)OIT_PI * (float)p / 6.0f;
        oit_v3 d = oit_v3_make(cosf(a), 0, sinf(a));
        uint32_t c = oit_emit_vertex(e, oit_v3_make(-1 + d.x, 1, 0.4f + d.z));
        uint32_t b = oit_emit_vertex(e, oit_v3_make(-1 + d.x, -1, 0.4f + d.z));
        oit_emit_quad(e, s0, b, c, s1);
    }
    hard_color(e, 0.75f, 120);
    oit_shape_box(e, oit_v3_make(0.2f, -0.6f, 0.2f), oit_v3_make(0.6f, -0.2f, 0.6f));
    oit_shape_box(e, oit_v3_make(0.6f, -0.2f, 0.2f), oit_v3_make(1.0f, 0.2f, 0.6f)); /* shares an edge */
    oit_shape_box(e, oit_v3_make(1.0f, 0.2f, 0.6f), oit_v3_make(1.4f, 0.6f, 1.0f)); /* shares a corner */
}

/* 600 parallel squares between z = -1 and 1, jittered in x and y: 600
 * layers on the central pixels (the Power Plant reached 590). */
static void case_stack(oit_emit *e, uint64_t seed)
{
    oit_rng r = oit_rng_make(seed, 0x4a5d);
    for (int i = 0; i < 600; i++) {
        float z = -1.0f + 2.0f * (float)i / 599.0f;
        float jx = oit_rng_range(&r, -0.1f, 0.1f), jy = oit_rng_range(&r, -0.1f, 0.1f);
        hard_color(e, (float)i / 600.0f, 8);
        hard_quad(e, oit_v3_make(-1 + jx, -1 + jy, z), oit_v3_make(2, 0, 0), oit_v3_make(0, 2, 0));
    }
}

/* A 10^3 lattice of small tilted boxes filling [-1,1]^3: from the centre
 * the eye is inside dense geometry and the near plane cuts boxes. */
static void case_dense(oit_emit *e, uint64_t seed)
{
    oit_rng r = oit_rng_make(seed, 0x4a5d);
    const int n = 10;
    for (int i = 0; i < n * n * n; i++) {
        oit_v3 c = oit_v3_make(-1 + (2.0f * (float)(i % n) + 1) / (float)n,
                               -1 + (2.0f * (float)(i / n % n) + 1) / (float)n,
                               -1 + (2.0f * (float)(i / (n * n)) + 1) / (float)n);
        oit_v3 k = oit_v3_normalize(oit_v3_make(oit_rng_range(&r, -1, 1), oit_rng_range(&r, -1, 1), 1));
        float ang = oit_rng_range(&r, 0, (float)OIT_PI);
        float h = 0.45f / (float)n;
        oit_v3 a = oit_v3_scale(oit_v3_rotate(oit_v3_make(1, 0, 0), k, ang), h);
        oit_v3 b = oit_v3_scale(oit_v3_rotate(oit_v3_make(0, 1, 0), k, ang), h);
        oit_v3 d = oit_v3_scale(oit_v3_rotate(oit_v3_make(0, 0, 1), k, ang), h);
        hard_color(e, oit_rng_range(&r, 0, 1), 60);
        hard_box(e, c, a, b, d);
    }
}

/* Opaque and transparent together (view/render/image/shade.h, "Opaque triangles"):
 * an opaque box (alpha 255) inside a transparent sphere, a transparent
 * slab through the box, and a second opaque box outside the sphere,
 * partly in front of it. Behind the opaque faces nothing shows, and the
 * GL methods store nothing. */
static void case_mixed(oit_emit *e, uint64_t seed)
{
    (void)seed;
    hard_color(e, 0.6f, 90);
    oit_shape_sphere(e, oit_v3_make(0, 0, 0), 1.0f, 32);
    hard_color(e, 0.08f, 255);
    oit_shape_box(e, oit_v3_make(-0.4f, -0.4f, -0.4f), oit_v3_make(0.4f, 0.4f, 0.4f));
    hard_color(e, 0.33f, 140);
    oit_shape_box(e, oit_v3_make(-0.8f, -0.1f, -0.7f), oit_v3_make(0.8f, 0.1f, 0.7f));
    hard_color(e, 0.9f, 255);
    oit_shape_box(e, oit_v3_make(0.6f, -0.9f, 0.9f), oit_v3_make(1.1f, -0.5f, 1.3f));
}

typedef struct hard_case {
    const char *name;
    hard_fn fn;
} hard_case;

static const hard_case CASES[] = {
    {"coplanar", case_coplanar}, {"rings", case_rings},       {"sticks", case_sticks},
    {"moebius", case_moebius},   {"degenerate", case_degenerate}, {"nearflat", case_nearflat},
    {"far", case_far},           {"tiny", case_tiny},         {"thin", case_thin},
    {"nonmanifold", case_nonmanifold}, {"stack", case_stack}, {"dense", case_dense},
    {"coplanar_tiny", case_coplanar_tiny}, {"coplanar_far", case_coplanar_far},
    {"decal", case_decal},       {"touching", case_touching}, {"mixed", case_mixed},
};

const char *oit_scene_hard_case_name(int i)
{
    return i >= 0 && i < (int)(sizeof CASES / sizeof CASES[0]) ? CASES[i].name : NULL;
}

int oit_scene_hard_offset(const oit_scene_args *a, double offset[3])
{
    int far = a->hard_case && (!strcmp(a->hard_case, "far") || !strcmp(a->hard_case, "coplanar_far"));
    for (int k = 0; k < 3; k++)
        offset[k] = far ? 1e7 : 0.0;
    return far;
}

oit_status oit_scene_hard(oit_emit *e, const oit_scene_args *a, oit_error *err)
{
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++)
        if (a->hard_case && !strcmp(a->hard_case, CASES[i].name)) {
            CASES[i].fn(e, a->seed);
            return oit_emit_flush(e);
        }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "hard: unknown case '%s'",
                         a->hard_case ? a->hard_case : "(none)");
}
