/* Integration of the oitgen tool: every scene at a small size gives a valid
 * PLY with the counts it declares (parsed here independently, and through
 * oit_read_ply), closed outward-wound solids of one colour each, the
 * triangle budget it was asked for, identical bytes for identical arguments
 * and different bytes for another seed; --help, usage errors and a missing
 * input give the documented exit codes and messages.
 *
 * Also, for large outputs measured by hand: `test_oitgen --depth FILE.ply
 * [AZ EL]` prints the depth complexity (surfaces per pixel) of an
 * orthographic 512x512 view, `test_oitgen --check FILE.ply` the solid
 * checks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include <fcntl.h>

#include "oit/mesh.h"
#include "tests/lib/scene_ply_check.h"
#include "tests/lib/test_check.h"

#define PROBE_PI 3.14159265358979323846


static char bin[512], tmp[512];

typedef struct run_result {
    int code;
    char out[4096], err[4096];
} run_result;

static void slurp(const char *path, char *buf, size_t n)
{
    FILE *f = fopen(path, "r");
    size_t k = f ? fread(buf, 1, n - 1, f) : 0;
    buf[k] = 0;
    if (f)
        fclose(f);
}

/* Runs oitgen with the NULL-terminated arguments; captures its output. */
static run_result run(const char *const *args)
{
    run_result r = {.code = -1};
    char out[600], err[600], exe[600];
    snprintf(out, sizeof out, "%s/oitgen.stdout", tmp);
    snprintf(err, sizeof err, "%s/oitgen.stderr", tmp);
    snprintf(exe, sizeof exe, "%s/oitgen", bin);
    const char *argv[32] = {exe};
    for (int i = 0; args[i] && i < 30; i++)
        argv[i + 1] = args[i];
    pid_t pid = fork();
    if (pid == 0) {
        int fo = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644), fe = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fo, 1);
        dup2(fe, 2);
        execv(exe, (char *const *)argv);
        _exit(127);
    }
    int st;
    if (pid > 0 && waitpid(pid, &st, 0) == pid && WIFEXITED(st))
        r.code = WEXITSTATUS(st);
    slurp(out, r.out, sizeof r.out);
    slurp(err, r.err, sizeof r.err);
    return r;
}

static char *tmp_path(const char *name)
{
    static char paths[8][600];
    static int next;
    char *p = paths[next++ % 8];
    snprintf(p, 600, "%s/%s", tmp, name);
    return p;
}

static int same_bytes(const char *a, const char *b)
{
    size_t na, nb;
    uint8_t *x = test_read_file(a, &na), *y = test_read_file(b, &nb);
    int same = x && y && na == nb && !memcmp(x, y, na);
    free(x);
    free(y);
    return same;
}

/* Generates, checks the summary line against the file, loads it. */
static int generate(const char *const *args, const char *path, test_ply *p)
{
    run_result r = run(args);
    CHECK(r.code == 0, "oitgen %s: exit %d: %s", args[0], r.code, r.err);
    unsigned long long t = 0, v = 0, b = 0;
    double s = -1;
    CHECK(sscanf(r.out, "triangles %llu vertices %llu bytes %llu seconds %lf", &t, &v, &b, &s) == 4,
          "summary line '%s'", r.out);
    if (test_ply_load(p, path)) {
        CHECK(0, "%s", p->why);
        return 1;
    }
    CHECK(t == p->faces && v == p->vertices && b == p->file_bytes && s >= 0,
          "summary says %llu/%llu/%llu, file has %zu/%zu/%zu", t, v, b, p->faces, p->vertices, p->file_bytes);
    return 0;
}

/* Closed, outward, one colour per solid; returns the solid count. */
static size_t check_solids(const char *what, const test_ply *p)
{
    size_t open = test_ply_open_edges(p), comps, inverted, multi;
    test_ply_components(p, &comps, &inverted, &multi);
    printf("%s: %zu triangles, %zu vertices, %zu bytes, %zu solids, %zu bad edges, %zu inside out, "
           "%zu off-colour vertices\n", what, p->faces, p->vertices, p->file_bytes, comps, open, inverted, multi);
    CHECK(open == 0 && inverted == 0 && multi == 0, "%s: %zu open edges, %zu inverted, %zu off colour",
          what, open, inverted, multi);
    return comps;
}

static oit_status count_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    *(uint64_t *)user += n;
    return OIT_OK;
}

/* The project's reader must see the same triangles, colour and alpha. */
static void check_with_reader(const char *path, const test_ply *p)
{
    uint64_t n = 0;
    oit_mesh_info info;
    oit_error err = {0};
    oit_status s = oit_read_ply(path, NULL, count_sink, &n, &info, &err);
    CHECK(s == OIT_OK, "oit_read_ply %s: %s", path, err.message);
    CHECK(n == p->faces && info.triangles == p->faces, "oit_read_ply: %llu triangles, file has %zu",
          (unsigned long long)n, p->faces);
    CHECK((info.attributes & (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA)) == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA),
          "oit_read_ply: attributes %u lack colour or alpha", info.attributes);
}

static void test_cli(void)
{
    run_result r = run((const char *[]){"--help", NULL});
    CHECK(r.code == 0, "--help exit %d", r.code);
    const char *words[] = {"quads", "instances", "plant", "demo", "--count", "--coverage",
                           "--triangles", "--input", "--seed", "-o", "--clashes"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        CHECK(strstr(r.out, words[i]), "--help does not mention %s", words[i]);
    const char *const bad[][8] = {
        {"plant", "--bogus", "3", "-o", "x.ply", NULL},
        {"quads", "--coverage", "1.5", "-o", "x.ply", NULL},
        {"quads", "--count", "12abc", "-o", "x.ply", NULL},
        {"nosuchscene", "-o", "x.ply", NULL},
        {"demo", NULL},
        {"quads", "--triangles", "20000", "-o", "x.ply", NULL},
        {"plant", "--triangles", "5", "-o", "x.ply", NULL},
        {"instances", "-o", "x.ply", NULL},
        {"plant", "--clashes", "sometimes", "-o", "x.ply", NULL},
        {"quads", "--clashes", "allow", "-o", "x.ply", NULL},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        r = run(bad[i]);
        CHECK(r.code == 2 && r.err[0], "oitgen %s %s: exit %d, stderr '%s' (want 2 and a message)",
              bad[i][0], bad[i][1] ? bad[i][1] : "", r.code, r.err);
    }
    const char *missing = tmp_path("no-such-mesh.ply"), *out = tmp_path("never.ply");
    r = run((const char *[]){"instances", "--input", missing, "-o", out, NULL});
    printf("missing input: exit %d: %s", r.code, r.err);
    CHECK((r.code == 1 || r.code == 3) && strstr(r.err, "no-such-mesh.ply"),
          "missing input: exit %d, stderr '%s'", r.code, r.err);
    char t1[700];
    snprintf(t1, sizeof t1, "%s.tmp", out);
    CHECK(access(out, F_OK) != 0 && access(t1, F_OK) != 0, "a failed run left %s or its .tmp", out);
}

static void test_quads(void)
{
    const char *path = tmp_path("quads.ply");
    enum { N = 50 };
    test_ply p;
    if (generate((const char *[]){"quads", "--count", "50", "--coverage", "0.3", "-o", path, NULL}, path, &p))
        return;
    CHECK(p.faces == 2 * N && p.vertices == 4 * N, "quads: %zu faces %zu vertices", p.faces, p.vertices);
    /* Every quad must face +Z, cover 0.3 of the square, contain the centre
     * and sit at its own depth. */
    float z[N];
    int covering = 0, facing = 0, area_ok = 0, distinct = 1;
    for (int q = 0; q < N && p.vertices == 4 * N; q++) {
        const float *v = p.xyz + 12 * q;
        float x0 = v[0], y0 = v[1], x1 = v[6], y1 = v[7];
        z[q] = v[2];
        covering += x0 < 0 && 0 < x1 && y0 < 0 && 0 < y1 && x0 >= -1 && x1 <= 1 && y0 >= -1 && y1 <= 1;
        area_ok += fabsf((x1 - x0) * (y1 - y0) - 0.3f * 4) < 1e-4f;
        for (int f = 0; f < 2; f++) {
            const uint32_t *t = p.idx + 3 * (2 * q + f);
            const float *a = p.xyz + 3 * t[0], *b = p.xyz + 3 * t[1], *c = p.xyz + 3 * t[2];
            facing += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0;
        }
        for (int k = 0; k < q; k++)
            distinct &= z[k] != z[q];
    }
    printf("quads: %d of %d cover the centre, %d of %d triangles face +Z, %d of %d have area 1.2, "
           "depths distinct %d\n", covering, N, facing, 2 * N, area_ok, N, distinct);
    CHECK(covering == N && facing == 2 * N && area_ok == N && distinct, "quads geometry wrong");
    check_with_reader(path, &p);
    test_ply_free(&p);
}

static void test_demo(const char *path)
{
    test_ply p;
    if (generate((const char *[]){"demo", "-o", path, NULL}, path, &p))
        return;
    size_t solids = check_solids("demo", &p);
    CHECK(p.faces > 90000 && p.faces < 110000, "demo: %zu triangles, want about 100K", p.faces);
    CHECK(solids == 7, "demo: %zu solids, want 3 rings + 3 spheres + 1 band", solids);
    check_with_reader(path, &p);
    test_ply_free(&p);
}

static void test_instances(const char *mesh, const test_ply *src)
{
    const char *path = tmp_path("instances.ply");
    test_ply p;
    if (generate((const char *[]){"instances", "--input", mesh, "--count", "3", "-o", path, NULL}, path, &p))
        return;
    size_t solids = check_solids("instances", &p);
    CHECK(p.faces == 3 * src->faces && p.vertices == 3 * src->vertices && solids == 21,
          "instances: %zu faces %zu vertices %zu solids for 3 copies of %zu/%zu", p.faces, p.vertices,
          solids, src->faces, src->vertices);
    /* Copies 1 and 2 are copy 0 moved by 1.1 extents along x, then z. */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < src->vertices; v++)
        for (int k = 0; k < 3; k++)
            lo[k] = fminf(lo[k], src->xyz[3 * v + k]), hi[k] = fmaxf(hi[k], src->xyz[3 * v + k]);
    size_t nv = src->vertices, off = 0;
    for (size_t v = 0; v < nv && p.vertices == 3 * nv; v++) {
        const float *a = p.xyz + 3 * v, *b = p.xyz + 3 * (nv + v), *c = p.xyz + 3 * (2 * nv + v);
        off += fabsf(b[0] - a[0] - 1.1f * (hi[0] - lo[0])) > 1e-3f || b[1] != a[1] || b[2] != a[2];
        off += fabsf(c[2] - a[2] - 1.1f * (hi[2] - lo[2])) > 1e-3f || c[1] != a[1] || c[0] != a[0];
    }
    CHECK(off == 0, "instances: %zu vertices not at their grid offset", off);
    int colours_differ = p.vertices == 3 * nv && memcmp(p.vrgba, p.vrgba + 4 * nv, 4) != 0;
    CHECK(colours_differ, "instances: copies 0 and 1 share a colour");
    test_ply_free(&p);
}

/* Pairs of triangles of different solids whose boxes overlap by more than
 * a tenth of a millimetre on every axis. A clash-free plant has none: each
 * of its objects lies inside boxes kept apart from every other object's
 * (scene_plant.c), and a triangle's box lies inside one of them. Boxes are
 * hashed into cells; a pair counts in the cell holding its overlap's lowest
 * corner only. */
typedef struct cell_entry {
    uint64_t key;
    uint32_t tri;
} cell_entry;

static int cmp_entry(const void *a, const void *b)
{
    const cell_entry *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->tri > y->tri) - (x->tri < y->tri);
}

static size_t plant_clashes(const test_ply *p)
{
    const float cell = 0.25f, tol = 1e-4f;
    size_t n = p->faces, cap = 0, m = 0, clashes = 0;
    float (*lo)[3] = malloc(n * sizeof *lo), (*hi)[3] = malloc(n * sizeof *hi), base[3] = {1e30f, 1e30f, 1e30f};
    uint32_t *solid = malloc(n * sizeof *solid), *parent = malloc((p->vertices + 1) * sizeof *parent);
    cell_entry *e = NULL;
    for (size_t v = 0; v < p->vertices; v++)
        parent[v] = (uint32_t)v;
    for (size_t f = 0; f < n; f++)
        for (int k = 1; k < 3; k++)
            parent[test_find(parent, p->idx[3 * f + k])] = test_find(parent, p->idx[3 * f]);
    for (size_t f = 0; f < n; f++) {
        solid[f] = test_find(parent, p->idx[3 * f]);
        for (int a = 0; a < 3; a++) {
            lo[f][a] = 1e30f, hi[f][a] = -1e30f;
            for (int k = 0; k < 3; k++) {
                float x = p->xyz[3 * p->idx[3 * f + k] + a];
                lo[f][a] = fminf(lo[f][a], x), hi[f][a] = fmaxf(hi[f][a], x);
            }
            base[a] = fminf(base[a], lo[f][a]);
        }
    }
    for (size_t f = 0; f < n; f++) {
        int c0[3], c1[3];
        for (int a = 0; a < 3; a++)
            c0[a] = (int)((lo[f][a] - base[a]) / cell), c1[a] = (int)((hi[f][a] - base[a]) / cell);
        for (int z = c0[2]; z <= c1[2]; z++)
            for (int y = c0[1]; y <= c1[1]; y++)
                for (int x = c0[0]; x <= c1[0]; x++) {
                    if (m == cap)
                        e = realloc(e, (cap = cap ? 2 * cap : 1 << 16) * sizeof *e);
                    e[m++] = (cell_entry){(uint64_t)z << 42 | (uint64_t)y << 21 | (uint64_t)x, (uint32_t)f};
                }
    }
    qsort(e, m, sizeof *e, cmp_entry);
    for (size_t g = 0, h; g < m; g = h) {
        for (h = g; h < m && e[h].key == e[g].key; h++)
            ;
        for (size_t i = g; i < h; i++)
            for (size_t j = i + 1; j < h; j++) {
                uint32_t s = e[i].tri, t = e[j].tri;
                int overlap = solid[s] != solid[t];
                uint64_t key = 0;
                for (int a = 2; a >= 0 && overlap; a--) {
                    float l = fmaxf(lo[s][a], lo[t][a]), u = fminf(hi[s][a], hi[t][a]);
                    overlap = u - l > tol;
                    key = key << 21 | (uint64_t)(int)((l - base[a]) / cell);
                }
                clashes += overlap && key == e[g].key;
            }
    }
    free(lo), free(hi), free(solid), free(parent), free(e);
    return clashes;
}

static void test_plant(void)
{
    const char *a = tmp_path("plant_a.ply"), *b = tmp_path("plant_b.ply"), *c = tmp_path("plant_c.ply");
    static const uint64_t sizes[] = {10000, 60000};
    for (int i = 0; i < 2; i++) {
        char t[32];
        snprintf(t, sizeof t, "%llu", (unsigned long long)sizes[i]);
        test_ply p;
        if (generate((const char *[]){"plant", "--triangles", t, "-o", a, NULL}, a, &p))
            continue;
        char what[64];
        snprintf(what, sizeof what, "plant %s", t);
        size_t solids = check_solids(what, &p);
        double dev = ((double)p.faces - (double)sizes[i]) / (double)sizes[i];
        printf("plant %s: %zu triangles (%+.3f%%), %zu solids\n", t, p.faces, 100 * dev, solids);
        CHECK(fabs(dev) <= 0.10, "plant: %zu triangles for --triangles %s", p.faces, t);
        size_t alpha_out = 0;
        for (size_t v = 0; v < p.vertices; v++)
            alpha_out += p.vrgba[4 * v + 3] < 51 || p.vrgba[4 * v + 3] > 154;
        CHECK(alpha_out == 0, "plant: %zu vertices with alpha outside 0.2..0.6", alpha_out);
        if (i == 1)
            check_with_reader(a, &p);
        size_t clashes = plant_clashes(&p);
        printf("plant %s: %zu clashing triangle pairs\n", t, clashes);
        CHECK(clashes == 0, "plant %s: %zu pairs of triangles of different solids overlap", t, clashes);
        test_ply_free(&p);
    }
    /* The stress case does clash, which shows the check above can fail. */
    test_ply q;
    if (!generate((const char *[]){"plant", "--triangles", "60000", "--clashes", "allow", "-o", a, NULL}, a, &q)) {
        size_t clashes = plant_clashes(&q);
        printf("plant 60000 --clashes allow: %zu clashing triangle pairs\n", clashes);
        CHECK(clashes > 1000, "plant --clashes allow: only %zu clashing pairs", clashes);
        test_ply_free(&q);
    }
    run((const char *[]){"plant", "--triangles", "60000", "--seed", "7", "-o", a, NULL});
    run((const char *[]){"plant", "--seed", "7", "--triangles", "60000", "-o", b, NULL});
    run((const char *[]){"plant", "--triangles", "60000", "--seed", "8", "-o", c, NULL});
    int same = same_bytes(a, b), differ = !same_bytes(a, c);
    printf("plant determinism: same seed identical %d, other seed differs %d\n", same, differ);
    CHECK(same && differ, "plant: same seed identical %d, other seed different %d", same, differ);
    run((const char *[]){"quads", "--seed", "3", "-o", a, NULL});
    run((const char *[]){"quads", "--seed", "3", "-o", b, NULL});
    run((const char *[]){"quads", "--seed", "4", "-o", c, NULL});
    CHECK(same_bytes(a, b) && !same_bytes(a, c), "quads: seed does not determine the bytes");
}

/* Orthographic depth complexity: surfaces covering each pixel centre. */
static int depth_probe(const char *path, float az, float el)
{
    test_ply p;
    if (test_ply_load(&p, path)) {
        fprintf(stderr, "%s\n", p.why);
        return 1;
    }
    enum { RES = 512 };
    float a = az * (float)PROBE_PI / 180, e = el * (float)PROBE_PI / 180;
    float d[3] = {cosf(e) * sinf(a), sinf(e), cosf(e) * cosf(a)}; /* toward the eye */
    float r[3] = {cosf(a), 0, -sinf(a)};
    float u[3] = {d[1] * r[2] - d[2] * r[1], d[2] * r[0] - d[0] * r[2], d[0] * r[1] - d[1] * r[0]};
    float *uv = malloc(sizeof(float) * 2 * (p.vertices + 1));
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t v = 0; v < p.vertices; v++) {
        const float *x = p.xyz + 3 * v;
        uv[2 * v] = x[0] * r[0] + x[1] * r[1] + x[2] * r[2];
        uv[2 * v + 1] = x[0] * u[0] + x[1] * u[1] + x[2] * u[2];
        for (int k = 0; k < 2; k++)
            lo[k] = fminf(lo[k], uv[2 * v + k]), hi[k] = fmaxf(hi[k], uv[2 * v + k]);
    }
    float scale = (RES - 1) / fmaxf(hi[0] - lo[0], hi[1] - lo[1]);
    uint32_t *count = calloc(RES * RES, sizeof *count);
    for (size_t f = 0; f < p.faces; f++) {
        float px[3], py[3];
        for (int k = 0; k < 3; k++) {
            px[k] = (uv[2 * p.idx[3 * f + k]] - lo[0]) * scale;
            py[k] = (uv[2 * p.idx[3 * f + k] + 1] - lo[1]) * scale;
        }
        float area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
        if (area == 0)
            continue;
        int x0 = (int)ceilf(fminf(px[0], fminf(px[1], px[2]))), x1 = (int)floorf(fmaxf(px[0], fmaxf(px[1], px[2])));
        int y0 = (int)ceilf(fminf(py[0], fminf(py[1], py[2]))), y1 = (int)floorf(fmaxf(py[0], fmaxf(py[1], py[2])));
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++) {
                int in = 1;
                for (int k = 0; k < 3; k++) {
                    int j = (k + 1) % 3;
                    float w = (px[j] - px[k]) * (y - py[k]) - (py[j] - py[k]) * (x - px[k]);
                    in &= area > 0 ? w >= 0 : w <= 0;
                }
                count[y * RES + x] += in;
            }
    }
    uint64_t sum = 0, covered = 0, maxc = 0;
    for (int i = 0; i < RES * RES; i++) {
        sum += count[i];
        covered += count[i] > 0;
        maxc = count[i] > maxc ? count[i] : maxc;
    }
    printf("%s: azimuth %.0f elevation %.0f, %dx%d orthographic: max depth complexity %llu, "
           "mean %.1f over %llu covered pixels\n", path, az, el, RES, RES, (unsigned long long)maxc,
           covered ? (double)sum / (double)covered : 0.0, (unsigned long long)covered);
    free(count);
    free(uv);
    test_ply_free(&p);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 3 && !strcmp(argv[1], "--check")) {
        test_ply p;
        if (test_ply_load(&p, argv[2]))
            return fprintf(stderr, "%s\n", p.why), 1;
        check_solids(argv[2], &p);
        test_ply_free(&p);
        return test_failures != 0;
    }
    if (argc >= 3 && !strcmp(argv[1], "--depth"))
        return depth_probe(argv[2], argc > 3 ? strtof(argv[3], NULL) : 30, argc > 4 ? strtof(argv[4], NULL) : 20);
    const char *b = getenv("OIT_BIN"), *t = getenv("OIT_TEST_TMP");
    if (!b) {
        fprintf(stderr, "OIT_BIN is not set (run through ctest)\n");
        return 1;
    }
    snprintf(bin, sizeof bin, "%s", b);
    snprintf(tmp, sizeof tmp, "%s", t ? t : "/tmp");
    test_cli();
    test_quads();
    const char *demo = tmp_path("demo.ply");
    test_demo(demo);
    test_ply src;
    if (!test_ply_load(&src, demo)) {
        test_instances(demo, &src);
        test_ply_free(&src);
    }
    test_plant();
    depth_probe(tmp_path("plant_a.ply"), 30, 20);
    return test_verdict();
}
