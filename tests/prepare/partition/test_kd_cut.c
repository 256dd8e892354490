/* prepare/partition/kd_cut.h: the cutting plane that crosses fewest triangles
 * among pieces no axis plane parts, and none when max_cut or K rule every
 * plane out. */
#include "prepare/partition/kd_cut.h"
#include "tests/prepare/partition/partition_test.h"

/* A quad of the plane z = h in the frame u = (1,1,0)/sqrt2, v = (-1,1,0)/sqrt2. */
static void push_uv_quad(tri_list *l, double u0, double u1, double v0, double v1, float h)
{
    const double r = sqrt(0.5);
    oit_vertex c[4];
    for (int i = 0; i < 4; i++) {
        double u = i & 1 ? u1 : u0, v = i & 2 ? v1 : v0;
        c[i] = vtx((float)(r * (u - v)), (float)(r * (u + v)), h);
    }
    push3(l, c[0], c[1], c[3]);
    push3(l, c[0], c[3], c[2]);
}

/* Three long pieces side by side along a diagonal, weights 2 (K = 4),
 * each of the last two with a triangle reaching back across the gap before
 * it: every axis plane, and every plane tilted out of the diagonal, crosses
 * long triangles, the plane of normal (1,-1,0) in the first gap crosses
 * only one (in the second gap, the third piece would count below too). */
static void test_kd_cut(void)
{
    tri_list l = {0};
    uint32_t slot[16];
    const double r = sqrt(0.5);
    push_uv_quad(&l, -3, 3, -1, -0.1, 0);
    push_uv_quad(&l, -3, 3, -1, -0.1, 2);
    size_t zero = l.n, first = 0;
    for (int piece = 1; piece <= 2; piece++) {
        double v0 = piece == 1 ? 0.1 : 1.2, v1 = piece == 1 ? 1 : 2, back = v0 - 0.5;
        push_uv_quad(&l, -3, 3, v0, v1, 0);
        push_uv_quad(&l, -3, 3, v0, v1, 2);
        push3(&l, vtx((float)(r * -back), (float)(r * back), 0),
              vtx((float)(r * -back), (float)(r * back), 2),
              vtx((float)(r * -(v0 + 0.4)), (float)(r * (v0 + 0.4)), 1));
        if (piece == 1)
            first = l.n;
    }
    for (size_t i = 0; i < l.n; i++)
        slot[i] = i < zero ? 0 : i < first ? 1 : 2;
    const uint32_t weight[3] = {2, 2, 2};
    const float lo[3] = {-4, -4, -1}, hi[3] = {4, 4, 3};
    oit_kd_cut cut;
    int found = oit_kd_find_cut(l.t, l.n, slot, weight, 3, 4, lo, hi, UINT32_MAX, &cut);
    const int *n = cut.plane.n;
    double v = cut.plane.d / sqrt(2.0);
    printf("kd cut: found %d, normal (%d %d %d), d %g (v = %g), %u crossed\n", found, n[0], n[1],
           n[2], cut.plane.d, v, cut.cut);
    CHECK(found == 1 && cut.cut == 1 && n[0] == 1 && n[1] == -1 && n[2] == 0,
          "want the plane of normal (1,-1,0) crossing 1 triangle");
    CHECK(found == 1 && -v > -0.1 && -v < 0.1, "plane at v = %g, want inside the gap (-0.1, 0.1)",
          -v);
    CHECK(oit_kd_find_cut(l.t, l.n, slot, weight, 3, 4, lo, hi, 0, &cut) == 0,
          "max_cut 0: a plane crossing nothing does not exist");
    CHECK(oit_kd_find_cut(l.t, l.n, slot, weight, 3, 2, lo, hi, UINT32_MAX, &cut) == 0,
          "K = 2: a half of 2 pieces cannot be within 2 layers");
    free(l.t);
}

int main(void)
{
    test_kd_cut();
    return test_verdict();
}
