/* prepare/partition/kd.h, the guaranteed scheme's build: every part within K (or
 * wide), its bound the sum of its pieces', inside its leaf, area kept,
 * sources carried; a torus, a saddle that ends as one wide part, and bars
 * that a diagonal slab separates (a slab leaf, nothing clipped) or that
 * cross (clipped). */
#include "prepare/partition/convex.h"
#include "prepare/partition/kd.h"
#include "prepare/partition/plane_exact.h"
#include "tests/prepare/partition/partition_test.h"

static oit_status kd_of(const tri_list *l, uint32_t K, oit_kd_result *r, oit_error *err)
{
    float lo[3] = {-4, -4, -4}, hi[3] = {4, 4, 4};
    oit_convex_result cr;
    if (oit_convex_cluster(l->t, l->n, NULL, &cr, err))
        return OIT_ERR_NOMEM;
    oit_kd_params kp = {K, 0, 0, OIT_KD_SLABS_ALL};
    uint32_t *src = odd_sources(l->n);
    oit_status s = oit_kd_build(lo, hi, l->t, src, l->n, cr.piece_of, cr.plane_of,
                                cr.piece_count, &kp, r, err);
    oit_convex_result_free(&cr);
    free(src);
    if (s == OIT_OK)
        check_sources("kd", l, r);
    return s;
}

/* Every part within K (or wide), its bound the sum of 1 or 2 per piece,
 * inside its leaf's box, and no area lost or gained. */
static void check_kd(const char *name, const tri_list *l, const oit_kd_result *r, uint32_t K)
{
    double area_in = 0, area_out = 0;
    for (size_t i = 0; i < l->n; i++)
        area_in += tri_area(&l->t[i]);
    for (size_t i = 0; i < r->tri_count; i++)
        area_out += tri_area(&r->tris[i]);
    CHECK(fabs(area_out - area_in) <= 1e-5 * area_in, "%s: area %.9g in, %.9g out", name,
          area_in, area_out);
    uint32_t wide = 0;
    for (size_t p = 0; p < r->part_count; p++) {
        const oit_kd_part *pt = &r->parts[p];
        uint32_t sum = 0;
        for (uint32_t q = 0; q < pt->piece_count; q++)
            sum += r->pieces[pt->piece_first + q].plane_count > 1 ? 2 : 1;
        CHECK(pt->layer_bound == sum, "%s: part %zu bound %u, pieces say %u", name, p,
              pt->layer_bound, sum);
        wide += pt->layer_bound > K;
    }
    CHECK(wide == r->wide_parts, "%s: %u wide parts, result says %u", name, wide, r->wide_parts);
    for (size_t n = 0; n < r->node_count; n++) {
        const oit_kd_node *nd = &r->nodes[n];
        if (nd->axis >= 0 || nd->part < 0)
            continue;
        const oit_kd_part *pt = &r->parts[nd->part];
        for (size_t i = pt->tri_first; i < pt->tri_first + pt->tri_count; i++)
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) {
                    float x = r->tris[i].v[v].pos[k];
                    CHECK(x >= nd->lo[k] && x <= nd->hi[k], "%s: part %d leaves its box",
                          name, nd->part);
                }
    }
    for (size_t i = 0; i < r->slab_count; i++) {
        const oit_kd_slab_leaf *sl = &r->slabs[i];
        const float *n = sl->planes.normal;
        CHECK(sl->planes.d0 <= sl->planes.d1, "%s: slab %zu planes %g > %g", name, i,
              sl->planes.d0, sl->planes.d1);
        for (int h = 0; h < 2; h++) {
            const oit_kd_part *pt = &r->parts[h ? sl->part_above : sl->part_below];
            CHECK(pt->layer_bound <= K, "%s: slab %zu: a part of %u layers", name, i,
                  pt->layer_bound);
            for (size_t t = pt->tri_first; t < pt->tri_first + pt->tri_count; t++)
                for (int v = 0; v < 3; v++) {
                    const float *q = r->tris[t].v[v].pos;
                    double x = (double)n[0] * q[0] + (double)n[1] * q[1] + (double)n[2] * q[2];
                    CHECK(h ? oit_plane_side_exact(n, sl->planes.d1, q) >= 0
                            : oit_plane_side_exact(n, sl->planes.d0, q) <= 0,
                          "%s: slab %zu: a vertex at %.9g is on the wrong side of %g..%g", name,
                          i, x, sl->planes.d0, sl->planes.d1);
                }
        }
    }
    printf("kd %s: %zu triangles -> %zu, %zu parts (%u wide, %zu slabs), depth %u\n", name,
           l->n, r->tri_count, r->part_count, wide, r->slab_count, r->depth);
}

/* Two parallel diagonal bars side by side: every axis plane through their
 * common box cuts one, a diagonal plane separates them, so at K = 2 the
 * node becomes a slab leaf and nothing is clipped. Two crossing bars have
 * no separating plane: they are clipped, as before. */
static void test_kd_slab_leaves(void)
{
    const double r2 = sqrt(0.5), u[3] = {r2, r2, 0}, v[3] = {-r2, r2, 0}, h[3] = {2, 0.15, 0.5};
    tri_list side = {0}, cross = {0};
    for (int i = 0; i < 2; i++)
        make_bar(&side, (const double[3]){v[0] * (i ? 0.4 : -0.4), v[1] * (i ? 0.4 : -0.4), 0.1},
                 u, v, h);
    make_bar(&cross, (const double[3]){0, 0, 0.1}, u, v, h);
    make_bar(&cross, (const double[3]){0, 0, 0.1}, v, (const double[3]){-r2, -r2, 0}, h);
    oit_kd_result r;
    oit_error err = {0};
    CHECK(kd_of(&side, 2, &r, &err) == OIT_OK, "side by side: %s", err.message);
    check_kd("side by side", &side, &r, 2);
    CHECK(r.slab_count == 1 && r.part_count == 2 && r.tri_count == side.n && r.split_added == 0,
          "side by side: %zu slabs, %zu parts, %zu of %zu triangles, want 1 slab, 2 parts and "
          "nothing clipped", r.slab_count, r.part_count, r.tri_count, side.n);
    if (r.slab_count) {
        const float *n = r.slabs[0].planes.normal;
        CHECK(fabs(fabs(n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) - 1) < 1e-3,
              "side by side: slab normal (%g %g %g), want +-(%g %g 0)", n[0], n[1], n[2], v[0],
              v[1]);
    }
    oit_kd_result_free(&r);
    CHECK(kd_of(&cross, 2, &r, &err) == OIT_OK, "crossing: %s", err.message);
    check_kd("crossing", &cross, &r, 2);
    CHECK(r.slab_count == 0 && r.split_added > 0, "crossing: %zu slabs, %llu triangles added; "
          "crossing bars have no separating plane", r.slab_count,
          (unsigned long long)r.split_added);
    oit_kd_result_free(&r);
    free(side.t);
    free(cross.t);
}

static void test_kd(void)
{
    tri_list torus = {0}, saddle = {0};
    make_torus(&torus, 24, 12);
    /* 16 sectors around one vertex, alternately up and down: 8 two-plane
     * pieces meet there (16 layers), so it ends as one wide part. */
    oit_vertex c = vtx(0.31f, 0.17f, 0.05f);
    for (int i = 0; i < 16; i++) {
        double a0 = 2 * PI * i / 16, a1 = 2 * PI * (i + 1) / 16;
        push3(&saddle, c, vtx(0.31f + (float)cos(a0), 0.17f + (float)sin(a0), i % 2 ? -0.55f : 0.65f),
              vtx(0.31f + (float)cos(a1), 0.17f + (float)sin(a1), i % 2 ? 0.65f : -0.55f));
    }
    oit_kd_result r;
    oit_error err = {0};
    CHECK(kd_of(&torus, 8, &r, &err) == OIT_OK, "torus: %s", err.message);
    check_kd("torus", &torus, &r, 8);
    CHECK(r.wide_parts == 0, "torus: %u wide parts, it has no vertex of > 8 layers",
          r.wide_parts);
    oit_kd_result_free(&r);
    CHECK(kd_of(&saddle, 8, &r, &err) == OIT_OK, "saddle: %s", err.message);
    check_kd("saddle", &saddle, &r, 8);
    CHECK(r.wide_parts == 1, "saddle: %u wide parts, want 1 (the centre)", r.wide_parts);
    oit_kd_result_free(&r);
    free(torus.t);
    free(saddle.t);
}

int main(void)
{
    test_kd();
    test_kd_slab_leaves();
    return test_verdict();
}
