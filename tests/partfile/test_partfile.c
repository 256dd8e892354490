/* Part file writer and reader: round trip of every field and byte, byte-
 * identical output, and refusal of every kind of corruption (truncation,
 * flipped bytes, wrong version, out-of-range index behind valid checksums,
 * sections outside the file or overlapping, absurd counts). Also runs
 * `oitprep info` on a good and a bad file.
 *
 * usage: test_partfile CORPUS_DIR [--write-corpus]
 * The small scene must equal CORPUS_DIR/small.oitp byte for byte (the fuzz
 * seed); --write-corpus rewrites that file after a deliberate format change.
 */
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "partfile/write.h"

#include "partfile/checksum.h"
#include "partfile/layout.h"
#include "tests/partfile/partfile_reencode.h"
#include "tests/partfile/partfile_reseal.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>


/* ---- the synthetic scene ---------------------------------------------------- */

typedef struct part_in {
    float *pos;
    uint8_t *rgba;
    uint32_t nv;
    uint32_t *idx;
    uint64_t ni;
    uint32_t *src; /* ni / 3 source indices, < the scene's 1000 triangles_in */
    oit_partfile_piece_desc pieces[4];
    uint32_t np;
} part_in;

typedef struct grid_in {
    oit_partfile_grid_desc desc;
    uint32_t counts[8];
    uint32_t parts[16];
} grid_in;

typedef struct scene {
    part_in parts[4];
    uint32_t nparts;
    grid_in grids[3];
    uint32_t ngrids;
    oit_partfile_slab_desc slabs[2];
    uint32_t inside[2][2];
    uint32_t nslabs;
} scene;

static void tetra(part_in *p, uint32_t v0, const float base[3], float size, uint32_t piece)
{
    static const float corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const uint32_t tri[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            p->pos[(v0 + i) * 3 + k] = base[k] + size * corner[i][k];
    for (int i = 0; i < 12; i++)
        p->idx[p->ni++] = v0 + tri[i];
    p->pieces[piece] = (oit_partfile_piece_desc){.triangle_count = 4, .plane_count = 4};
}

static void alloc_part(part_in *p, uint32_t nv, uint64_t ni, int colour)
{
    p->nv = nv;
    p->pos = calloc((size_t)nv * 3, sizeof *p->pos);
    p->idx = calloc(ni, sizeof *p->idx);
    p->src = malloc((ni / 3 ? ni / 3 : 1) * sizeof *p->src);
    for (uint64_t t = 0; t < ni / 3; t++)
        p->src[t] = (uint32_t)((t * 7 + nv) % 997);
    p->rgba = colour ? malloc((size_t)nv * 4) : NULL;
    for (uint32_t i = 0; colour && i < nv * 4; i++)
        p->rgba[i] = (uint8_t)(i * 37 + 11);
}

/* A planar nx x ny vertex grid at z: one convex piece of 2(nx-1)(ny-1) triangles. */
static void plane(part_in *p, uint32_t nx, uint32_t ny, const float lo[2], float step, float z,
                  int colour)
{
    alloc_part(p, nx * ny, 6ull * (nx - 1) * (ny - 1), colour);
    for (uint32_t y = 0; y < ny; y++)
        for (uint32_t x = 0; x < nx; x++) {
            float *v = p->pos + ((size_t)y * nx + x) * 3;
            v[0] = lo[0] + step * (float)x;
            v[1] = lo[1] + step * (float)y;
            v[2] = z;
        }
    for (uint32_t y = 0; y + 1 < ny; y++)
        for (uint32_t x = 0; x + 1 < nx; x++) {
            uint32_t a = y * nx + x, q[6] = {a, a + 1, a + nx, a + 1, a + nx + 1, a + nx};
            memcpy(p->idx + p->ni, q, sizeof q);
            p->ni += 6;
        }
    p->pieces[0] = (oit_partfile_piece_desc){.triangle_count = p->ni / 3, .plane_count = 1};
    p->np = 1;
}

static void small_parts(scene *s)
{
    part_in *a = &s->parts[0], *b = &s->parts[1];
    alloc_part(a, 4, 12, 0);
    tetra(a, 0, (const float[3]){1, 1, 1}, 3, 0);
    a->np = 1;
    alloc_part(b, 8, 24, 1);
    tetra(b, 0, (const float[3]){5, 5, 2}, 3, 0);
    tetra(b, 4, (const float[3]){2, 6, 5}, 2.5f, 1);
    b->np = 2;
    s->nparts = 2;
}

static void set_grid(grid_in *g, const uint32_t dims[3], const float origin[3], const float cs[3],
                     uint32_t parent_grid, uint32_t parent_cell, const uint32_t *counts,
                     const uint32_t *parts)
{
    uint32_t cells = dims[0] * dims[1] * dims[2], total = 0;
    memcpy(g->desc.dims, dims, sizeof g->desc.dims);
    memcpy(g->desc.origin, origin, sizeof g->desc.origin);
    memcpy(g->desc.cell_size, cs, sizeof g->desc.cell_size);
    g->desc.parent_grid = parent_grid;
    g->desc.parent_cell = parent_cell;
    memcpy(g->counts, counts, cells * sizeof *counts);
    for (uint32_t c = 0; c < cells; c++)
        total += counts[c];
    memcpy(g->parts, parts, total * sizeof *parts);
    g->desc.cell_counts = g->counts;
    g->desc.cell_parts = g->parts;
}

static void set_slab(scene *s, uint32_t i, const float n[3], float d0, float d1, uint32_t grid,
                     uint32_t cell, uint32_t below, uint32_t above, const uint32_t *inside,
                     uint32_t ninside)
{
    oit_partfile_slab_desc *sl = &s->slabs[i];
    memcpy(sl->normal, n, sizeof sl->normal);
    sl->d0 = d0;
    sl->d1 = d1;
    sl->grid = grid;
    sl->cell = cell;
    sl->part_below = below;
    sl->part_above = above;
    if (ninside)
        memcpy(s->inside[i], inside, ninside * sizeof *inside);
    sl->inside = s->inside[i];
    sl->inside_count = ninside;
}

/* Two tetra parts, a 1x1x1 grid refined by a 1x1x2 subgrid, one slab. */
static void small_scene(scene *s)
{
    memset(s, 0, sizeof *s);
    small_parts(s);
    set_grid(&s->grids[0], (const uint32_t[3]){1, 1, 1}, (const float[3]){0, 0, 0},
             (const float[3]){10, 10, 10}, 0, 0, (const uint32_t[]){2}, (const uint32_t[]){0, 1});
    set_grid(&s->grids[1], (const uint32_t[3]){1, 1, 2}, (const float[3]){0, 0, 0},
             (const float[3]){10, 10, 5}, 0, 0, (const uint32_t[]){2, 1},
             (const uint32_t[]){0, 1, 1});
    s->ngrids = 2;
    set_slab(s, 0, (const float[3]){0, 0, 1}, 4.0f, 4.5f, 1, 0, 0, 1, NULL, 0);
    s->nslabs = 1;
}

/* Adds a 70000-vertex part (32-bit indices, colour) and a 65536-vertex part
 * (the largest with 16-bit indices), a 2x2x1 grid with subgrids two deep and
 * two slabs. */
static void big_scene(scene *s)
{
    memset(s, 0, sizeof *s);
    small_parts(s);
    plane(&s->parts[2], 280, 250, (const float[2]){0.5f, 0.5f}, 0.068f, 5, 1);
    part_in *d = &s->parts[3];
    alloc_part(d, 65536, 6, 0);
    for (uint32_t i = 0; i < 65536; i++) {
        d->pos[i * 3 + 0] = 15;
        d->pos[i * 3 + 1] = 10 + (float)(i % 256) / 25.6f;
        d->pos[i * 3 + 2] = (float)(i / 256) / 25.6f;
    }
    const uint32_t tris[6] = {0, 1, 65535, 65535, 65534, 2};
    memcpy(d->idx, tris, sizeof tris);
    d->ni = 6;
    d->pieces[0] = (oit_partfile_piece_desc){.triangle_count = 2, .plane_count = 1};
    d->np = 1;
    s->nparts = 4;
    set_grid(&s->grids[0], (const uint32_t[3]){2, 2, 1}, (const float[3]){0, 0, 0},
             (const float[3]){10, 10, 10}, 0, 0, (const uint32_t[]){3, 2, 2, 2},
             (const uint32_t[]){0, 1, 2, 2, 3, 1, 2, 2, 3});
    set_grid(&s->grids[1], (const uint32_t[3]){2, 1, 1}, (const float[3]){10, 10, 0},
             (const float[3]){5, 10, 10}, 0, 3, (const uint32_t[]){1, 2},
             (const uint32_t[]){2, 2, 3});
    set_grid(&s->grids[2], (const uint32_t[3]){1, 1, 2}, (const float[3]){15, 10, 0},
             (const float[3]){5, 10, 5}, 1, 1, (const uint32_t[]){2, 1},
             (const uint32_t[]){2, 3, 3});
    s->ngrids = 3;
    set_slab(s, 0, (const float[3]){0, 0, 1}, 1.5f, 2.5f, 0, 0, 0, 1, (const uint32_t[]){2}, 1);
    set_slab(s, 1, (const float[3]){1, 0, 0}, 14.9f, 15.1f, 2, 0, 2, 3, NULL, 0);
    s->nslabs = 2;
}

static void scene_free(scene *s)
{
    for (uint32_t i = 0; i < s->nparts; i++) {
        free(s->parts[i].pos);
        free(s->parts[i].rgba);
        free(s->parts[i].idx);
        free(s->parts[i].src);
    }
}

static oit_status write_scene_ordered(const scene *s, const char *path, uint32_t align,
                                      oit_partfile_order order, oit_error *err)
{
    oit_partfile_writer *w;
    oit_partfile_writer_desc wd = {.part_align = align, .source_name = "synthetic \"scene\"",
                                   .options = "-K 8", .attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA,
                                   .origin = {1e7, -2500000.5, 0.125}, .order = order};
    oit_status st = oit_partfile_writer_create(path, &wd, &w, err);
    for (uint32_t i = 0; !st && i < s->nparts; i++) {
        const part_in *p = &s->parts[i];
        oit_partfile_part_desc pd = {.positions = p->pos, .rgba = p->rgba, .vertex_count = p->nv,
                                     .indices = p->idx, .index_count = p->ni,
                                     .sources = p->src, .pieces = p->pieces, .piece_count = p->np};
        st = oit_partfile_writer_add_part(w, &pd, NULL, err);
    }
    if (!st)
        st = oit_partfile_writer_set_grid(w, &s->grids[0].desc, err);
    for (uint32_t g = 1; !st && g < s->ngrids; g++)
        st = oit_partfile_writer_add_subgrid(w, &s->grids[g].desc, NULL, err);
    for (uint32_t i = 0; !st && i < s->nslabs; i++)
        st = oit_partfile_writer_add_slab(w, &s->slabs[i], NULL, err);
    if (st) {
        oit_partfile_writer_abort(w);
        return st;
    }
    oit_partfile_stats stats = {.triangles_in = 1000, .triangles_dropped = 3, .triangles_split = 7};
    return oit_partfile_writer_finish(w, &stats, err);
}

static oit_status write_scene(const scene *s, const char *path, uint32_t align, oit_error *err)
{
    return write_scene_ordered(s, path, align, OIT_PARTFILE_ORDER_KEEP, err);
}

/* s written as dir/name (that path in path[600]), then read back whole: its
 * bytes (free them; NULL when either failed, said as a failed check) and
 * their count in *n. */
static uint8_t *write_and_read(const scene *s, const char *dir, const char *name, uint32_t align,
                               char *path, size_t *n)
{
    oit_error err = {0};
    *n = 0;
    snprintf(path, 600, "%s/%s", dir, name);
    CHECK(write_scene(s, path, align, &err) == OIT_OK, "%s: %s", path, err.message);
    return test_read_file(path, n);
}

/* ---- round trip ------------------------------------------------------------- */

/* A triangle as the renderer sees it: its three positions in order (the tie
 * rule's plane starts at vertex 0), colours, and its source index. */
typedef struct tri_key {
    float pos[9];
    uint8_t rgba[12];
    uint32_t src;
} tri_key;

static int tri_key_cmp(const void *a, const void *b) { return memcmp(a, b, sizeof(tri_key)); }

/* Vertex i's position at pos + i * stride, its colour at rgba + i * rgba_stride. */
static tri_key key_of(const float *pos, size_t stride, const uint8_t *rgba, size_t rgba_stride,
                      const uint32_t v[3], uint32_t src)
{
    tri_key k;
    memset(&k, 0, sizeof k);
    for (int c = 0; c < 3; c++) {
        memcpy(k.pos + 3 * c, (const uint8_t *)pos + v[c] * stride, 12);
        if (rgba)
            memcpy(k.rgba + 4 * c, rgba + v[c] * rgba_stride, 4);
    }
    k.src = src;
    return k;
}

/* Written with OIT_PARTFILE_ORDER_CACHE: each piece holds the same
 * triangles (positions bit for bit, vertex order, colours, source index)
 * as written, in whatever order. */
static void check_cache_order(const char *tmp, const scene *s)
{
    char path[600];
    snprintf(path, sizeof path, "%s/partfile_ordered.oitp", tmp);
    oit_error err = {0};
    CHECK(write_scene_ordered(s, path, 64, OIT_PARTFILE_ORDER_CACHE, &err) == OIT_OK, "%s",
          err.message);
    oit_partfile *pf = NULL;
    CHECK(oit_partfile_open(path, NULL, &pf, &err) == OIT_OK, "%s", err.message);
    if (!pf)
        return;
    oit_partfile_buffer buf = {0};
    uint64_t differ = 0, moved = 0;
    for (uint32_t i = 0; i < s->nparts; i++) {
        const part_in *in = &s->parts[i];
        oit_partfile_part_view v;
        CHECK(oit_partfile_part_data(pf, i, &buf, &v, &err) == OIT_OK, "%s", err.message);
        if (v.index_count != in->ni)
            continue;
        uint64_t n = in->ni / 3, first = 0;
        tri_key *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
        for (uint64_t t = 0; a && b && t < n; t++) {
            uint32_t iv[3] = {in->idx[3 * t], in->idx[3 * t + 1], in->idx[3 * t + 2]};
            uint32_t ov[3] = {oit_partfile_index(&v, 3 * t), oit_partfile_index(&v, 3 * t + 1),
                              oit_partfile_index(&v, 3 * t + 2)};
            a[t] = key_of(in->pos, 12, in->rgba, 4, iv, in->src[t]);
            b[t] = key_of(v.positions, v.stride, v.rgba, v.stride, ov,
                          oit_partfile_source(&v, t));
            moved += memcmp(&a[t], &b[t], sizeof a[t]) != 0;
        }
        for (uint32_t k = 0; a && b && k < in->np; k++) {
            uint64_t c = in->pieces[k].triangle_count;
            qsort(a + first, c, sizeof *a, tri_key_cmp);
            qsort(b + first, c, sizeof *b, tri_key_cmp);
            differ += memcmp(a + first, b + first, c * sizeof *a) != 0;
            first += c;
        }
        free(a);
        free(b);
    }
    printf("  vertex-cache order: %llu triangles moved, %llu pieces with other triangles\n",
           (unsigned long long)moved, (unsigned long long)differ);
    CHECK(differ == 0, "cache order: %llu pieces hold other triangles than written",
          (unsigned long long)differ);
    CHECK(moved > 0, "cache order moved no triangle: the test would not see a lost source");
    oit_partfile_buffer_free(&buf);
    oit_partfile_close(pf);
    remove(path);
}

static void check_part_bytes(const oit_partfile *pf, uint32_t i, const part_in *in)
{
    oit_partfile_part_view v;
    oit_error err = {0};
    oit_partfile_buffer buf = {0};
    CHECK(oit_partfile_part_data(pf, i, &buf, &v, &err) == OIT_OK, "%s", err.message);
    uint64_t bad_pos = 0, bad_rgba = 0, bad_idx = 0;
    for (uint32_t j = 0; j < in->nv; j++) {
        const uint8_t *vert = (const uint8_t *)v.positions + (size_t)j * v.stride;
        bad_pos += memcmp(vert, in->pos + (size_t)j * 3, 12) != 0;
        if (in->rgba)
            bad_rgba += memcmp(v.rgba + (size_t)j * v.stride, in->rgba + (size_t)j * 4, 4) != 0;
    }
    for (uint64_t j = 0; j < v.index_count; j++) {
        uint32_t x = oit_partfile_index(&v, j);
        bad_idx += x != in->idx[j];
    }
    uint64_t bad_src = 0;
    for (uint64_t t = 0; t < v.index_count / 3; t++)
        bad_src += oit_partfile_source(&v, t) != in->src[t];
    CHECK(bad_pos == 0 && bad_rgba == 0 && bad_idx == 0 && bad_src == 0,
          "part %u: %llu positions, %llu colours, %llu indices, %llu source indices differ", i,
          (unsigned long long)bad_pos, (unsigned long long)bad_rgba, (unsigned long long)bad_idx,
          (unsigned long long)bad_src);
    CHECK(v.index_count == in->ni, "part %u: %llu indices, wrote %llu", i,
          (unsigned long long)v.index_count, (unsigned long long)in->ni);
    CHECK((in->rgba != NULL) == (v.rgba != NULL) && v.stride == (in->rgba ? 16u : 12u),
          "part %u: stride %u", i, v.stride);
    oit_partfile_buffer_free(&buf);
}

static void check_part_record(const oit_partfile *pf, uint32_t i, const part_in *in,
                              uint64_t *piece)
{
    const oit_partfile_part *p = &oit_partfile_parts(pf)[i];
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (uint32_t j = 0; j < in->nv * 3; j++) {
        lo[j % 3] = in->pos[j] < lo[j % 3] ? in->pos[j] : lo[j % 3];
        hi[j % 3] = in->pos[j] > hi[j % 3] ? in->pos[j] : hi[j % 3];
    }
    CHECK(!memcmp(lo, p->bounds_min, 12) && !memcmp(hi, p->bounds_max, 12), "part %u bounds", i);
    CHECK(p->vertex_count == in->nv && p->index_count == in->ni && p->piece_count == in->np &&
              p->piece_first == *piece,
          "part %u: %u vertices %llu indices %u pieces from %u", i, p->vertex_count,
          (unsigned long long)p->index_count, p->piece_count, p->piece_first);
    CHECK(p->index_bits == (in->nv <= 65536 ? 16u : 32u), "part %u: %u-bit", i, p->index_bits);
    CHECK(p->attributes == (in->rgba ? 3u : 0u), "part %u attributes %u", i, p->attributes);
    CHECK(p->layer_bound == 2 * in->np, "part %u layer bound %u", i, p->layer_bound);
    const oit_partfile_piece *pc = oit_partfile_pieces(pf) + p->piece_first;
    uint64_t first = 0;
    for (uint32_t k = 0; k < in->np; k++) {
        CHECK(pc[k].part == i && pc[k].triangle_first == first &&
                  pc[k].triangle_count == in->pieces[k].triangle_count &&
                  pc[k].plane_count == in->pieces[k].plane_count,
              "part %u piece %u", i, k);
        first += in->pieces[k].triangle_count;
    }
    *piece += in->np;
    check_part_bytes(pf, i, in);
}

static void check_grids(const oit_partfile *pf, const scene *s)
{
    CHECK(oit_partfile_grid_count(pf) == s->ngrids, "%u grids", oit_partfile_grid_count(pf));
    for (uint32_t g = 0; g < s->ngrids && g < oit_partfile_grid_count(pf); g++) {
        const oit_partfile_grid *gr = oit_partfile_grid_at(pf, g);
        const grid_in *in = &s->grids[g];
        CHECK(!memcmp(gr->dims, in->desc.dims, 12) && !memcmp(gr->origin, in->desc.origin, 12) &&
                  !memcmp(gr->cell_size, in->desc.cell_size, 12),
              "grid %u geometry", g);
        uint32_t depth = g ? oit_partfile_grid_at(pf, gr->parent_grid)->depth + 1 : 0;
        CHECK(gr->depth == depth && (g == 0 || (gr->parent_grid == in->desc.parent_grid &&
                                                gr->parent_cell == in->desc.parent_cell)),
              "grid %u: depth %u parent %u/%u", g, gr->depth, gr->parent_grid, gr->parent_cell);
        const uint32_t *want = in->parts;
        for (uint64_t c = 0; c < gr->cell_count; c++) {
            uint32_t n;
            const uint32_t *got = oit_partfile_cell_parts(pf, g, c, &n);
            CHECK(n == in->counts[c] && !memcmp(got, want, n * sizeof *got),
                  "grid %u cell %llu: %u parts", g, (unsigned long long)c, n);
            want += in->counts[c];
            const oit_partfile_cell *cell = &oit_partfile_cells(pf, g)[c];
            uint32_t sub = 0, slab = 0;
            for (uint32_t k = 1; k < s->ngrids; k++)
                sub = s->grids[k].desc.parent_grid == g && s->grids[k].desc.parent_cell == c ? k : sub;
            for (uint32_t k = 0; k < s->nslabs; k++)
                slab = s->slabs[k].grid == g && s->slabs[k].cell == c ? k + 1 : slab;
            CHECK(cell->subgrid == sub && cell->slab == slab, "grid %u cell %llu: links %u %u", g,
                  (unsigned long long)c, cell->subgrid, cell->slab);
        }
    }
}

static void check_slabs(const oit_partfile *pf, const scene *s)
{
    CHECK(oit_partfile_slab_count(pf) == s->nslabs, "%u slabs", oit_partfile_slab_count(pf));
    for (uint32_t i = 0; i < s->nslabs && i < oit_partfile_slab_count(pf); i++) {
        const oit_partfile_slab *sl = oit_partfile_slab_at(pf, i);
        const oit_partfile_slab_desc *in = &s->slabs[i];
        uint32_t n;
        const uint32_t *inside = oit_partfile_slab_inside(pf, i, &n);
        CHECK(!memcmp(sl->normal, in->normal, 12) && sl->d0 == in->d0 && sl->d1 == in->d1 &&
                  sl->grid == in->grid && sl->cell == in->cell &&
                  sl->part_below == in->part_below && sl->part_above == in->part_above &&
                  n == in->inside_count && (n == 0 || !memcmp(inside, in->inside, n * 4)),
              "slab %u", i);
    }
}

static void check_summary(const oit_partfile *pf, const scene *s, size_t bytes)
{
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    uint64_t tris = 0, pieces = 0, cells = 0, idx16 = 0;
    uint32_t layers = 0;
    for (uint32_t i = 0; i < s->nparts; i++) {
        tris += s->parts[i].ni / 3;
        pieces += s->parts[i].np;
        idx16 += s->parts[i].nv <= 65536;
        layers = 2 * s->parts[i].np > layers ? 2 * s->parts[i].np : layers;
    }
    for (uint32_t g = 0; g < s->ngrids; g++)
        cells += (uint64_t)s->grids[g].desc.dims[0] * s->grids[g].desc.dims[1] *
                 s->grids[g].desc.dims[2];
    printf("  summary: %llu triangles, %llu parts (%llu 16-bit), %llu pieces, %llu cells, "
           "%llu subgrids (depth %u), %llu slabs, layer bound %u, %llu bytes\n",
           (unsigned long long)sum.triangles, (unsigned long long)sum.parts,
           (unsigned long long)sum.parts_index16, (unsigned long long)sum.pieces,
           (unsigned long long)sum.cells, (unsigned long long)sum.subgrids, sum.subgrid_depth,
           (unsigned long long)sum.slabs, sum.layer_bound, (unsigned long long)sum.bytes);
    CHECK(sum.origin[0] == 1e7 && sum.origin[1] == -2500000.5 && sum.origin[2] == 0.125,
          "origin (%.17g %.17g %.17g) did not round-trip", sum.origin[0], sum.origin[1],
          sum.origin[2]);
    CHECK(sum.version == OIT_PARTFILE_VERSION && sum.K == 8 && sum.triangles == tris && sum.parts == s->nparts &&
              sum.pieces == pieces && sum.cells == cells && sum.subgrids == s->ngrids - 1u &&
              sum.subgrid_depth == s->ngrids - 1u && sum.slabs == s->nslabs &&
              sum.layer_bound == layers && sum.parts_index16 == idx16 &&
              sum.parts_index32 == s->nparts - idx16 && sum.bytes == bytes &&
              sum.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA) && sum.triangles_in == 1000 &&
              sum.triangles_dropped == 3 && sum.triangles_split == 7,
          "summary differs from the scene");
}

static void check_round_trip(const oit_partfile *pf, const scene *s, size_t bytes)
{
    check_summary(pf, s, bytes);
    CHECK(!strcmp(oit_partfile_source_name(pf), "synthetic \"scene\"") &&
              !strcmp(oit_partfile_options(pf), "-K 8"),
          "META strings '%s' '%s'", oit_partfile_source_name(pf), oit_partfile_options(pf));
    CHECK(oit_partfile_part_count(pf) == s->nparts, "%u parts", oit_partfile_part_count(pf));
    uint64_t piece = 0;
    for (uint32_t i = 0; i < s->nparts && i < oit_partfile_part_count(pf); i++) {
        check_part_record(pf, i, &s->parts[i], &piece);
        const oit_partfile_part *p = &oit_partfile_parts(pf)[i];
        oit_partfile_summary sum;
        oit_partfile_get_summary(pf, &sum);
        CHECK(p->data_offset % sum.part_align == 0, "part %u blob at %llu", i,
              (unsigned long long)p->data_offset);
    }
    check_grids(pf, s);
    check_slabs(pf, s);
}

/* ---- files ------------------------------------------------------------------- */

static int spill(const char *path, const uint8_t *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int ok = fwrite(b, 1, n, f) == n;
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* ---- corruption -------------------------------------------------------------- */

typedef struct corrupt_ctx {
    const uint8_t *good;
    size_t size;
    char path[512];
    int cases;
} corrupt_ctx;

static pf_section get_section(const uint8_t *b, uint32_t type)
{
    pf_section s;
    memcpy(&s, b + PF_HEADER_BYTES + (type - 1) * PF_ENTRY_BYTES, sizeof s);
    return s;
}

static void put_section(uint8_t *b, uint32_t type, const pf_section *s)
{
    memcpy(b + PF_HEADER_BYTES + (type - 1) * PF_ENTRY_BYTES, s, sizeof *s);
}

/* The reader must refuse buf with OIT_ERR_FORMAT and a message that names
 * the file and contains needle. */
static void expect_refused(corrupt_ctx *c, const char *what, const uint8_t *buf, size_t n,
                           const char *needle)
{
    c->cases++;
    if (spill(c->path, buf, n) != 0) {
        CHECK(0, "cannot write %s", c->path);
        return;
    }
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_status st = oit_partfile_open(c->path, NULL, &pf, &err);
    CHECK(st == OIT_ERR_FORMAT && pf == NULL, "%s: status %s", what, oit_status_name(st));
    CHECK(strstr(err.message, c->path) != NULL, "%s: message does not name the file: %s", what,
          err.message);
    CHECK(!needle || strstr(err.message, needle), "%s: expected '%s' in: %s", what, needle,
          err.message);
    printf("  refused %-34s %s\n", what, err.message + strlen(c->path) + 2);
    oit_partfile_close(pf);
}

static void corrupt_truncations(corrupt_ctx *c)
{
    size_t cuts[2 * PF_SECTION_COUNT + 4];
    size_t n = 0;
    cuts[n++] = 0;
    cuts[n++] = PF_HEADER_BYTES - 1;
    cuts[n++] = PF_TABLE_END - 1;
    cuts[n++] = c->size - 1;
    for (uint32_t t = 1; t <= PF_SECTION_COUNT; t++) {
        pf_section s = get_section(c->good, t);
        cuts[n++] = s.offset;
        cuts[n++] = s.offset + s.size;
    }
    for (size_t i = 0; i < n; i++) {
        if (cuts[i] >= c->size)
            continue;
        char what[64];
        snprintf(what, sizeof what, "truncated to %zu bytes", cuts[i]);
        expect_refused(c, what, c->good, cuts[i], cuts[i] == 0 ? "empty" : "bytes");
    }
}

static void corrupt_flips(corrupt_ctx *c, uint8_t *b)
{
    for (uint32_t t = 1; t <= PF_SECTION_COUNT; t++) {
        pf_section s = get_section(c->good, t);
        if (!s.size)
            continue;
        memcpy(b, c->good, c->size);
        b[s.offset + s.size / 2] ^= 0x10;
        char what[64];
        snprintf(what, sizeof what, "flipped byte in %s", pf_section_name(t));
        expect_refused(c, what, b, c->size, "checksum");
    }
    memcpy(b, c->good, c->size);
    b[40] ^= 1; /* part_count */
    expect_refused(c, "flipped byte in header", b, c->size, "checksum");
    memcpy(b, c->good, c->size);
    b[PF_HEADER_BYTES + 3 * PF_ENTRY_BYTES + 9] ^= 1;
    expect_refused(c, "flipped byte in section table", b, c->size, NULL);
}

static void set_u32(uint8_t *b, size_t at, uint32_t v) { memcpy(b + at, &v, 4); }
static void set_u64(uint8_t *b, size_t at, uint64_t v) { memcpy(b + at, &v, 8); }

/* The good file with one decoded value of part `part` replaced (index i,
 * or source index i when `source`), re-encoded and resealed
 * (partfile_reencode.h), expected refused with needle. */
static void corrupt_decoded(corrupt_ctx *c, uint32_t part, int source, uint64_t i,
                            uint32_t value, const char *what, const char *needle)
{
    decoded_part d = {0};
    CHECK(decode_part(c->good, part, &d) == 0, "%s: the good file's part %u does not decode",
          what, part);
    (source ? d.sources : d.indices)[i] = value;
    size_t n = 0;
    uint8_t *b = reencode_part(c->good, c->size, part, &d, &n);
    decoded_part_free(&d);
    CHECK(b != NULL, "%s: cannot re-encode part %u", what, part);
    if (b)
        expect_refused(c, what, b, n, needle);
    free(b);
}

/* Edits an index of part `part`, re-encodes it and reseals every checksum. */
static void corrupt_index(corrupt_ctx *c, uint8_t *b, uint32_t part, uint32_t value,
                          const char *needle)
{
    (void)b;
    char what[64];
    snprintf(what, sizeof what, "index %u in part %u, resealed", value, part);
    corrupt_decoded(c, part, 0, 3, value, what, needle);
}

/* Edits the source index of triangle `tri` of part `part`, re-encodes it
 * and reseals every checksum. */
static void corrupt_source(corrupt_ctx *c, uint8_t *b, uint32_t part, uint32_t tri,
                           uint32_t value, const char *needle)
{
    (void)b;
    char what[80];
    snprintf(what, sizeof what, "source index %u of part %u, resealed", value, part);
    corrupt_decoded(c, part, 1, tri, value, what, needle);
}

/* Writes part 1's record p back at `at`, reseals, and expects a refusal. */
static void expect_part_refused(corrupt_ctx *c, uint8_t *b, size_t at,
                                const oit_partfile_part *p, const char *what,
                                const char *want)
{
    memcpy(b + at, p, sizeof *p);
    reseal_part(b, c->size, 1);
    reseal(b, c->size);
    expect_refused(c, what, b, c->size, want);
}

/* Stored streams that do not decode, behind valid checksums: the
 * vertex/index boundary moved by one byte, then garbage in the index
 * stream. Refused (not read past, not crashed on) with a message naming
 * the file and the part. */
static void corrupt_streams(corrupt_ctx *c, uint8_t *b)
{
    pf_section ps = get_section(c->good, PF_SEC_PARTS);
    size_t at = ps.offset + sizeof(oit_partfile_part); /* part 1 */
    oit_partfile_part p;
    memcpy(b, c->good, c->size);
    memcpy(&p, b + at, sizeof p);
    p.stored_vertex_bytes -= 1;
    p.stored_index_bytes += 1;
    expect_part_refused(c, b, at, &p, "vertex stream one byte short, resealed",
                        "part 1: the vertex stream does not decode");
    memcpy(b, c->good, c->size);
    memcpy(&p, b + at, sizeof p);
    memset(b + p.data_offset + p.stored_vertex_bytes + 1, 0xff,
           (size_t)(p.stored_index_bytes - 2));
    expect_part_refused(c, b, at, &p, "index stream garbage, resealed", "part 1: ");
    memcpy(b, c->good, c->size);
    memcpy(&p, b + at, sizeof p);
    p.stored_bytes += 1;
    p.stored_source_bytes += 1;
    expect_part_refused(c, b, at, &p, "source stream one byte long, resealed",
                        "part 1: the source index stream does not decode");
}

static void corrupt_semantics(corrupt_ctx *c, uint8_t *b)
{
    memcpy(b, c->good, c->size);
    set_u32(b, offsetof(pf_header, version), 6);
    expect_refused(c, "version 6", b, c->size, "part file version 6, this build reads version 5");
    memcpy(b, c->good, c->size);
    set_u32(b, offsetof(pf_header, version), 0);
    expect_refused(c, "version 0", b, c->size, "part file version 0, this build reads version 5");
    memcpy(b, c->good, c->size);
    set_u32(b, offsetof(pf_header, version), 4);
    expect_refused(c, "version 4", b, c->size,
                   "part file version 4 stores its parts unencoded, this build reads version 5");
    for (uint32_t v = 1; v <= 3; v++) {
        memcpy(b, c->good, c->size);
        set_u32(b, offsetof(pf_header, version), v);
        char what[32];
        snprintf(what, sizeof what, "version %u", v);
        expect_refused(c, what, b, c->size, "convert the model again");
    }

    corrupt_index(c, b, 2, 70000, "index 70000 >= 70000 vertices");
    corrupt_index(c, b, 0, 9, "index 9 >= 4 vertices");
    /* triangles_in is 1000: 999 is the last valid source index. */
    corrupt_source(c, b, 1, 5, 1000, "part 1: triangle 5: source index 1000 >= 1000 source");
    corrupt_source(c, b, 3, 1, 0xFFFFFFFFu, "part 3: triangle 1: source index 4294967295");

    memcpy(b, c->good, c->size);
    pf_section s = get_section(b, PF_SEC_PIECES);
    s.offset = pf_align_up(c->size + 8, 8);
    put_section(b, PF_SEC_PIECES, &s);
    reseal(b, c->size);
    expect_refused(c, "PIECES offset past the end", b, c->size, "outside");

    memcpy(b, c->good, c->size);
    s = get_section(b, PF_SEC_GRID);
    s.offset = get_section(b, PF_SEC_PARTS).offset;
    put_section(b, PF_SEC_GRID, &s);
    reseal(b, c->size);
    expect_refused(c, "GRID overlapping PARTS", b, c->size, "overlap");

    memcpy(b, c->good, c->size);
    set_u64(b, offsetof(pf_header, part_count), 4000000000ull);
    reseal(b, c->size);
    expect_refused(c, "header claims 4e9 parts", b, c->size, "4000000000");

    memcpy(b, c->good, c->size);
    set_u64(b, get_section(b, PF_SEC_GRID).offset + offsetof(pf_grid_block, cell_count),
            4000000000ull);
    reseal(b, c->size);
    expect_refused(c, "GRID claims 4e9 cells", b, c->size, "4000000000");

    memcpy(b, c->good, c->size);
    set_u32(b, get_section(b, PF_SEC_SLABS).offset + offsetof(pf_slab_block, slab_count),
            4000000000u);
    reseal(b, c->size);
    expect_refused(c, "SLABS claims 4e9 slabs", b, c->size, "4000000000");

    /* A cutting plane's integer normal (1,-1,0) is valid (versions 1 and 2,
     * which asked for unit normals, are no longer read); a zero normal is
     * refused. */
    size_t normal = get_section(b, PF_SEC_SLABS).offset + sizeof(pf_slab_block);
    const float integer_normal[3] = {1, -1, 0}, zero[3] = {0, 0, 0};
    memcpy(b, c->good, c->size);
    memcpy(b + normal, integer_normal, sizeof integer_normal);
    reseal(b, c->size);
    oit_partfile *pf = NULL;
    oit_error err = {0};
    CHECK(spill(c->path, b, c->size) == 0 && oit_partfile_open(c->path, NULL, &pf, &err) == OIT_OK,
          "slab normal (1,-1,0): %s", err.message);
    oit_partfile_close(pf);
    memcpy(b, c->good, c->size);
    memcpy(b + normal, zero, sizeof zero);
    reseal(b, c->size);
    expect_refused(c, "slab normal zero", b, c->size, "zero");

    memcpy(b, c->good, c->size);
    pf_section ps = get_section(b, PF_SEC_PARTS);
    set_u32(b, ps.offset + offsetof(oit_partfile_part, layer_bound), 9); /* K is 8 */
    reseal(b, c->size);
    expect_refused(c, "layer bound 9 > K", b, c->size, "layer bound 9");

    memcpy(b, c->good, c->size);
    pf_section gs = get_section(b, PF_SEC_GRID);
    size_t list0 = gs.offset + sizeof(pf_grid_block) + sizeof(oit_partfile_grid) +
                   4 * sizeof(oit_partfile_cell);
    set_u32(b, list0 + 4, 7); /* cell 0's second part: no part 7 */
    reseal(b, c->size);
    expect_refused(c, "cell names part 7 of 4", b, c->size, "part 7");
}

/* The last part's stored streams reaching past PART_DATA's end, its source
 * stream grown to match and every checksum resealed: only the blob bounds
 * can see it. */
static void corrupt_blob_bounds(corrupt_ctx *c, uint8_t *b)
{
    memcpy(b, c->good, c->size);
    pf_section ps = get_section(b, PF_SEC_PARTS), ds = get_section(b, PF_SEC_PART_DATA);
    pf_header h;
    memcpy(&h, b, sizeof h);
    oit_partfile_part p;
    size_t at = ps.offset + (size_t)(h.part_count - 1) * sizeof p;
    memcpy(&p, b + at, sizeof p);
    uint64_t slack = ds.offset + ds.size - (p.data_offset + p.stored_bytes);
    p.stored_source_bytes += slack + 1;
    p.stored_bytes += slack + 1;
    memcpy(b + at, &p, sizeof p);
    reseal(b, c->size);
    expect_refused(c, "last blob past PART_DATA, resealed", b, c->size, "outside PART_DATA");
}

/* With deferred part data the section checksum is skipped, so a flipped byte
 * in one part's blob must be found by that part's own checksum when it is
 * validated, and only there. */
static void corrupt_deferred(corrupt_ctx *c, uint8_t *b)
{
    memcpy(b, c->good, c->size);
    pf_section ps = get_section(b, PF_SEC_PARTS);
    oit_partfile_part p;
    memcpy(&p, b + ps.offset + sizeof p, sizeof p);
    b[p.data_offset + p.stored_bytes / 2] ^= 0x04;
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_partfile_open_desc od = {.defer_part_data = true};
    CHECK(spill(c->path, b, c->size) == 0 && oit_partfile_open(c->path, &od, &pf, &err) == OIT_OK,
          "deferred open of a file with a flipped blob byte: %s", err.message);
    if (!pf)
        return;
    c->cases++;
    CHECK(oit_partfile_validate_part(pf, 0, &err) == OIT_OK, "deferred part 0: %s", err.message);
    oit_status st = oit_partfile_validate_part(pf, 1, &err);
    CHECK(st == OIT_ERR_FORMAT && strstr(err.message, "part 1: checksum"),
          "deferred part 1 with a flipped byte: status %s, %s", oit_status_name(st), err.message);
    printf("  refused %-34s %s\n", "flipped blob byte, deferred", err.message);
    oit_partfile_close(pf);
}

static void check_corruptions(const char *tmp, const uint8_t *good, size_t size)
{
    corrupt_ctx c = {.good = good, .size = size};
    snprintf(c.path, sizeof c.path, "%s/partfile_corrupt.oitp", tmp);
    uint8_t *b = malloc(size);
    corrupt_truncations(&c);
    corrupt_flips(&c, b);
    corrupt_semantics(&c, b);
    corrupt_blob_bounds(&c, b);
    corrupt_streams(&c, b);
    corrupt_deferred(&c, b);
    free(b);
    printf("  %d corrupt files refused\n", c.cases);
    remove(c.path);
}

/* ---- oitprep info ------------------------------------------------------------- */

static int run_tool(const char *args, const char *out, char *text, size_t cap)
{
    const char *bin = getenv("OIT_BIN");
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "\"%s/oitprep\" %s > \"%s\" 2>&1", bin ? bin : ".", args, out);
    int rc = system(cmd);
    FILE *f = fopen(out, "rb");
    size_t n = f ? fread(text, 1, cap - 1, f) : 0;
    text[n] = 0;
    if (f)
        fclose(f);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static void check_tool(const char *tmp, const char *good, const uint8_t *bytes, size_t size)
{
    char out[600], args[1200], text[8192];
    snprintf(out, sizeof out, "%s/partfile_info.txt", tmp);
    snprintf(args, sizeof args, "info \"%s\"", good);
    int rc = run_tool(args, out, text, sizeof text);
    printf("  oitprep info: exit %d\n%s", rc, text);
    CHECK(rc == 0 && strstr(text, "parts      4") && strstr(text, "triangles  138956"),
          "oitprep info: exit %d", rc);
    snprintf(args, sizeof args, "info --json \"%s\"", good);
    rc = run_tool(args, out, text, sizeof text);
    printf("  oitprep info --json: exit %d\n  %s", rc, text);
    static const char *keys[] = {"\"triangles\": 138956", "\"parts\": 4", "\"pieces\": 5",
                                 "\"slabs\": 2", "\"cells\": 8", "\"subgrid_depth\": 2",
                                 "\"bytes\": ", "\"layer_bound\": 4",
                                 "\"attributes\": [\"color\", \"alpha\"]", "\"version\": 5",
                                 "\"K\": 8"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        CHECK(strstr(text, keys[i]), "--json lacks %s", keys[i]);
    CHECK(rc == 0 && text[0] == '{' && strchr(text, '}'), "--json: exit %d", rc);
    char bad[600];
    snprintf(bad, sizeof bad, "%s/partfile_bad.oitp", tmp);
    spill(bad, bytes, size / 2);
    snprintf(args, sizeof args, "info \"%s\"", bad);
    rc = run_tool(args, out, text, sizeof text);
    printf("  oitprep info on a truncated file: exit %d: %s", rc, text);
    CHECK(rc == 3 && strstr(text, bad), "bad file: exit %d", rc);
    rc = run_tool("info", out, text, sizeof text);
    CHECK(rc == 2, "no FILE: exit %d", rc);
    /* Conversion itself is tested in tests/prepare/convert/; here only that a
     * missing input is an I/O failure that names the file. */
    rc = run_tool("no-such-model.ply -o x.oitp", out, text, sizeof text);
    CHECK(rc == 1 && strstr(text, "no-such-model.ply"), "conversion of a missing file: exit %d",
          rc);
    remove(bad);
    remove(out);
}

/* ---- the rest ------------------------------------------------------------------ */

static void check_crc(void)
{
    const char *v = "123456789";
    CHECK(oit_crc32c(0, v, 9) == 0xE3069283u && oit_crc32c_portable(0, v, 9) == 0xE3069283u,
          "CRC-32C check value");
    uint8_t buf[1000];
    for (int i = 0; i < 1000; i++)
        buf[i] = (uint8_t)(i * 131 + 7);
    for (size_t n = 0; n < 1000; n += 37)
        CHECK(oit_crc32c(oit_crc32c(0, buf, n / 3), buf + n / 3, n - n / 3) ==
                  oit_crc32c_portable(0, buf, n),
              "CRC-32C paths differ at %zu bytes", n);
}

static void check_deferred(const char *path, const scene *s)
{
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_partfile_open_desc od = {.defer_part_data = true};
    CHECK(oit_partfile_open(path, &od, &pf, &err) == OIT_OK, "%s", err.message);
    if (!pf)
        return;
    oit_partfile_part_view v;
    oit_partfile_buffer buf = {0};
    CHECK(oit_partfile_part_data(pf, 2, &buf, &v, &err) == OIT_ERR_ARGUMENT,
          "deferred: part data before validation");
    oit_partfile_buffer_free(&buf);
    CHECK(oit_partfile_validate_part(pf, 2, &err) == OIT_OK, "%s", err.message);
    check_part_bytes(pf, 2, &s->parts[2]);
    CHECK(oit_partfile_validate_part(pf, 4, &err) == OIT_ERR_ARGUMENT, "part 4 of 4");
    oit_partfile_close(pf);
}

/* A writer given a cell that names a missing part must not leave a file. */
static void check_writer_refuses(const char *tmp)
{
    scene s;
    small_scene(&s);
    s.grids[0].parts[1] = 5;
    char path[600], tmp_path[700];
    snprintf(path, sizeof path, "%s/partfile_refused.oitp", tmp);
    snprintf(tmp_path, sizeof tmp_path, "%s.tmp", path);
    remove(path);
    oit_error err = {0};
    oit_status st = write_scene(&s, path, 8, &err);
    printf("  writer refuses a bad cell list: %s\n", err.message);
    CHECK(st == OIT_ERR_ARGUMENT && strstr(err.message, "part 5"), "status %s",
          oit_status_name(st));
    CHECK(access(path, F_OK) != 0 && access(tmp_path, F_OK) != 0, "a file was left behind");
    scene_free(&s);
}

/* A file of an older version (small-v1.oitp: version 1, written before
 * META held the origin) has no source indices: it is refused, the message
 * naming the file and telling the user to convert the model again. */
static void check_version1(const char *corpus)
{
    char path[600];
    snprintf(path, sizeof path, "%s/small-v1.oitp", corpus);
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_status st = oit_partfile_open(path, NULL, &pf, &err);
    printf("  version 1 file: %s\n", err.message);
    CHECK(st == OIT_ERR_FORMAT && !pf && strstr(err.message, "small-v1.oitp") &&
              strstr(err.message, "version 1") && strstr(err.message, "convert the model again"),
          "version 1 file: status %s, %s", oit_status_name(st), err.message);
    oit_partfile_close(pf);
}

static void check_small(const char *tmp, const char *corpus, int write_corpus)
{
    scene s;
    small_scene(&s);
    char path[600], golden[600];
    size_t n = 0, gn = 0;
    uint8_t *b = write_and_read(&s, tmp, "partfile_small.oitp", 8, path, &n);
    snprintf(golden, sizeof golden, "%s/small.oitp", corpus);
    if (write_corpus && b)
        CHECK(spill(golden, b, n) == 0, "cannot write %s", golden);
    uint8_t *g = test_read_file(golden, &gn);
    printf("  small scene: %zu bytes, %s %s\n", n, golden,
           g && gn == n && !memcmp(b, g, n) ? "identical" : "DIFFERENT");
    CHECK(g && gn == n && !memcmp(b, g, n),
          "%s differs from the fuzz seed %s (rerun with --write-corpus after a format change)",
          path, golden);
    oit_partfile *pf = NULL;
    oit_error err = {0};
    CHECK(oit_partfile_open_memory(b, n, "small", NULL, &pf, &err) == OIT_OK, "%s", err.message);
    if (pf)
        check_round_trip(pf, &s, n);
    oit_partfile_close(pf);
    free(b);
    free(g);
    scene_free(&s);
    check_version1(corpus);
}

int main(int argc, char **argv)
{
    const char *tmp = getenv("OIT_TEST_TMP") ? getenv("OIT_TEST_TMP") : "/tmp";
    const char *corpus = argc > 1 ? argv[1] : "tests/corpus/partfile";
    check_crc();
    check_small(tmp, corpus, argc > 2 && !strcmp(argv[2], "--write-corpus"));

    scene s;
    big_scene(&s);
    char a[600], b[600];
    size_t na = 0, nb = 0;
    uint8_t *ba = write_and_read(&s, tmp, "partfile_a.oitp", 0, a, &na);
    uint8_t *bb = write_and_read(&s, tmp, "partfile_b.oitp", 0, b, &nb);
    printf("  big scene: %zu and %zu bytes, %s\n", na, nb,
           na == nb && ba && bb && !memcmp(ba, bb, na) ? "byte-identical" : "DIFFERENT");
    CHECK(ba && bb && na == nb && na > 0 && !memcmp(ba, bb, na), "two writes differ");
    oit_partfile *pf = NULL;
    oit_error err = {0};
    CHECK(oit_partfile_open(a, NULL, &pf, &err) == OIT_OK, "%s", err.message);
    if (pf) {
        check_round_trip(pf, &s, na);
        /* Dropped pages of the mapping fault back in: every part reads the
         * same afterwards; parts out of range are ignored. */
        oit_partfile_drop_part_data(pf, 0, UINT32_MAX);
        oit_partfile_drop_part_data(pf, UINT32_MAX, 5);
        check_round_trip(pf, &s, na);
    }
    oit_partfile_close(pf);
    check_deferred(a, &s);
    check_cache_order(tmp, &s);
    if (ba)
        check_corruptions(tmp, ba, na);
    check_tool(tmp, a, ba, na);
    check_writer_refuses(tmp);
    remove(a);
    remove(b);
    free(ba);
    free(bb);
    scene_free(&s);
    return test_verdict();
}
