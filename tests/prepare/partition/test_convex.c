/* prepare/partition/convex.h: greedy convex clustering on shapes whose piece counts
 * are known (cube, torus, coincident and overlapping coplanar triangles),
 * and a planar fan whose last triangle overlaps its first. */
#include "prepare/partition/convex.h"
#include "tests/prepare/partition/partition_test.h"

/* Clusters l; checks every triangle has a piece and every piece passes the
 * brute-force check; returns the piece count (0 on failure). */
static uint32_t cluster(const char *name, const tri_list *l)
{
    oit_convex_result r;
    oit_error err = {0};
    if (oit_convex_cluster(l->t, l->n, NULL, &r, &err) != OIT_OK) {
        CHECK(0, "%s: oit_convex_cluster failed: %s", name, err.message);
        return 0;
    }
    uint32_t *idx = malloc((l->n ? l->n : 1) * sizeof *idx);
    size_t non_convex = 0, assigned = 0, max_size = 0;
    for (uint32_t p = 0; p < r.piece_count; p++) {
        size_t m = 0;
        for (size_t i = 0; i < l->n; i++)
            if (r.piece_of[i] == p)
                idx[m++] = (uint32_t)i;
        assigned += m;
        max_size = m > max_size ? m : max_size;
        CHECK(m > 0, "%s: piece %u is empty", name, p);
        non_convex += !oit_convex_check(l->t, idx, m);
    }
    printf("convex %s: %zu triangles -> %u pieces (largest %zu)\n", name, l->n, r.piece_count,
           max_size);
    CHECK(assigned == l->n, "%s: %zu of %zu triangles in a piece", name, assigned, l->n);
    CHECK(non_convex == 0, "%s: %zu pieces fail oit_convex_check", name, non_convex);
    uint32_t count = r.piece_count;
    oit_convex_result_free(&r);
    free(idx);
    return count;
}

static int whole_is_convex(const tri_list *l)
{
    uint32_t *idx = malloc(l->n * sizeof *idx);
    for (size_t i = 0; i < l->n; i++)
        idx[i] = (uint32_t)i;
    int ok = oit_convex_check(l->t, idx, l->n);
    free(idx);
    return ok;
}

static void test_convex(void)
{
    tri_list cube = {0}, torus = {0}, opp = {0}, overlap = {0}, adjacent = {0}, fan = {0};
    make_cube(&cube, -0.5f, 1.5f);
    CHECK(whole_is_convex(&cube), "the cube must pass oit_convex_check");
    uint32_t n = cluster("cube", &cube);
    CHECK(n == 1, "closed cube: %u pieces, want 1", n);

    make_torus(&torus, 12, 8);
    CHECK(!whole_is_convex(&torus), "the torus must fail oit_convex_check");
    n = cluster("torus 12x8", &torus);
    CHECK(n > 1 && n < torus.n, "torus: %u pieces, want several (2..%zu)", n, torus.n - 1);

    oit_vertex a = vtx(0, 0, 0), b = vtx(1, 0, 0), c = vtx(0, 1, 0), d = vtx(1, 1, 0);
    push3(&opp, a, b, c);
    push3(&opp, a, c, b);
    n = cluster("coincident opposite-facing", &opp);
    CHECK(n == 2, "coincident opposite-facing triangles: %u pieces, want 2", n);

    push3(&overlap, a, b, c);
    push3(&overlap, vtx(0.25f, 0.25f, 0), vtx(1.25f, 0.25f, 0), vtx(0.25f, 1.25f, 0));
    n = cluster("overlapping coplanar", &overlap);
    CHECK(n == 2, "overlapping coplanar same-facing triangles: %u pieces, want 2", n);

    /* An edge-connected fan of eight 50-degree triangles round one centre,
     * 400 degrees in all: the last overlaps the first but shares no edge
     * with it, and the breadth-first growth reaches it through the chain,
     * so only a check against every triangle on the plane (not just the
     * newest, its neighbour) keeps it out of the first piece. */
    for (int i = 0; i < 8; i++) {
        double a0 = (50.0 * i) * PI / 180.0, a1 = (50.0 * (i + 1)) * PI / 180.0;
        push3(&fan, vtx(0, 0, 0), vtx((float)cos(a0), (float)sin(a0), 0),
              vtx((float)cos(a1), (float)sin(a1), 0));
    }
    n = cluster("overlapping planar fan", &fan);
    CHECK(n == 2, "a planar fan whose last triangle overlaps its first: %u pieces, want 2", n);

    push3(&adjacent, a, b, c);
    push3(&adjacent, b, d, c);
    n = cluster("adjacent coplanar", &adjacent);
    CHECK(n == 1, "adjacent coplanar same-facing triangles: %u pieces, want 1", n);

    free(cube.t);
    free(torus.t);
    free(opp.t);
    free(overlap.t);
    free(adjacent.t);
    free(fan.t);
}

int main(void)
{
    test_convex();
    return test_verdict();
}
