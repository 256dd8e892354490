/* prepare/partition/kd_slab.h: oit_kd_find_slab's contract, judged from its output
 * alone. When it finds a slab, every vertex of the pieces it puts below lies
 * on or below d0 and every vertex of those above on or above d1, exactly for
 * the normal as stored (a wrong plane or swapped sides fail); every piece
 * gets a side, both sides hold triangles and weigh at most K (a piece left
 * out or put with too many fails); pieces that share a vertex share a side.
 * It finds the widest gap where several qualify, and none for crossing bars,
 * boxes a rounding apart, one group, a group over K or more than 2K in
 * all. */
#include "prepare/partition/kd_slab.h"
#include "prepare/partition/plane_exact.h"
#include "tests/prepare/partition/partition_test.h"

/* A node: triangles with their piece slots. */
typedef struct slab_node {
    tri_list l;
    uint32_t slot[256];
    uint32_t np;
} slab_node;

/* Gives the triangles appended since `from` the slot of a new piece. */
static void end_piece(slab_node *nd, size_t from)
{
    for (size_t i = from; i < nd->l.n && i < sizeof nd->slot / sizeof nd->slot[0]; i++)
        nd->slot[i] = nd->np;
    nd->np++;
}

/* Appends an axis-aligned box [lo, hi] as the next piece. */
static void add_box(slab_node *nd, const double lo[3], const double hi[3])
{
    const double c[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    const double h[3] = {0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), 0.5 * (hi[2] - lo[2])};
    size_t from = nd->l.n;
    make_bar(&nd->l, c, (const double[3]){1, 0, 0}, (const double[3]){0, 1, 0}, h);
    end_piece(nd, from);
}

/* Shuffles the triangles with their slots (a fixed LCG), so that no result
 * can lean on the pieces arriving one after another. */
static void shuffle(slab_node *nd)
{
    uint32_t s = 99;
    for (size_t i = nd->l.n; i > 1; i--) {
        s = s * 1664525u + 1013904223u;
        size_t j = (s >> 8) % i;
        oit_triangle t = nd->l.t[i - 1];
        uint32_t k = nd->slot[i - 1];
        nd->l.t[i - 1] = nd->l.t[j];
        nd->slot[i - 1] = nd->slot[j];
        nd->l.t[j] = t;
        nd->slot[j] = k;
    }
}

static int same_vertex(const oit_triangle *a, const oit_triangle *b)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (!memcmp(a->v[i].pos, b->v[j].pos, sizeof a->v[i].pos))
                return 1;
    return 0;
}

/* Runs oit_kd_find_slab on nd at K and checks a found slab against the
 * contract; returns what it returned, the slab and the sides. */
static int find_checked(const char *name, slab_node *nd, const uint32_t *weight, uint32_t K,
                        oit_kd_slab *slab, uint8_t *side)
{
    memset(side, 0xaa, nd->np); /* a side never written shows */
    int found = oit_kd_find_slab(nd->l.t, nd->l.n, nd->slot, weight, nd->np, K, slab, side);
    CHECK(found == 0 || found == 1, "%s: returned %d", name, found);
    if (found != 1)
        return found;
    const float *n = slab->normal;
    double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    CHECK(fabs(len - 1) < 1e-6 && slab->d0 <= slab->d1,
          "%s: normal (%g %g %g) of length %.9g, planes %.9g..%.9g", name, n[0], n[1], n[2], len,
          slab->d0, slab->d1);
    uint32_t w[2] = {0, 0};
    for (uint32_t p = 0; p < nd->np; p++) {
        CHECK(side[p] <= 1, "%s: piece %u has no side (%u)", name, p, side[p]);
        if (side[p] <= 1)
            w[side[p]] += weight[p];
    }
    CHECK(w[0] <= K && w[1] <= K, "%s: sides weigh %u and %u, K %u", name, w[0], w[1], K);
    size_t count[2] = {0, 0}, wrong = 0, split = 0;
    for (size_t i = 0; i < nd->l.n; i++) {
        uint8_t s = side[nd->slot[i]];
        if (s > 1)
            continue;
        count[s]++;
        for (int v = 0; v < 3; v++) {
            const float *q = nd->l.t[i].v[v].pos;
            wrong += s ? oit_plane_side_exact(n, slab->d1, q) < 0
                       : oit_plane_side_exact(n, slab->d0, q) > 0;
        }
        for (size_t j = 0; j < i; j++)
            split += same_vertex(&nd->l.t[i], &nd->l.t[j]) && side[nd->slot[j]] != s;
    }
    CHECK(count[0] && count[1] && count[0] + count[1] == nd->l.n,
          "%s: %zu triangles below, %zu above, of %zu", name, count[0], count[1], nd->l.n);
    CHECK(wrong == 0, "%s: %zu vertices on the wrong side of %.9g..%.9g along (%g %g %g)", name,
          wrong, slab->d0, slab->d1, n[0], n[1], n[2]);
    CHECK(split == 0, "%s: %zu pairs of triangles share a vertex across the slab", name, split);
    return found;
}

/* Two parallel diagonal bars side by side: no axis plane parts them, the
 * diagonal one does; two crossing bars have no separating plane. */
static void test_bars(void)
{
    const double r2 = sqrt(0.5), u[3] = {r2, r2, 0}, v[3] = {-r2, r2, 0}, h[3] = {2, 0.15, 0.5};
    const uint32_t weight[2] = {2, 2};
    oit_kd_slab slab;
    uint8_t side[2];
    slab_node side_by_side = {0}, cross = {0};
    for (int i = 0; i < 2; i++) {
        size_t from = side_by_side.l.n;
        make_bar(&side_by_side.l,
                 (const double[3]){v[0] * (i ? 0.4 : -0.4), v[1] * (i ? 0.4 : -0.4), 0.1}, u, v, h);
        end_piece(&side_by_side, from);
    }
    shuffle(&side_by_side);
    CHECK(find_checked("bars side by side", &side_by_side, weight, 2, &slab, side) == 1,
          "bars side by side: no slab");
    const float *n = slab.normal;
    CHECK(fabs(fabs(n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) - 1) < 1e-3 && side[0] != side[1],
          "bars side by side: normal (%g %g %g), sides %u %u: want +-(%g %g 0), one bar a side",
          n[0], n[1], n[2], side[0], side[1], v[0], v[1]);
    printf("kd slab: bars side by side parted along (%g %g %g) at %.9g..%.9g\n", n[0], n[1], n[2],
           slab.d0, slab.d1);
    for (int i = 0; i < 2; i++) {
        size_t from = cross.l.n;
        make_bar(&cross.l, (const double[3]){0, 0, 0.1}, i ? v : u,
                 i ? (const double[3]){-r2, -r2, 0} : v, h);
        end_piece(&cross, from);
    }
    CHECK(find_checked("crossing bars", &cross, weight, 2, &slab, side) == 0,
          "crossing bars have no separating plane");
    free(side_by_side.l.t);
    free(cross.l.t);
}

/* Boxes along x; gap[i] before box i + 1. */
static void boxes_along_x(slab_node *nd, int count, const double *gap)
{
    double x = 0;
    for (int i = 0; i < count; i++) {
        add_box(nd, (const double[3]){x, 0, 0}, (const double[3]){x + 1, 1, 1});
        x += 1 + (i + 1 < count ? gap[i] : 0);
    }
    shuffle(nd);
}

/* Several gaps: the weights rule some out, the widest of the rest wins. */
static void test_gaps(void)
{
    oit_kd_slab slab;
    uint8_t side[4];
    /* Four boxes of 2 layers at K = 4: only the middle gap leaves both
     * sides within K, though the outer ones are wider. */
    slab_node four = {0};
    const uint32_t w2[4] = {2, 2, 2, 2};
    boxes_along_x(&four, 4, (const double[3]){1.0, 0.5, 1.0});
    CHECK(find_checked("four boxes", &four, w2, 4, &slab, side) == 1, "four boxes: no slab");
    CHECK(side[0] == side[1] && side[2] == side[3] && side[1] != side[2],
          "four boxes at K = 4: sides %u %u %u %u, want the middle gap", side[0], side[1], side[2],
          side[3]);
    /* Three boxes of 1 layer at K = 2: both gaps qualify, the wider wins. */
    slab_node three = {0};
    const uint32_t w1[3] = {1, 1, 1};
    boxes_along_x(&three, 3, (const double[2]){0.5, 2.0});
    CHECK(find_checked("three boxes", &three, w1, 2, &slab, side) == 1, "three boxes: no slab");
    CHECK(side[0] == side[1] && side[1] != side[2] && fabsf(slab.normal[0]) > 0.999f,
          "three boxes: sides %u %u %u along (%g %g %g), want the wider gap, along x", side[0],
          side[1], side[2], slab.normal[0], slab.normal[1], slab.normal[2]);
    CHECK(slab.d1 - slab.d0 > 1.5f, "three boxes: planes %.9g..%.9g, want most of the 2.0 gap",
          slab.d0, slab.d1);
    free(four.l.t);
    free(three.l.t);
}

/* What must not give a slab, each beside the same node that does. */
static void test_refused(void)
{
    oit_kd_slab slab;
    uint8_t side[3];
    const uint32_t w1[3] = {1, 1, 1}, w2[3] = {2, 2, 2}, w3[2] = {3, 3};
    /* A gap of one float ulp is below the rounding margin: the boxes only
     * touch. A quarter apart they part. */
    for (int apart = 0; apart < 2; apart++) {
        slab_node two = {0};
        double x1 = apart ? 1.25 : (double)nextafterf(1.0f, 2.0f);
        add_box(&two, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1});
        add_box(&two, (const double[3]){x1, 0, 0}, (const double[3]){2, 1, 1});
        int found =
            find_checked(apart ? "boxes apart" : "boxes an ulp apart", &two, w1, 1, &slab, side);
        CHECK(found == apart, "boxes %s apart: found %d", apart ? "a quarter" : "an ulp", found);
        /* Each of 3 layers: 6 in all, over 2K at K = 2, even apart. */
        if (apart)
            CHECK(oit_kd_find_slab(two.l.t, two.l.n, two.slot, w3, 2, 2, &slab, side) == 0,
                  "6 layers in all at K = 2 must give no slab");
        free(two.l.t);
    }
    /* Boxes 0 and 1 share a corner, box 2 stands apart: the shared pair is
     * one group, which fits K = 2 at a layer a box and not K = 3 at two. */
    slab_node corner = {0};
    add_box(&corner, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1});
    add_box(&corner, (const double[3]){1, 1, 1}, (const double[3]){2, 2, 2});
    add_box(&corner, (const double[3]){4, 0, 0}, (const double[3]){5, 1, 1});
    shuffle(&corner);
    CHECK(find_checked("shared corner", &corner, w1, 2, &slab, side) == 1 && side[0] == side[1] &&
              side[1] != side[2],
          "shared corner: sides %u %u %u, want the pair together", side[0], side[1], side[2]);
    CHECK(find_checked("shared corner over K", &corner, w2, 3, &slab, side) == 0,
          "a group of 4 layers at K = 3 must give no slab");
    /* One piece: nothing to part. */
    CHECK(oit_kd_find_slab(corner.l.t, 12, (const uint32_t[12]){0}, w1, 1, 2, &slab, side) == 0,
          "one piece must give no slab");
    free(corner.l.t);
}

int main(void)
{
    test_bars();
    test_gaps();
    test_refused();
    return test_verdict();
}
