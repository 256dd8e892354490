/* prepare/partition/kd_fast.h, the fast scheme's build: parts within T triangles
 * with measured bounds, sources carried, a stack split below the file's
 * layer limit; nodes a few ulps wide that no plane can split end as one
 * part each, with a valid tree and nothing lost or stored twice. */
#include "prepare/partition/kd.h"
#include "prepare/partition/kd_fast.h"
#include "prepare/partition/layers_measured.h"
#include "tests/prepare/partition/partition_test.h"

/* Every part within T triangles and inside its leaf's box, bounds equal to
 * the measured count, few triangles added. */
static void check_fast(const char *name, const tri_list *l, uint32_t T, const oit_kd_result *r)
{
    size_t tris = 0;
    for (size_t i = 0; i < r->node_count; i++) {
        const oit_kd_node *nd = &r->nodes[i];
        if (nd->axis >= 0 || nd->part < 0)
            continue;
        const oit_kd_part *p = &r->parts[nd->part];
        tris += p->tri_count;
        CHECK(p->tri_count <= T || p->layer_bound > OIT_PARTFILE_MAX_LAYERS / 2,
              "%s: part of %zu triangles > %u", name, p->tri_count, T);
        uint32_t want = 0;
        oit_layers_measure(r->tris + p->tri_first, p->tri_count, &want, NULL);
        CHECK(p->layer_bound == (want < OIT_PARTFILE_MAX_LAYERS ? want : OIT_PARTFILE_MAX_LAYERS),
              "%s: part bound %u, measured %u", name, p->layer_bound, want);
        for (size_t t = p->tri_first; t < p->tri_first + p->tri_count; t++)
            for (int v = 0; v < 3; v++)
                for (int a = 0; a < 3; a++) {
                    float x = r->tris[t].v[v].pos[a];
                    CHECK(x >= nd->lo[a] && x <= nd->hi[a], "%s: vertex outside its leaf",
                          name);
                }
    }
    CHECK(tris == r->tri_count, "%s: leaves hold %zu of %zu triangles", name, tris, r->tri_count);
    CHECK(r->tri_count <= l->n + l->n / 5, "%s: %zu -> %zu triangles", name, l->n, r->tri_count);
    CHECK(r->slab_count == 0 && r->piece_count == r->part_count, "%s: slabs or pieces", name);
}

static void test_kd_fast(void)
{
    tri_list torus = {0}, stack = {0};
    make_torus(&torus, 64, 32);
    make_stack(&stack, 100);
    float lo[3] = {-2, -2, -2}, hi[3] = {2, 2, 2};
    oit_kd_fast_params p = {500, 8, 0, 0};
    oit_kd_result r;
    oit_error err = {0};
    uint32_t *src = odd_sources(torus.n);
    CHECK(oit_kd_build_fast(lo, hi, torus.t, src, torus.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    free(src);
    check_sources("kd fast torus", &torus, &r);
    CHECK(r.part_count >= torus.n / 500 && r.part_count <= torus.n / 50,
          "torus of %zu: %zu parts at T = 500", torus.n, r.part_count);
    printf("kd fast torus: %zu triangles -> %zu, %zu parts at T = 500, most measured %u\n",
           torus.n, r.tri_count, r.part_count, r.max_measured);
    check_fast("torus", &torus, 500, &r);
    oit_kd_result_free(&r);
    /* 100 sheets in one node of 200 triangles: above the file's 64 layers,
     * so it is split further (along z) until every part is within it. */
    float slo[3] = {0, 0, 0}, shi[3] = {8, 8, 8};
    p.part_triangles = 100000;
    src = odd_sources(stack.n);
    CHECK(oit_kd_build_fast(slo, shi, stack.t, src, stack.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    free(src);
    check_sources("kd fast stack", &stack, &r);
    CHECK(r.part_count >= 2 && r.clamped_parts == 0 && r.max_measured <= 64 &&
              r.tri_count == stack.n,
          "stack of 100: %zu parts, %u clamped, max %u, %zu triangles", r.part_count,
          r.clamped_parts, r.max_measured, r.tri_count);
    printf("kd fast stack of 100 sheets: %zu parts, most measured %u\n", r.part_count,
           r.max_measured);
    check_fast("stack", &stack, 100000, &r);
    oit_kd_result_free(&r);
    p.part_triangles = 0;
    CHECK(oit_kd_build_fast(lo, hi, torus.t, NULL, torus.n, &p, &r, &err) == OIT_ERR_ARGUMENT,
          "parts of 0 triangles must be refused");
    free(torus.t);
    free(stack.t);
}

/* The tree of a fast build, checked against its input alone: the root is the
 * given box; every split lies strictly inside its node and halves it into
 * its two children (one level deeper); every leaf names its own part or
 * none, and the parts tile the output triangles; each part lies in its
 * leaf's closed box with its measured layer count (1..64); every output
 * triangle carries an input source; and every input triangle that no split
 * plane on its way down crosses comes out exactly once, bit for bit, in the
 * leaf it falls in (a triangle in a plane goes below). Returns the number of
 * input triangles that some plane clipped. */
static size_t check_fast_tree(const char *name, const tri_list *l, const float lo[3],
                              const float hi[3], const oit_kd_result *r)
{
    size_t bad_node = 0, bad_part = 0, bad_tri = 0, lost = 0, doubled = 0, clipped = 0;
    CHECK(r->node_count >= 1 && !memcmp(r->nodes[0].lo, lo, 12) && !memcmp(r->nodes[0].hi, hi, 12),
          "%s: the root is not the cell's box", name);
    unsigned char *part_seen = calloc(r->part_count + 1, 1);
    for (size_t i = 0; i < r->node_count; i++) {
        const oit_kd_node *nd = &r->nodes[i];
        if (nd->axis >= 0) {
            int a = nd->axis;
            const oit_kd_node *c = &r->nodes[nd->child];
            int ok = a < 3 && nd->child + 1u < r->node_count && nd->child > i &&
                     nd->lo[a] < nd->split && nd->split < nd->hi[a];
            for (int h = 0; ok && h < 2; h++)
                for (int k = 0; k < 3; k++) {
                    float want_lo = h && k == a ? nd->split : nd->lo[k];
                    float want_hi = !h && k == a ? nd->split : nd->hi[k];
                    ok &= c[h].lo[k] == want_lo && c[h].hi[k] == want_hi &&
                          c[h].depth == nd->depth + 1;
                }
            bad_node += !ok;
            continue;
        }
        if (nd->part < 0)
            continue;
        if ((size_t)nd->part >= r->part_count || part_seen[nd->part]++) {
            bad_part++;
            continue;
        }
        const oit_kd_part *p = &r->parts[nd->part];
        uint32_t layers = 0;
        oit_layers_measure(r->tris + p->tri_first, p->tri_count, &layers, NULL);
        layers = layers < OIT_PARTFILE_MAX_LAYERS ? layers : OIT_PARTFILE_MAX_LAYERS;
        bad_part += p->tri_count == 0 || p->layer_bound != layers || p->layer_bound < 1;
        for (size_t t = p->tri_first; t < p->tri_first + p->tri_count && t < r->tri_count; t++)
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) {
                    float x = r->tris[t].v[v].pos[k];
                    bad_tri += !(x >= nd->lo[k] && x <= nd->hi[k]);
                }
    }
    size_t covered = 0;
    for (size_t p = 0; p < r->part_count; p++) {
        bad_part += !part_seen[p] || r->parts[p].tri_first != covered;
        covered += r->parts[p].tri_count;
    }
    bad_part += covered != r->tri_count;
    for (size_t i = 0; i < r->tri_count; i++)
        bad_tri += r->src[i] % 2 == 0 || (r->src[i] - 1) / 2 >= l->n;
    /* Each input triangle down the tree to its leaf, unless a plane crosses it. */
    for (size_t i = 0; i < l->n && !bad_node; i++) {
        const oit_triangle *t = &l->t[i];
        size_t n = 0;
        int cut = 0;
        while (r->nodes[n].axis >= 0 && !cut) {
            const oit_kd_node *nd = &r->nodes[n];
            float a = t->v[0].pos[nd->axis], b = t->v[1].pos[nd->axis], c = t->v[2].pos[nd->axis];
            float tmin = fminf(a, fminf(b, c)), tmax = fmaxf(a, fmaxf(b, c));
            if (tmax <= nd->split)
                n = nd->child;
            else if (tmin >= nd->split)
                n = nd->child + 1;
            else
                cut = 1;
        }
        clipped += cut;
        if (cut)
            continue;
        int32_t part = r->nodes[n].part;
        size_t copies = 0, same = 0;
        for (size_t j = 0; j < r->tri_count; j++)
            if (r->src[j] == 2 * i + 1) {
                copies++;
                same += part >= 0 && j >= r->parts[part].tri_first &&
                        j < r->parts[part].tri_first + r->parts[part].tri_count &&
                        !memcmp(r->tris[j].v, t->v, sizeof t->v);
            }
        lost += same == 0;
        doubled += copies > 1;
    }
    CHECK(bad_node == 0 && bad_part == 0 && bad_tri == 0,
          "%s: %zu bad splits, %zu bad parts (leaf, cover, layer bound), %zu triangles outside "
          "their leaf or of no source", name, bad_node, bad_part, bad_tri);
    CHECK(lost == 0 && doubled == 0,
          "%s: of %zu triangles no plane cuts, %zu lost or changed, %zu stored twice", name,
          l->n - clipped, lost, doubled);
    free(part_seen);
    return clipped;
}

/* A coordinate k ulps above x. */
static float ulps(float x, int k)
{
    while (k-- > 0)
        x = nextafterf(x, INFINITY);
    return x;
}

/* n triangles with corners on the float grid of [base, base + w ulps] on
 * every axis, none degenerate. */
static void make_ulp_cluster(tri_list *l, const float base[3], int w, int n, uint32_t seed)
{
    for (int i = 0; i < n; i++) {
        float c[3][3];
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                seed = seed * 1664525u + 1013904223u;
                c[v][k] = ulps(base[k], (int)((seed >> 16) % (uint32_t)(w + 1)));
            }
        oit_triangle t = {{vtx(c[0][0], c[0][1], c[0][2]), vtx(c[1][0], c[1][1], c[1][2]),
                           vtx(c[2][0], c[2][1], c[2][2])}};
        if (tri_area(&t) > 0)
            push(l, &t);
        else
            i--;
    }
}

/* Nodes no plane can split: a few ulps wide. The build must end (the test's
 * timeout), keep a valid tree, lose and duplicate nothing, and make such a
 * node one part however many triangles it holds. */
static void test_kd_fast_ulps(void)
{
    oit_kd_fast_params p = {4, 8, 0, 0};
    oit_kd_result r;
    oit_error err = {0};
    /* 1 ulp a side: no float lies strictly inside, so the cell is one part
     * of all its triangles, in input order. */
    const float base[3] = {1.0f, -3.0f, 1024.0f};
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = base[k];
        hi[k] = ulps(base[k], 1);
    }
    tri_list one = {0};
    make_ulp_cluster(&one, base, 1, 40, 7);
    uint32_t *src = odd_sources(one.n);
    CHECK(oit_kd_build_fast(lo, hi, one.t, src, one.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    CHECK(r.node_count == 1 && r.part_count == 1 && r.tri_count == one.n &&
              r.nodes[0].part == 0 && !memcmp(r.tris, one.t, one.n * sizeof *one.t) &&
              !memcmp(r.src, src, one.n * sizeof *src),
          "1-ulp cell of %zu triangles: %zu nodes, %zu parts, %zu triangles: want the cell as "
          "one part, its triangles as given", one.n, r.node_count, r.part_count, r.tri_count);
    check_fast_tree("1-ulp cell", &one, lo, hi, &r);
    oit_kd_result_free(&r);
    free(src);
    /* 2 and 3 ulps a side: a plane or two, then unsplittable nodes. */
    for (int w = 2; w <= 3; w++) {
        tri_list l = {0};
        for (int k = 0; k < 3; k++)
            hi[k] = ulps(base[k], w);
        make_ulp_cluster(&l, base, w, 60, 11u * (uint32_t)w);
        src = odd_sources(l.n);
        char name[48];
        snprintf(name, sizeof name, "%d-ulp cell", w);
        CHECK(oit_kd_build_fast(lo, hi, l.t, src, l.n, &p, &r, &err) == OIT_OK, "%s: %s", name,
              err.message);
        check_fast_tree(name, &l, lo, hi, &r);
        CHECK(r.node_count > 1 && r.node_count < 200, "%s: %zu nodes", name, r.node_count);
        oit_kd_result_free(&r);
        free(src);
        free(l.t);
    }
    /* A cell of ordinary size whose triangles gather in a 2-ulp cluster
     * beside a torus: the build descends to the cluster and stops there. */
    tri_list mix = {0};
    make_torus(&mix, 24, 12);
    const float spot[3] = {0.7f, 0.3f, 0.2f};
    make_ulp_cluster(&mix, spot, 2, 50, 5);
    const float clo[3] = {-2, -2, -2}, chi[3] = {2, 2, 2};
    src = odd_sources(mix.n);
    p.part_triangles = 16;
    CHECK(oit_kd_build_fast(clo, chi, mix.t, src, mix.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    size_t clipped = check_fast_tree("torus and a 2-ulp cluster", &mix, clo, chi, &r);
    printf("kd fast, ulp-wide nodes: 1-ulp cell one part of %zu; torus and a cluster of 50: "
           "%zu parts, depth %u, %zu triangles clipped\n", one.n, r.part_count, r.depth,
           clipped);
    CHECK(r.depth < 48, "torus and a 2-ulp cluster: depth %u, the cap", r.depth);
    oit_kd_result_free(&r);
    free(src);
    free(mix.t);
    free(one.t);
}

int main(void)
{
    test_kd_fast();
    test_kd_fast_ulps();
    return test_verdict();
}
