/* The pick's ordering (view/render/pick/pick.h), on hits made by hand
 * where the walk rarely makes them:
 * - two pieces of one source triangle met at their seam (a part file's
 *   clipped triangle, both pieces on the ray) are one layer, the nearer;
 * - equal depth keys break by source index, whatever order the hits came;
 * - a hit outside [znear, zfar] or cut away by a section plane is no layer;
 * - a walk over a two-triangle mesh finds the one the ray meets and not
 *   the other, and the part of a hit in core is OIT_PICK_NO_PART. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/lib/test_check.h"
#include "view/render/pick/pick.h"

/* A square at z from -1..1 in x and y, facing +z, as two triangles. */
static oit_triangle tri_at(float z, int second, uint8_t red)
{
    oit_triangle t;
    memset(&t, 0, sizeof t);
    const float a[3][2] = {{-1, -1}, {1, -1}, {1, 1}}, b[3][2] = {{-1, -1}, {1, 1}, {-1, 1}};
    for (int v = 0; v < 3; v++) {
        t.v[v].pos[0] = second ? b[v][0] : a[v][0];
        t.v[v].pos[1] = second ? b[v][1] : a[v][1];
        t.v[v].pos[2] = z;
        t.v[v].rgba[0] = red;
        t.v[v].rgba[3] = 128;
    }
    return t;
}

static void view_of(oit_view *v)
{
    memset(v, 0, sizeof *v);
    v->camera = (oit_camera){.eye = {0, 0, 5}, .up = {0, 1, 0}, .fovy_deg = 40,
                             .znear = 0.5f, .zfar = 20.0f};
    v->width = v->height = 9;
    v->shading.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    v->shading.scene_scale = 1.0f;
    oit_shading_resolve_defaults(&v->shading);
}

static oit_pick_hit hit(const oit_pick_ray *r, float z, uint64_t source, uint32_t part)
{
    oit_pick_hit h;
    memset(&h, 0, sizeof h);
    h.tri = tri_at(z, 0, (uint8_t)(40 * source));
    h.source = source;
    h.part = part;
    h.t = (float)((z - r->org[2]) / r->dir[2]);
    h.u = h.v = 0.25f;
    return h;
}

static size_t compose(const oit_pick_ray *r, oit_pick_hits *hits, oit_pick_layer *out, size_t cap)
{
    return oit_pick_compose(r, hits, out, cap);
}

static void check_pieces_and_ties(const oit_pick_ray *r)
{
    oit_pick_hits hits = {0};
    oit_error err = {0};
    /* source 7 twice (two pieces, parts 3 and 4, the second a hair
     * further), sources 9 and 2 at one depth, source 5 behind */
    const oit_pick_hit in[5] = {hit(r, 0.5f, 9, 1), hit(r, 0.0f, 5, 2), hit(r, 1.0f, 7, 4),
                                hit(r, 0.5f, 2, 0), hit(r, 1.0f, 7, 3)};
    for (int i = 0; i < 5; i++)
        CHECK(oit_pick_hits_add(&hits, &in[i], &err) == OIT_OK, "%s", err.message);
    hits.h[2].t += 1e-6f; /* part 4's piece: further */
    oit_pick_layer l[8];
    size_t n = compose(r, &hits, l, 8);
    CHECK(n == 4, "%zu layers, want 4 (the two pieces of source 7 one layer)", n);
    static const uint64_t want[4] = {7, 2, 9, 5};
    for (size_t i = 0; i < n && i < 4; i++)
        CHECK(l[i].source_triangle == want[i], "layer %zu is source %llu, want %llu", i,
              (unsigned long long)l[i].source_triangle, (unsigned long long)want[i]);
    CHECK(n >= 1 && l[0].part == 3, "source 7's layer is part %u's piece, want 3's (nearer)",
          n ? l[0].part : 0);
    CHECK(n >= 3 && l[1].depth == l[2].depth, "sources 2 and 9 are not at one key");
    oit_pick_hits_free(&hits);
}

static void check_dropped(const oit_pick_ray *r, oit_view *v)
{
    oit_pick_hits hits = {0};
    oit_error err = {0};
    const oit_pick_hit in[2] = {hit(r, 4.8f, 1, 0), hit(r, 0.0f, 2, 0)}; /* 0.2 from the eye */
    for (int i = 0; i < 2; i++)
        CHECK(oit_pick_hits_add(&hits, &in[i], &err) == OIT_OK, "%s", err.message);
    oit_pick_layer l[4];
    size_t n = compose(r, &hits, l, 4);
    CHECK(n == 1 && l[0].source_triangle == 2, "a hit before znear is a layer (%zu)", n);
    oit_pick_hits_free(&hits);
    /* keep z <= -0.5: the hit at z = 0 goes */
    v->clip.count = 1;
    v->clip.plane[0][2] = -1.0f;
    v->clip.plane[0][3] = -0.5f;
    const oit_pick_hit in2[2] = {hit(r, 0.0f, 2, 0), hit(r, -1.0f, 3, 0)};
    for (int i = 0; i < 2; i++)
        CHECK(oit_pick_hits_add(&hits, &in2[i], &err) == OIT_OK, "%s", err.message);
    n = compose(r, &hits, l, 4);
    CHECK(n == 1 && l[0].source_triangle == 3, "a hit the plane cuts away is a layer (%zu)", n);
    v->clip.count = 0;
    oit_pick_hits_free(&hits);
}

static void check_walk(const oit_pick_ray *r)
{
    oit_mesh m = {0};
    oit_triangle t[2] = {tri_at(0.0f, 0, 200), tri_at(0.0f, 1, 100)};
    /* the second triangle moved aside: the centre pixel's ray meets the
     * first only */
    for (int v = 0; v < 3; v++)
        t[1].v[v].pos[0] += 5.0f;
    CHECK(oit_mesh_append(&m, t, 2, NULL) == OIT_OK, "mesh");
    oit_pick_hits hits = {0};
    oit_error err = {0};
    CHECK(oit_pick_mesh(r, &m, NULL, &hits, &err) == OIT_OK, "%s", err.message);
    CHECK(hits.n == 1 && hits.h[0].source == 0 && hits.h[0].part == OIT_PICK_NO_PART,
          "the walk found %zu hits (want source 0, no part)", hits.n);
    oit_pick_hits_free(&hits);
    oit_mesh_free(&m);
}

int main(void)
{
    oit_view v;
    view_of(&v);
    oit_pick_ray r;
    oit_error err = {0};
    CHECK(oit_pick_ray_make(&v, 4, 4, &r, &err) == OIT_OK, "%s", err.message);
    check_pieces_and_ties(&r);
    check_dropped(&r, &v);
    check_walk(&r);
    CHECK(oit_pick_ray_make(&v, 9, 4, &r, &err) == OIT_ERR_ARGUMENT, "pixel 9 of 9 accepted");
    return test_verdict();
}
