/* partfile/part_blob.c and validate_parts.c: a piece's bounds against its
 * triangles, as a property over random files and random corruptions of them.
 *
 * Each round writes a random part file with the writer (1-4 parts of 1-4
 * pieces, random vertices, some unused and some signed zeros, each piece's
 * triangles mostly drawn from its own window of vertices so that piece
 * boxes differ, colour on some parts, the vertex-cache order on some
 * files) and asserts:
 *   - the file opens, and its pieces' bounds are the min/max of their own
 *     triangles' vertices (computed here, bit for bit);
 *   - each corruption below, every checksum resealed, is refused with
 *     OIT_ERR_FORMAT and a message naming the piece's record ("PIECES:
 *     record J"), both by a full open and, with deferred part data, by the
 *     open or by validating that part:
 *       shrink  one bound of one piece moved inward by one ulp (still inside
 *               its part: only the triangles can tell);
 *       grow    one bound moved outward by one ulp where that stays inside
 *               the part's box;
 *       swap    two pieces of a part with different boxes trade bounds;
 *       part    a piece's bounds replaced by its part's (a superset);
 *       index   one index of a piece's triangle re-pointed (streams
 *               re-encoded) at a vertex of the part outside the piece's box:
 *               the part's own bounds and every other check still hold;
 *       outside a piece's bound moved one ulp beyond its part's box: refused
 *               already by a deferred open, which reads no triangle.
 * The counts of each kind are printed and each must be > 0, so the
 * generator cannot drift into files where a kind never applies. */
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "partfile/write.h"

#include "partfile/layout.h"
#include "tests/lib/test_rng.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"
#include "tests/partfile/partfile_reencode.h"
#include "tests/partfile/partfile_reseal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_PARTS = 4, MAX_PIECES = 4, MAX_V = 300, MAX_T = 4 * 24, ROUNDS = 48 };

typedef struct part_in {
    float pos[MAX_V * 3];
    uint8_t rgba[MAX_V * 4];
    uint32_t nv, idx[MAX_T * 3], src[MAX_T];
    uint64_t ni;
    oit_partfile_piece_desc pieces[MAX_PIECES];
    uint32_t np;
    int colour;
} part_in;

/* A coordinate: mostly random in [c - 4, c + 4], now and then a signed zero
 * or a repeat of the last one (ties in the min/max). */
static float coordinate(rng *r, float c, float last)
{
    switch (rnd(r, 16)) {
    case 0:
        return 0.0f;
    case 1:
        return -0.0f;
    case 2:
        return last;
    default:
        return c + ((float)rnd(r, 1u << 20) / (float)(1u << 17) - 4.0f);
    }
}

static void random_part(rng *r, part_in *p, uint32_t first_source)
{
    memset(p, 0, sizeof *p);
    p->nv = 3 + rnd(r, MAX_V - 3);
    p->np = 1 + rnd(r, MAX_PIECES);
    p->colour = rnd(r, 2);
    float c[3] = {(float)rnd(r, 40) - 20.0f, (float)rnd(r, 40) - 20.0f, (float)rnd(r, 40) - 20.0f};
    for (uint32_t i = 0; i < p->nv * 3; i++)
        p->pos[i] = coordinate(r, c[i % 3], i >= 3 ? p->pos[i - 3] : 0.0f);
    for (uint32_t i = 0; i < p->nv * 4; i++)
        p->rgba[i] = (uint8_t)rnd(r, 256);
    for (uint32_t k = 0; k < p->np; k++) {
        /* the piece's window of vertices; one index in 8 from anywhere */
        uint32_t a = rnd(r, p->nv), len = 1 + rnd(r, p->nv - a);
        uint32_t n = 1 + rnd(r, 24);
        for (uint32_t t = 0; t < 3 * n; t++)
            p->idx[p->ni + t] = rnd(r, 8) ? a + rnd(r, len) : rnd(r, p->nv);
        for (uint32_t t = 0; t < n; t++)
            p->src[p->ni / 3 + t] = first_source + (uint32_t)p->ni / 3 + t;
        p->ni += 3 * n;
        p->pieces[k] = (oit_partfile_piece_desc){n, 1};
    }
}

/* The scene's parts, all listed by the one cell of a 1x1x1 grid. */
static oit_status write_file(const char *path, const part_in *parts, uint32_t n,
                             oit_partfile_order order, oit_error *err)
{
    oit_partfile_writer_desc wd = {.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA,
                                   .part_align = 64, .order = order};
    oit_partfile_writer *w = NULL;
    oit_status s = oit_partfile_writer_create(path, &wd, &w, err);
    if (s)
        return s;
    uint32_t list[MAX_PARTS];
    for (uint32_t i = 0; !s && i < n; i++) {
        const part_in *p = &parts[i];
        oit_partfile_part_desc d = {.positions = p->pos, .rgba = p->colour ? p->rgba : NULL,
                                    .vertex_count = p->nv, .indices = p->idx,
                                    .index_count = p->ni, .sources = p->src,
                                    .pieces = p->pieces, .piece_count = p->np};
        s = oit_partfile_writer_add_part(w, &d, &list[i], err);
    }
    uint32_t count = n;
    oit_partfile_grid_desc g = {{1, 1, 1}, {-100, -100, -100}, {200, 200, 200},
                                OIT_PARTFILE_NONE, OIT_PARTFILE_NONE, &count, list};
    if (!s)
        s = oit_partfile_writer_set_grid(w, &g, err);
    if (s) {
        oit_partfile_writer_abort(w);
        return s;
    }
    oit_partfile_stats st = {.triangles_in = MAX_PARTS * MAX_T};
    return oit_partfile_writer_finish(w, &st, err);
}

/* ---- the file's records, in its bytes ------------------------------------- */

static pf_section section(const uint8_t *b, uint32_t type)
{
    pf_section s;
    memcpy(&s, b + PF_HEADER_BYTES + (type - 1) * PF_ENTRY_BYTES, sizeof s);
    return s;
}

static size_t piece_at(const uint8_t *b, uint32_t j)
{
    return section(b, PF_SEC_PIECES).offset + (size_t)j * sizeof(oit_partfile_piece);
}

static oit_partfile_piece get_piece(const uint8_t *b, uint32_t j)
{
    oit_partfile_piece pc;
    memcpy(&pc, b + piece_at(b, j), sizeof pc);
    return pc;
}

static void put_piece(uint8_t *b, uint32_t j, const oit_partfile_piece *pc)
{
    memcpy(b + piece_at(b, j), pc, sizeof *pc);
}

/* ---- refusals --------------------------------------------------------------- */

typedef struct tally {
    unsigned long kinds[6], files;
} tally;

enum { K_SHRINK, K_GROW, K_SWAP, K_PART, K_INDEX, K_OUTSIDE };
static const char *const kind_name[6] = {"shrink", "grow", "swap", "part", "index", "outside"};

/* b (n bytes) must be refused, naming piece record j of part `part`: by a
 * full open, and by a deferred open (when at_open) or else by validating
 * the part after it. */
static void expect_refused(const uint8_t *b, size_t n, uint32_t part, uint32_t j, int at_open,
                           const char *what)
{
    char needle[64];
    snprintf(needle, sizeof needle, "PIECES: record %u", j);
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_status s = oit_partfile_open_memory(b, n, "corrupt.oitp", NULL, &pf, &err);
    CHECK(s == OIT_ERR_FORMAT && !pf && strstr(err.message, needle),
          "%s: open: status %s, want a refusal naming '%s': %s", what, oit_status_name(s),
          needle, err.message);
    oit_partfile_close(pf);
    pf = NULL;
    oit_partfile_open_desc od = {.defer_part_data = true};
    err = (oit_error){0};
    s = oit_partfile_open_memory(b, n, "corrupt.oitp", &od, &pf, &err);
    if (at_open) {
        CHECK(s == OIT_ERR_FORMAT && strstr(err.message, needle),
              "%s: deferred open: status %s, want a refusal naming '%s': %s", what,
              oit_status_name(s), needle, err.message);
    } else if (s != OIT_OK) {
        CHECK(0, "%s: deferred open refused a file only its triangles can fault: %s", what,
              err.message);
    } else {
        s = oit_partfile_validate_part(pf, part, &err);
        CHECK(s == OIT_ERR_FORMAT && strstr(err.message, needle),
              "%s: deferred validation of part %u: status %s, want '%s': %s", what, part,
              oit_status_name(s), needle, err.message);
    }
    oit_partfile_close(pf);
}

/* Piece record j with one bound (side 0 min, 1 max, axis a) set to v. */
static void corrupt_bound(const uint8_t *good, size_t n, uint8_t *b, uint32_t j, int side, int a,
                          float v, const char *what, int at_open)
{
    memcpy(b, good, n);
    oit_partfile_piece pc = get_piece(b, j);
    (side ? pc.bounds_max : pc.bounds_min)[a] = v;
    put_piece(b, j, &pc);
    reseal(b, n);
    expect_refused(b, n, pc.part, j, at_open, what);
}

static int same_box(const oit_partfile_piece *x, const oit_partfile_piece *y)
{
    return !memcmp(x->bounds_min, y->bounds_min, 12) && !memcmp(x->bounds_max, y->bounds_max, 12);
}

/* Bounds edits of piece j of part p (record pr). */
static void corrupt_bounds(tally *t, rng *r, const uint8_t *good, size_t n, uint8_t *b,
                           const oit_partfile_part *pr, uint32_t j)
{
    oit_partfile_piece pc = get_piece(good, j);
    int side = rnd(r, 2), a = rnd(r, 3);
    float v = (side ? pc.bounds_max : pc.bounds_min)[a];
    float in = side ? pc.bounds_min[a] : pc.bounds_max[a]; /* toward the other side */
    float out = side ? INFINITY : -INFINITY;
    float part_edge = (side ? pr->bounds_max : pr->bounds_min)[a];
    char what[96];
    if (v != in) {
        snprintf(what, sizeof what, "piece %u %s[%d] one ulp in", j, side ? "max" : "min", a);
        corrupt_bound(good, n, b, j, side, a, nextafterf(v, in), what, 0);
        t->kinds[K_SHRINK]++;
    }
    if (v != part_edge) {
        snprintf(what, sizeof what, "piece %u %s[%d] one ulp out", j, side ? "max" : "min", a);
        corrupt_bound(good, n, b, j, side, a, nextafterf(v, out), what, 0);
        t->kinds[K_GROW]++;
    }
    snprintf(what, sizeof what, "piece %u %s[%d] one ulp beyond its part", j,
             side ? "max" : "min", a);
    corrupt_bound(good, n, b, j, side, a, nextafterf(part_edge, out), what, 1);
    t->kinds[K_OUTSIDE]++;
    oit_partfile_piece whole = pc;
    memcpy(whole.bounds_min, pr->bounds_min, 12);
    memcpy(whole.bounds_max, pr->bounds_max, 12);
    if (!same_box(&whole, &pc)) {
        memcpy(b, good, n);
        put_piece(b, j, &whole);
        reseal(b, n);
        snprintf(what, sizeof what, "piece %u with its part's bounds", j);
        expect_refused(b, n, pc.part, j, 0, what);
        t->kinds[K_PART]++;
    }
    if (j + 1 < pr->piece_first + pr->piece_count) {
        oit_partfile_piece next = get_piece(good, j + 1);
        if (!same_box(&next, &pc)) {
            memcpy(b, good, n);
            oit_partfile_piece x = pc, y = next;
            memcpy(x.bounds_min, next.bounds_min, 12);
            memcpy(x.bounds_max, next.bounds_max, 12);
            memcpy(y.bounds_min, pc.bounds_min, 12);
            memcpy(y.bounds_max, pc.bounds_max, 12);
            put_piece(b, j, &x);
            put_piece(b, j + 1, &y);
            reseal(b, n);
            snprintf(what, sizeof what, "pieces %u and %u swap bounds", j, j + 1);
            expect_refused(b, n, pc.part, j, 0, what);
            t->kinds[K_SWAP]++;
        }
    }
}

static int outside_box(const float *v, const oit_partfile_piece *pc)
{
    for (int a = 0; a < 3; a++)
        if (v[a] < pc->bounds_min[a] || v[a] > pc->bounds_max[a])
            return 1;
    return 0;
}

/* One index of a triangle of piece j re-pointed at a vertex outside the
 * piece's box, the part's streams re-encoded. */
static void corrupt_index(tally *t, rng *r, const uint8_t *good, size_t n, uint32_t part,
                          const oit_partfile_part *pr, uint32_t j)
{
    oit_partfile_piece pc = get_piece(good, j);
    decoded_part d = {0};
    CHECK(decode_part(good, part, &d) == 0, "part %u of a good file does not decode", part);
    uint32_t stride = pf_vertex_stride(pr->attributes) / 4, start = rnd(r, pr->vertex_count);
    uint32_t v = UINT32_MAX;
    for (uint32_t k = 0; k < pr->vertex_count && v == UINT32_MAX; k++) {
        uint32_t c = (start + k) % pr->vertex_count;
        if (outside_box((const float *)(const void *)d.vertices + (size_t)c * stride, &pc))
            v = c;
    }
    if (v != UINT32_MAX) {
        uint64_t i = 3 * (pc.triangle_first + rnd(r, (uint32_t)pc.triangle_count)) + rnd(r, 3);
        d.indices[i] = v;
        size_t m = 0;
        uint8_t *b = reencode_part(good, n, part, &d, &m);
        CHECK(b != NULL, "part %u: cannot re-encode", part);
        char what[96];
        snprintf(what, sizeof what, "piece %u: index %llu -> vertex %u outside its box", j,
                 (unsigned long long)i, v);
        if (b)
            expect_refused(b, m, part, j, 0, what);
        free(b);
        t->kinds[K_INDEX]++;
    }
    decoded_part_free(&d);
}

/* ---- the good file ----------------------------------------------------------- */

/* The pieces' bounds are their triangles' (the writer's data, not the
 * reader's), compared bit for bit; signed zeros count as the writer's first. */
static void check_good(const uint8_t *b, size_t n, const part_in *parts, uint32_t np,
                       oit_partfile_order order)
{
    oit_partfile *pf = NULL;
    oit_error err = {0};
    CHECK(oit_partfile_open_memory(b, n, "good.oitp", NULL, &pf, &err) == OIT_OK,
          "a good file is refused: %s", err.message);
    oit_partfile_close(pf);
    if (order != OIT_PARTFILE_ORDER_KEEP)
        return; /* triangles reordered within pieces: the order of ties moves */
    uint32_t j = 0;
    for (uint32_t i = 0; i < np; i++) {
        const part_in *p = &parts[i];
        uint64_t t0 = 0;
        for (uint32_t k = 0; k < p->np; k++, j++) {
            float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            for (uint64_t x = 3 * t0; x < 3 * (t0 + p->pieces[k].triangle_count); x++)
                for (int a = 0; a < 3; a++) {
                    float v = p->pos[3 * p->idx[x] + a];
                    lo[a] = v < lo[a] ? v : lo[a];
                    hi[a] = v > hi[a] ? v : hi[a];
                }
            t0 += p->pieces[k].triangle_count;
            oit_partfile_piece pc = get_piece(b, j);
            CHECK(!memcmp(lo, pc.bounds_min, 12) && !memcmp(hi, pc.bounds_max, 12),
                  "part %u piece %u: stored bounds are not its triangles'", i, k);
        }
    }
}

int main(void)
{
    char path[600];
    test_tmp_path(path, sizeof path, "piece_bounds.oitp");
    static part_in parts[MAX_PARTS];
    rng r = {20240917u};
    tally t = {{0}, 0};
    for (int round = 0; round < ROUNDS; round++) {
        uint32_t np = 1 + rnd(&r, MAX_PARTS);
        for (uint32_t i = 0; i < np; i++)
            random_part(&r, &parts[i], i * MAX_T);
        oit_partfile_order order = round % 4 == 3 ? OIT_PARTFILE_ORDER_CACHE
                                                  : OIT_PARTFILE_ORDER_KEEP;
        oit_error err = {0};
        if (write_file(path, parts, np, order, &err) != OIT_OK) {
            CHECK(0, "round %d: the writer failed: %s", round, err.message);
            continue;
        }
        size_t n = 0;
        uint8_t *good = test_read_file(path, &n), *b = good ? malloc(n) : NULL;
        CHECK(good && b, "round %d: cannot read %s", round, path);
        if (good && b) {
            check_good(good, n, parts, np, order);
            pf_section ps = section(good, PF_SEC_PARTS);
            for (uint32_t i = 0; i < np; i++) {
                oit_partfile_part pr;
                memcpy(&pr, good + ps.offset + (size_t)i * sizeof pr, sizeof pr);
                for (uint32_t j = pr.piece_first; j < pr.piece_first + pr.piece_count; j++) {
                    corrupt_bounds(&t, &r, good, n, b, &pr, j);
                    corrupt_index(&t, &r, good, n, i, &pr, j);
                }
            }
            t.files++;
        }
        free(good);
        free(b);
    }
    remove(path);
    printf("%lu random files; corruptions refused:", t.files);
    for (int k = 0; k < 6; k++)
        printf(" %s %lu%s", kind_name[k], t.kinds[k], k < 5 ? "," : "\n");
    for (int k = 0; k < 6; k++)
        CHECK(t.kinds[k] > 0, "no '%s' corruption applied: the generator misses a case",
              kind_name[k]);
    return test_verdict();
}
