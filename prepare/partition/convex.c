/* Greedy convex clustering (convex.h). */
#include "prepare/partition/convex.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prepare/partition/predicates.h"
#include "base/sort.h"

/* ---- shared vertices and edge adjacency ------------------------------------ */

typedef struct mesh_graph {
    uint32_t *vid;   /* 3 per triangle: vertex id by exact position */
    double (*pos)[3];
    uint32_t vcount;
    uint32_t *nb_first; /* CSR: neighbours of t are nb[nb_first[t] .. nb_first[t+1]) */
    uint32_t *nb;
} mesh_graph;

static uint64_t hash_pos(const float p[3])
{
    uint32_t b[3];
    memcpy(b, p, sizeof b);
    uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < 3; k++)
        h = (h ^ b[k]) * 1099511628211ull;
    return h ^ (h >> 29);
}

static oit_status assign_vertex_ids(const oit_triangle *tris, size_t n, mesh_graph *g)
{
    size_t cap = 16;
    while (cap < 6 * n)
        cap *= 2;
    uint32_t *slot = malloc(cap * sizeof *slot);
    g->vid = malloc(3 * n * sizeof *g->vid);
    g->pos = malloc(3 * n * sizeof *g->pos);
    const float **key = malloc(3 * n * sizeof *key);
    if (!slot || !g->vid || !g->pos || !key) {
        free(slot);
        free(key);
        return OIT_ERR_NOMEM;
    }
    memset(slot, 0xff, cap * sizeof *slot);
    g->vcount = 0;
    for (size_t i = 0; i < 3 * n; i++) {
        const float *p = tris[i / 3].v[i % 3].pos;
        size_t h = hash_pos(p) & (cap - 1);
        while (slot[h] != UINT32_MAX && memcmp(key[slot[h]], p, 12) != 0)
            h = (h + 1) & (cap - 1);
        if (slot[h] == UINT32_MAX) {
            slot[h] = g->vcount;
            key[g->vcount] = p;
            for (int k = 0; k < 3; k++)
                g->pos[g->vcount][k] = p[k];
            g->vcount++;
        }
        g->vid[i] = slot[h];
    }
    free(slot);
    free(key);
    return OIT_OK;
}

typedef struct edge_rec {
    uint32_t a, b, tri;
} edge_rec;

static int edge_less(const edge_rec *p, const edge_rec *q)
{
    if (p->a != q->a)
        return p->a < q->a;
    if (p->b != q->b)
        return p->b < q->b;
    return p->tri < q->tri;
}
OIT_SORT_DEFINE(sort_edges, edge_rec, edge_less)

/* Neighbours over shared edges, in a deterministic order (by edge, then
 * triangle index). */
static oit_status build_adjacency(size_t n, mesh_graph *g)
{
    edge_rec *e = malloc(3 * n * sizeof *e);
    g->nb_first = calloc(n + 1, sizeof *g->nb_first);
    if (!e || !g->nb_first) {
        free(e);
        return OIT_ERR_NOMEM;
    }
    for (size_t t = 0; t < n; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = g->vid[3 * t + k], b = g->vid[3 * t + (k + 1) % 3];
            e[3 * t + k] = (edge_rec){a < b ? a : b, a < b ? b : a, (uint32_t)t};
        }
    sort_edges(e, 3 * n);
    /* Two passes over runs of equal edges: count, then fill. */
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0, j; i < 3 * n; i = j) {
            for (j = i + 1; j < 3 * n && e[j].a == e[i].a && e[j].b == e[i].b; j++)
                ;
            for (size_t x = i; x < j; x++)
                for (size_t y = i; y < j; y++) {
                    if (x == y || e[x].tri == e[y].tri)
                        continue;
                    if (pass == 0)
                        g->nb_first[e[x].tri + 1]++;
                    else
                        g->nb[g->nb_first[e[x].tri]++] = e[y].tri;
                }
        }
        if (pass == 0) {
            for (size_t t = 0; t < n; t++)
                g->nb_first[t + 1] += g->nb_first[t];
            total = g->nb_first[n];
            g->nb = malloc((total ? total : 1) * sizeof *g->nb);
            if (!g->nb) {
                free(e);
                return OIT_ERR_NOMEM;
            }
        }
    }
    /* The fill pass advanced each start to the next triangle's start. */
    memmove(g->nb_first + 1, g->nb_first, n * sizeof *g->nb_first);
    g->nb_first[0] = 0;
    free(e);
    return OIT_OK;
}

static void graph_free(mesh_graph *g)
{
    free(g->vid);
    free(g->pos);
    free(g->nb_first);
    free(g->nb);
}

/* ---- the growing piece ----------------------------------------------------- */

typedef struct piece_plane {
    uint32_t v[3];   /* graph vertex ids of the first triangle on the plane */
    int side;        /* where the piece's vertices lie: +1, -1, 0 (all on it) */
    uint32_t first;  /* triangles on the plane: first, then next_on_plane   */
} piece_plane;

typedef struct grower {
    const mesh_graph *g;
    uint32_t *vstamp;       /* per vertex: piece stamp when in the piece */
    uint32_t *vslot;        /* per vertex: index in verts when in piece */
    uint32_t *verts;        /* the piece's vertices */
    uint32_t nverts;
    int8_t *vsign;          /* per piece vertex: side of the candidate's plane */
    piece_plane *planes;
    uint32_t nplanes, planes_cap;
    uint32_t *next_on_plane; /* per triangle */
    uint32_t *pending;      /* planes whose side the candidate would fix */
    uint32_t stamp;
} grower;

static const double *gpos(const grower *w, uint32_t v)
{
    return w->g->pos[v];
}

/* The axis whose projection keeps the plane's orientation (normal component
 * nonzero) and the orientation there. */
static int facing(const grower *w, const uint32_t v[3], int *drop)
{
    for (int k = 0; k < 3; k++) {
        int o = oit_orient2d(gpos(w, v[0]), gpos(w, v[1]), gpos(w, v[2]), k);
        if (o) {
            *drop = k;
            return o;
        }
    }
    *drop = 0;
    return 0;
}

/* True when every vertex of q lies on the closed outer side of one edge of p
 * (p oriented with sign s in projection drop): a separating line exists. */
static int separated_by_edge_of(const grower *w, const uint32_t p[3], const uint32_t q[3],
                                int s, int drop)
{
    for (int e = 0; e < 3; e++) {
        const double *a = gpos(w, p[e]), *b = gpos(w, p[(e + 1) % 3]);
        int all_out = 1;
        for (int i = 0; i < 3 && all_out; i++)
            all_out = oit_orient2d(a, b, gpos(w, q[i]), drop) * s <= 0;
        if (all_out)
            return 1;
    }
    return 0;
}

/* Coplanar triangles with the same facing: interiors overlap unless an edge
 * of one separates them (separating axis theorem for convex polygons). */
static int coplanar_overlap(const grower *w, const uint32_t p[3], const uint32_t q[3], int s,
                            int drop)
{
    return !separated_by_edge_of(w, p, q, s, drop) && !separated_by_edge_of(w, q, p, s, drop);
}

static int on_plane_all(const grower *w, const piece_plane *q)
{
    for (int i = 0; i < 3; i++)
        if (w->vsign[w->vslot[q->v[i]]] != 0)
            return 0;
    return 1;
}

/* Decides whether triangle t (vertex ids tv) keeps the piece convex. On
 * success *coplanar is the plane t lies on (or UINT32_MAX), *tside the side
 * of t's plane the piece lies on, and w->pending lists the zero-side planes
 * that t's new vertices orient (their side to set: stored in the sign). */
static int accept_test(grower *w, const uint32_t tv[3], uint32_t *coplanar, int *tside,
                       uint32_t *npending, int *pending_side)
{
    const double *ta = gpos(w, tv[0]), *tb = gpos(w, tv[1]), *tc = gpos(w, tv[2]);
    int side = 0;
    for (uint32_t i = 0; i < w->nverts; i++) {
        int s = oit_orient3d(ta, tb, tc, gpos(w, w->verts[i]));
        w->vsign[i] = (int8_t)s;
        if (s && side && s != side)
            return 0;
        if (s)
            side = s;
    }
    *tside = side;
    uint32_t newv[3], nnew = 0;
    for (int i = 0; i < 3; i++)
        if (w->vstamp[tv[i]] != w->stamp)
            newv[nnew++] = tv[i];
    *coplanar = UINT32_MAX;
    *npending = 0;
    for (uint32_t p = 0; p < w->nplanes; p++) {
        piece_plane *q = &w->planes[p];
        if (on_plane_all(w, q)) {
            int dq;
            int fq = facing(w, q->v, &dq);
            int ft = oit_orient2d(ta, tb, tc, dq);
            if (fq != ft)
                return 0;
            for (uint32_t o = q->first; o != UINT32_MAX; o = w->next_on_plane[o])
                if (coplanar_overlap(w, &w->g->vid[3 * o], tv, fq, dq))
                    return 0;
            *coplanar = p;
            continue;
        }
        int qside = q->side;
        for (uint32_t i = 0; i < nnew; i++) {
            int s = oit_orient3d(gpos(w, q->v[0]), gpos(w, q->v[1]), gpos(w, q->v[2]),
                                 gpos(w, newv[i]));
            if (s && qside && s != qside)
                return 0;
            if (s)
                qside = s;
        }
        if (qside != q->side) {
            w->pending[*npending] = p;
            pending_side[(*npending)++] = qside;
        }
    }
    return 1;
}

static oit_status add_triangle(grower *w, uint32_t t, uint32_t coplanar, int tside,
                               uint32_t npending, const int *pending_side, uint32_t *plane_of)
{
    const uint32_t *tv = &w->g->vid[3 * t];
    for (uint32_t i = 0; i < npending; i++)
        w->planes[w->pending[i]].side = pending_side[i];
    for (int i = 0; i < 3; i++)
        if (w->vstamp[tv[i]] != w->stamp) {
            w->vstamp[tv[i]] = w->stamp;
            w->vslot[tv[i]] = w->nverts;
            w->verts[w->nverts++] = tv[i];
        }
    if (coplanar == UINT32_MAX) {
        if (w->nplanes == w->planes_cap) {
            uint32_t cap = w->planes_cap ? 2 * w->planes_cap : 64;
            piece_plane *p = realloc(w->planes, cap * sizeof *p);
            uint32_t *q = realloc(w->pending, cap * sizeof *q);
            if (p) w->planes = p;
            if (q) w->pending = q;
            if (!p || !q)
                return OIT_ERR_NOMEM;
            w->planes_cap = cap;
        }
        coplanar = w->nplanes++;
        piece_plane *q = &w->planes[coplanar];
        memcpy(q->v, tv, sizeof q->v);
        q->side = tside;
        q->first = UINT32_MAX;
    }
    w->next_on_plane[t] = w->planes[coplanar].first;
    w->planes[coplanar].first = t;
    plane_of[t] = coplanar;
    return OIT_OK;
}

typedef struct cluster_job {
    grower w;
    uint32_t *queue;
    uint32_t *tested; /* per triangle: stamp of the last piece that tested it */
    int *pending_side;
} cluster_job;

static oit_status grow_piece(cluster_job *j, uint32_t seed, uint32_t max_tris,
                             oit_convex_result *r)
{
    grower *w = &j->w;
    const mesh_graph *g = w->g;
    w->stamp = r->piece_count + 1;
    w->nverts = w->nplanes = 0;
    size_t head = 0, tail = 0;
    uint32_t size = 0;
    j->queue[tail++] = seed;
    j->tested[seed] = w->stamp;
    while (head < tail && size < max_tris) {
        uint32_t t = j->queue[head++];
        uint32_t coplanar, npending;
        int tside;
        if (!accept_test(w, &g->vid[3 * t], &coplanar, &tside, &npending, j->pending_side))
            continue;
        oit_status s = add_triangle(w, t, coplanar, tside, npending, j->pending_side, r->plane_of);
        if (s)
            return s;
        r->piece_of[t] = r->piece_count;
        size++;
        for (uint32_t k = g->nb_first[t]; k < g->nb_first[t + 1]; k++) {
            uint32_t u = g->nb[k];
            if (r->piece_of[u] == UINT32_MAX && j->tested[u] != w->stamp) {
                j->tested[u] = w->stamp;
                j->queue[tail++] = u;
            }
        }
    }
    r->plane_count[r->piece_count++] = w->nplanes;
    return OIT_OK;
}

static oit_status cluster_all(const oit_triangle *tris, size_t n, uint32_t max_tris,
                              const mesh_graph *g, oit_convex_result *r)
{
    cluster_job j = {0};
    j.w.g = g;
    j.w.vstamp = calloc(g->vcount ? g->vcount : 1, sizeof *j.w.vstamp);
    j.w.vslot = malloc((g->vcount ? g->vcount : 1) * sizeof *j.w.vslot);
    j.w.verts = malloc((g->vcount ? g->vcount : 1) * sizeof *j.w.verts);
    j.w.vsign = malloc(g->vcount ? g->vcount : 1);
    j.w.next_on_plane = malloc((n ? n : 1) * sizeof *j.w.next_on_plane);
    j.queue = malloc((n ? n : 1) * sizeof *j.queue);
    j.tested = calloc(n ? n : 1, sizeof *j.tested);
    j.pending_side = malloc((size_t)(n ? n : 1) * sizeof *j.pending_side);
    oit_status s = OIT_OK;
    if (!j.w.vstamp || !j.w.vslot || !j.w.verts || !j.w.vsign || !j.w.next_on_plane ||
        !j.queue || !j.tested || !j.pending_side)
        s = OIT_ERR_NOMEM;
    for (size_t t = 0; t < n && !s; t++)
        if (r->piece_of[t] == UINT32_MAX)
            s = grow_piece(&j, (uint32_t)t, max_tris, r);
    free(j.w.vstamp);
    free(j.w.vslot);
    free(j.w.verts);
    free(j.w.vsign);
    free(j.w.next_on_plane);
    free(j.w.planes);
    free(j.w.pending);
    free(j.queue);
    free(j.tested);
    free(j.pending_side);
    (void)tris;
    return s;
}

oit_status oit_convex_cluster(const oit_triangle *tris, size_t n, const oit_convex_params *params,
                              oit_convex_result *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    uint32_t max_tris = params && params->max_piece_triangles ? params->max_piece_triangles
                                                          : OIT_CONVEX_MAX_PIECE_DEFAULT;
    mesh_graph g = {0};
    oit_status s = assign_vertex_ids(tris, n, &g);
    if (!s)
        s = build_adjacency(n, &g);
    if (!s) {
        out->piece_of = malloc((n ? n : 1) * sizeof *out->piece_of);
        out->plane_of = malloc((n ? n : 1) * sizeof *out->plane_of);
        out->plane_count = malloc((n ? n : 1) * sizeof *out->plane_count);
        if (!out->piece_of || !out->plane_of || !out->plane_count)
            s = OIT_ERR_NOMEM;
        else
            memset(out->piece_of, 0xff, n * sizeof *out->piece_of);
    }
    if (!s)
        s = cluster_all(tris, n, max_tris, &g, out);
    graph_free(&g);
    if (s) {
        oit_convex_result_free(out);
        return oit_error_set(err, s, "convex clustering of %zu triangles: out of memory", n);
    }
    return OIT_OK;
}

void oit_convex_result_free(oit_convex_result *r)
{
    free(r->piece_of);
    free(r->plane_of);
    free(r->plane_count);
    memset(r, 0, sizeof *r);
}

/* ---- brute-force check ----------------------------------------------------- */

static void tri_pos(const oit_triangle *t, double p[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            p[i][k] = t->v[i].pos[k];
}

static int brute_overlap(double a[3][3], double b[3][3], int s, int drop)
{
    for (int pass = 0; pass < 2; pass++) {
        double (*p)[3] = pass ? b : a, (*q)[3] = pass ? a : b;
        for (int e = 0; e < 3; e++) {
            int all_out = 1;
            for (int i = 0; i < 3 && all_out; i++)
                all_out = oit_orient2d(p[e], p[(e + 1) % 3], q[i], drop) * s <= 0;
            if (all_out)
                return 0;
        }
    }
    return 1;
}

int oit_convex_check(const oit_triangle *tris, const uint32_t *idx, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        double a[3][3];
        tri_pos(&tris[idx[i]], a);
        int side = 0;
        for (size_t j = 0; j < count; j++) {
            double b[3][3];
            tri_pos(&tris[idx[j]], b);
            int on = 0;
            for (int v = 0; v < 3; v++) {
                int s = oit_orient3d(a[0], a[1], a[2], b[v]);
                if (s && side && s != side)
                    return 0;
                if (s)
                    side = s;
                on += s == 0;
            }
            if (on == 3 && j != i) {
                int drop = 0, fa = 0;
                for (; drop < 3 && !(fa = oit_orient2d(a[0], a[1], a[2], drop)); drop++)
                    ;
                if (drop == 3 || fa != oit_orient2d(b[0], b[1], b[2], drop) ||
                    brute_overlap(a, b, fa, drop))
                    return 0;
            }
        }
    }
    return 1;
}
