/* oit_gpu_mesh_draw_many (view/render/gl/gpu_mesh.h) against oit_gpu_mesh_draw on
 * each mesh in turn: 300 mesh views (some empty, primitive ids not in
 * drawing order) over two GL buffers whose gaps hold garbage, laid out so
 * the groups change: one buffer, runs alternating between the buffers,
 * slots in reverse order under a tiny forced window, meshes larger than that
 * window. Per case:
 *  - every pixel's multiset of packed fragments (count, sum and xor of a
 *    hash of the fragment's four words: depth, prim, colour) is the same;
 *  - at the frame's centre, which every even triangle of every mesh covers
 *    and no odd one does, the prims are exactly first_prim + index of those
 *    triangles, whichever path drew them (so the ids are absolute, not only
 *    equal between the paths);
 *  - the draw calls are the number of groups the layout makes, worked out
 *    by hand below.
 * The layouts run again with sourced views (oit_gpu_mesh_set_range_sourced,
 * as the streamer draws parts): each mesh's prims stored after its
 * triangles, reversed within the mesh, so the centre's prims are those
 * values, not first prim + index.
 * A wrong group base, first vertex or per-draw record shows in the
 * fingerprints; a wrong grouping in the call count.
 *
 * Every draw runs on poisoned GL state, since a driver may do the least GL
 * 4.5 allows where llvmpipe happens to do more: before each path the
 * current value of OIT_IN_DRAW is garbage, OIT_BIND_VERTS and OIT_BIND_PRIMS
 * point at a buffer of NaNs, and the multi-draw's command and record
 * buffers and each view's record buffer (found through GL queries after
 * the first draws) are filled with NaNs. After each draw the current value
 * must be untouched and the bound vertex array must take OIT_IN_DRAW from
 * a buffer with divisor 1 (no draw reads a current value, which GL leaves
 * undefined after an array draw and drivers latch as they please), and
 * OIT_BIND_PRIMS must name the meshes' buffer even for draws that read no
 * prims (an unbacked or stale block is undefined behaviour). The layouts
 * run in two rounds in one process (a second run must find nothing left
 * over by the first), with the driver's SSBO offset alignment and with 256
 * forced on the multi-draw and the views (oit_gpu_draws_set_align,
 * oit_gpu_mesh_set_align), and in shuffled and reversed mesh orders.
 * Finally draws through records that do not fit their bindings (a prim
 * past OIT_BIND_PRIMS, a first vertex past the draw's first, a triangle
 * past OIT_BIND_VERTS) must drop exactly those triangles, not read out of
 * range. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/lib/gl_test_scene.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gpu_draw_record.h"
#include "view/render/gl/gpu_mesh.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 64, H = 64, N = 300, SLOT = 1024, BUF_BYTES = 1 << 20, CENTER = 32 * W + 32 };

static const char fingerprint_fs[] =
    "layout(std430, binding = OIT_BIND_OUT) buffer Acc { uint acc[]; };\n"
    "void main() {\n"
    "    uvec4 f = oit_fragment();\n"
    "    uint h = f.x * 2654435761u ^ f.y * 2246822519u ^ f.z * 3266489917u ^ f.w * 668265263u;\n"
    "    h ^= h >> 15; h *= 2246822519u; h ^= h >> 13;\n"
    "    uint p = oit_pixel_index();\n"
    "    atomicAdd(acc[p * 3u], 1u);\n"
    "    atomicAdd(acc[p * 3u + 1u], h);\n"
    "    atomicXor(acc[p * 3u + 2u], h * 2654435769u + (h >> 7));\n"
    "    if (p == uint(32 * 64 + 32)) {\n" /* CENTER */
    "        uint prim = f.y & 0x7fffffffu;\n"
    "        uint c = uint(3 * 64 * 64);\n"
    "        atomicAdd(acc[c], 1u);\n"
    "        atomicAdd(acc[c + 1u], prim);\n"
    "        atomicXor(acc[c + 2u], prim * 2654435761u);\n"
    "    }\n"
    "}\n";

enum { ACC_WORDS = 3 * W * H + 3 };

typedef struct scene {
    oit_triangle *tris[N];
    size_t count[N];
    uint32_t first_prim[N];
} scene;

/* 1: views are sourced, triangle j of mesh i has prim prim_of(s, i, j). */
static int sourced;

static uint32_t prim_of(const scene *s, int i, size_t j)
{
    return s->first_prim[i] + (uint32_t)(sourced ? s->count[i] - 1 - j : j);
}

static uint32_t rng(uint32_t *r)
{
    *r = *r * 1664525u + 1013904223u;
    return *r >> 8;
}

static float unit(uint32_t *r)
{
    return (float)rng(r) / 16777216.0f;
}

/* Even triangles: around the view axis (they cover the centre pixel);
 * odd ones: small, left of x = -0.3 (they never do). */
static void make_triangle(oit_triangle *t, int even, uint32_t *r)
{
    float z = -2.0f - unit(r), cx = 0.4f * unit(r) - 0.2f, cy = 0.4f * unit(r) - 0.2f;
    float a0 = 6.2831853f * unit(r);
    for (int k = 0; k < 3; k++) {
        float *p = t->v[k].pos;
        if (even) {
            float a = a0 + 2.0943951f * (float)k;
            p[0] = cx + cosf(a);
            p[1] = cy + sinf(a);
        } else {
            p[0] = -2.4f + 1.7f * unit(r);
            p[1] = -2.4f + 4.8f * unit(r);
        }
        p[2] = z + 0.1f * unit(r);
        for (int c = 0; c < 4; c++)
            t->v[k].rgba[c] = (uint8_t)(rng(r) & 255);
        t->v[k].rgba[3] |= 0x10;
    }
}

static int make_scene(scene *s)
{
    uint32_t r = 12345;
    memset(s, 0, sizeof *s);
    for (int i = 0; i < N; i++) {
        s->count[i] = i % 11 == 5 ? 0 : 1 + (size_t)(i * 7) % 19;
        s->first_prim[i] = (uint32_t)(i * 7919) % 100003u;
        s->tris[i] = calloc(s->count[i] + 1, sizeof(oit_triangle));
        if (!s->tris[i])
            return 0;
        for (size_t j = 0; j < s->count[i]; j++)
            make_triangle(&s->tris[i][j], j % 2 == 0, &r);
    }
    return 1;
}

static void free_scene(scene *s)
{
    for (int i = 0; i < N; i++)
        free(s->tris[i]);
}

/* Where each mesh goes: the buffer (0 or 1) and byte offset. */
typedef struct layout {
    int buffer[N];
    uint64_t offset[N];
} layout;

typedef struct gl_state {
    GLuint prog, fbo, acc, buf[2];
    oit_gpu_mesh *views[N];
    oit_gpu_draws *draws;
    GLuint poison;          /* a small buffer of NaNs */
    GLuint scratch[2];      /* the multi-draw's commands and records, once seen */
    GLuint view_records[N]; /* each view's record buffer, once seen */
} gl_state;

/* A quiet NaN's bits, with a payload: garbage as a float and as a uint. */
static const GLuint garbage = 0xffc00001u;
static const GLuint garbage_attr[4] = {0xffc00001u, 0x7fc0beefu, 0xdeadbeefu, 0x7fffffffu};

/* "round r, alignment a, sourced: " before every case name */
static char prefix[96];

static int setup(gl_state *g, oit_error *err)
{
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *fs[] = {oit_glsl_version, oit_glsl_fragment_gen, fingerprint_fs, NULL};
    if (oit_gl_program_graphics("fingerprint", vs, fs, &g->prog, err) != OIT_OK ||
        oit_gpu_draws_create(&g->draws, err) != OIT_OK)
        return 0;
    for (int i = 0; i < N; i++)
        if (oit_gpu_mesh_create_view(0, &g->views[i], err) != OIT_OK)
            return 0;
    glCreateFramebuffers(1, &g->fbo);
    glNamedFramebufferParameteri(g->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, W);
    glNamedFramebufferParameteri(g->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, H);
    glCreateBuffers(1, &g->acc);
    glNamedBufferStorage(g->acc, ACC_WORDS * 4, NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateBuffers(2, g->buf);
    for (int b = 0; b < 2; b++)
        glNamedBufferStorage(g->buf[b], BUF_BYTES, NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateBuffers(1, &g->poison);
    glNamedBufferStorage(g->poison, 64, NULL, GL_DYNAMIC_STORAGE_BIT);
    glClearNamedBufferData(g->poison, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &garbage);
    oit_view v;
    scene_view(&v, W, H, OIT_SHADING_TRANSPARENT);
    oit_shading_resolve_defaults(&v.shading);
    oit_glsl_set_view(g->prog, &v);
    return oit_gl_check("test set-up", err) == OIT_OK;
}

static void teardown(gl_state *g)
{
    for (int i = 0; i < N; i++)
        oit_gpu_mesh_destroy(g->views[i]);
    oit_gpu_draws_destroy(g->draws);
    glDeleteProgram(g->prog);
    glDeleteFramebuffers(1, &g->fbo);
    glDeleteBuffers(1, &g->acc);
    glDeleteBuffers(2, g->buf);
    glDeleteBuffers(1, &g->poison);
}

/* Fills both buffers with garbage (NaN bit patterns), then writes the meshes
 * where the layout puts them and points the views there. */
static void place(gl_state *g, const scene *s, const layout *l)
{
    for (int b = 0; b < 2; b++)
        glClearNamedBufferData(g->buf[b], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &garbage);
    for (int i = 0; i < N; i++) {
        GLuint buf = g->buf[l->buffer[i]];
        if (s->count[i])
            glNamedBufferSubData(g->buf[l->buffer[i]], (GLintptr)l->offset[i],
                                 (GLsizeiptr)(s->count[i] * sizeof(oit_triangle)), s->tris[i]);
        oit_gpu_mesh_set_buffer(g->views[i], buf);
        if (!sourced) {
            oit_gpu_mesh_set_range(g->views[i], l->offset[i], s->count[i], s->first_prim[i]);
            continue;
        }
        uint32_t prims[64];
        for (size_t j = 0; j < s->count[i] && j < 64; j++)
            prims[j] = prim_of(s, i, j);
        if (s->count[i])
            glNamedBufferSubData(buf, (GLintptr)(l->offset[i] + s->count[i] * sizeof(oit_triangle)),
                                 (GLsizeiptr)(s->count[i] * 4), prims);
        oit_gpu_mesh_set_range_sourced(g->views[i], l->offset[i], s->count[i]);
    }
}

static void fill_garbage(GLuint buf)
{
    if (buf)
        glClearNamedBufferData(buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &garbage);
}

/* Garbage wherever a draw could read what it did not set: the current value
 * of its input, its storage bindings, its scratch buffers. */
static void poison(gl_state *g)
{
    glVertexAttribI4uiv(OIT_IN_DRAW, garbage_attr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, g->poison);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, g->poison);
    for (int k = 0; k < 2; k++)
        fill_garbage(g->scratch[k]);
    for (int i = 0; i < N; i++)
        fill_garbage(g->view_records[i]);
}

/* Violations of the draw-state rules after a draw (see the top). */
typedef struct state_faults {
    int current, array, prims;
} state_faults;

/* Checks the state a draw left; returns the buffer its input reads. */
static GLuint check_after(state_faults *f)
{
    GLuint cur[4];
    glGetVertexAttribIuiv(OIT_IN_DRAW, GL_CURRENT_VERTEX_ATTRIB, cur);
    f->current += memcmp(cur, garbage_attr, sizeof cur) != 0;
    GLint enabled = 0, divisor = 0, integer = 0, buf = 0;
    glGetVertexAttribiv(OIT_IN_DRAW, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &enabled);
    glGetVertexAttribiv(OIT_IN_DRAW, GL_VERTEX_ATTRIB_ARRAY_DIVISOR, &divisor);
    glGetVertexAttribiv(OIT_IN_DRAW, GL_VERTEX_ATTRIB_ARRAY_INTEGER, &integer);
    glGetVertexAttribiv(OIT_IN_DRAW, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &buf);
    f->array += !enabled || divisor != 1 || !integer || buf == 0;
    return (GLuint)buf;
}

static void prims_bound_to(state_faults *f, GLuint want)
{
    GLint prims = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, OIT_BIND_PRIMS, &prims);
    f->prims += (GLuint)prims != want;
}

static void report(const char *name, int many, const state_faults *f)
{
    const char *path = many ? "many" : "mesh by mesh";
    CHECK(f->current == 0, "%s: %s: %d draws changed the current value of OIT_IN_DRAW", name,
          path, f->current);
    CHECK(f->array == 0, "%s: %s: %d draws left OIT_IN_DRAW without an integer array of "
          "divisor 1 (a draw that reads its current value)", name, path, f->array);
    CHECK(f->prims == 0, "%s: %s: %d draws left OIT_BIND_PRIMS unbound or on a buffer that "
          "is not the meshes'", name, path, f->prims);
}

/* The views one by one, each on freshly poisoned bindings. */
static void draw_each(gl_state *g, int n, state_faults *f)
{
    for (int i = 0; i < n; i++) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, g->poison);
        oit_gpu_mesh_draw(g->views[i], g->prog);
        if (oit_gpu_mesh_triangles(g->views[i]) == 0)
            continue;
        g->view_records[i] = check_after(f);
        prims_bound_to(f, oit_gpu_mesh_buffer(g->views[i]));
    }
}

static void draw_all(gl_state *g, int n, state_faults *f)
{
    oit_gpu_mesh_draw_many(g->draws, (const oit_gpu_mesh *const *)g->views, n);
    int drew = 0;
    for (int i = 0; i < n; i++)
        drew |= oit_gpu_mesh_triangles(g->views[i]) != 0;
    if (!drew)
        return;
    g->scratch[1] = check_after(f);
    GLint cmds = 0, prims = 0;
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &cmds);
    g->scratch[0] = (GLuint)cmds;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, OIT_BIND_PRIMS, &prims);
    f->prims += (GLuint)prims != g->buf[0] && (GLuint)prims != g->buf[1];
}

/* Draws the views [0, n) one by one or with draw_many on poisoned state;
 * reads the accumulators into acc; returns the draw calls draw_many made. */
static uint64_t draw(gl_state *g, const char *name, int n, int many, uint32_t *acc)
{
    static const GLuint zero = 0;
    glClearNamedBufferData(g->acc, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, g->acc);
    oit_glsl_raster_begin(g->fbo, W, H);
    glUseProgram(g->prog);
    poison(g);
    uint64_t before = oit_gpu_draws_calls(g->draws);
    state_faults f = {0};
    if (many)
        draw_all(g, n, &f);
    else
        draw_each(g, n, &f);
    report(name, many, &f);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(g->acc, 0, ACC_WORDS * 4, acc);
    return oit_gpu_draws_calls(g->draws) - before;
}

/* The expected centre figures of meshes [0, n). */
static void center_of(const scene *s, int n, uint32_t out[3])
{
    memset(out, 0, 3 * sizeof *out);
    for (int i = 0; i < n; i++)
        for (size_t j = 0; j < s->count[i]; j += 2) {
            uint32_t prim = prim_of(s, i, j);
            out[0]++;
            out[1] += prim;
            out[2] ^= prim * 2654435761u;
        }
}

static void run_case(gl_state *g, const scene *s, const char *what, const layout *l, int n,
                     size_t window, uint64_t want_calls)
{
    static uint32_t ref[ACC_WORDS], got[ACC_WORDS];
    char name[192];
    snprintf(name, sizeof name, "%s%s", prefix, what);
    place(g, s, l);
    oit_gpu_draws_set_window(g->draws, window);
    draw(g, name, n, 0, ref);
    uint64_t calls = draw(g, name, n, 1, got);
    oit_gpu_draws_set_window(g->draws, 0);
    oit_error err = {0};
    CHECK(oit_gl_check(name, &err) == OIT_OK, "%s: %s", name, err.message);
    uint32_t want[3], frags = 0, differ = 0;
    center_of(s, n, want);
    for (int p = 0; p < W * H; p++) {
        frags += ref[3 * p];
        differ += memcmp(&ref[3 * p], &got[3 * p], 3 * sizeof *ref) != 0;
    }
    printf("%s: %d meshes, window %zu: %llu draw calls (want %llu), %u fragments, %u pixels "
           "differ, centre %u prims\n", name, n, window, (unsigned long long)calls,
           (unsigned long long)want_calls, frags, differ, got[3 * W * H]);
    CHECK(frags > 0, "%s: nothing drawn", name);
    CHECK(differ == 0, "%s: %u pixels differ from drawing mesh by mesh", name, differ);
    CHECK(calls == want_calls, "%s: %llu draw calls, want %llu", name,
          (unsigned long long)calls, (unsigned long long)want_calls);
    for (int k = 0; k < 3; k++) {
        CHECK(ref[3 * W * H + k] == want[k], "%s: mesh by mesh, centre figure %d is %u, want "
              "%u", name, k, ref[3 * W * H + k], want[k]);
        CHECK(got[3 * W * H + k] == want[k], "%s: many, centre figure %d is %u, want %u", name,
              k, got[3 * W * H + k], want[k]);
    }
}

/* Runs of consecutive non-empty meshes in one buffer. */
static uint64_t buffer_runs(const scene *s, const layout *l, int n)
{
    uint64_t runs = 0;
    int last = -1;
    for (int i = 0; i < n; i++)
        if (s->count[i]) {
            runs += l->buffer[i] != last;
            last = l->buffer[i];
        }
    return runs;
}

static void cases(gl_state *g, scene *s)
{
    static layout l;
    for (int i = 0; i < N; i++)
        l.buffer[i] = 0, l.offset[i] = (uint64_t)i * SLOT;
    run_case(g, s, "one buffer", &l, N, 0, 1);
    static uint32_t acc[ACC_WORDS];
    uint64_t none = draw(g, "no meshes", 0, 1, acc);
    CHECK(none == 0, "no meshes: %llu draw calls", (unsigned long long)none);

    for (int i = 0; i < N; i++)
        l.buffer[i] = (i / 3 + i / 7) % 2;
    run_case(g, s, "alternating runs", &l, N, 0, buffer_runs(s, &l, N));
    for (int i = 0; i < N; i++)
        l.buffer[i] = i % 2;
    run_case(g, s, "alternating", &l, N, 0, buffer_runs(s, &l, N));

    /* Tiny window of 64 triangles (3072 bytes) over the non-empty meshes
     * (at most 19 triangles, 912 bytes) in 1K slots in reverse order: a
     * group spans 3 slots (2 * 1024 + 912 fits, 3 * 1024 does not). */
    static scene packed;
    int m = 0;
    for (int i = 0; i < N; i++)
        if (s->count[i]) {
            packed.tris[m] = s->tris[i];
            packed.count[m] = s->count[i];
            packed.first_prim[m] = s->first_prim[i];
            m++;
        }
    for (int k = 0; k < N; k++) {
        l.buffer[k] = 0;
        l.offset[k] = k < m ? (uint64_t)(m - 1 - k) * SLOT : 0;
    }
    run_case(g, &packed, "reverse slots, window 64", &l, m, 64, (uint64_t)(m + 2) / 3);
}

/* A mesh of 150 triangles in a window of 64 is cut at 0, 64 and 128; its
 * last 22 share a group with a mesh that starts 1760 bytes further, not
 * with one 3552 bytes further; in the other buffer a mesh at 0 and one of
 * 129 triangles at 1024, whose windows [1024, 4096), [4096, 7168),
 * [7168, 7216) cannot join anything: 8 groups. */
static void big_meshes(gl_state *g)
{
    static const size_t count[5] = {150, 10, 10, 10, 129};
    static const int buffer[5] = {0, 0, 0, 1, 1};
    static const uint64_t offset[5] = {0, 7424, 9216, 0, 1024};
    static scene big;
    static layout l;
    uint32_t r = 777;
    for (int i = 0; i < 5; i++) {
        big.count[i] = count[i];
        big.first_prim[i] = 100000u * (uint32_t)(5 - i);
        big.tris[i] = calloc(count[i], sizeof(oit_triangle));
        for (size_t j = 0; big.tris[i] && j < count[i]; j++)
            make_triangle(&big.tris[i][j], j % 2 == 0, &r);
        l.buffer[i] = buffer[i];
        l.offset[i] = offset[i];
        CHECK(big.tris[i] != NULL, "out of memory");
    }
    for (int i = 5; i < N; i++)
        l.buffer[i] = 1, l.offset[i] = 0;
    if (big.tris[0] && big.tris[1] && big.tris[2] && big.tris[3] && big.tris[4])
        run_case(g, &big, "big meshes, window 64", &l, 5, 64, 8);
    for (int i = 0; i < 5; i++)
        free(big.tris[i]);
}

/* The meshes in a shuffled order (their slots, buffers and prims their
 * own), then in reverse: in one buffer, one group whatever the order; in
 * two, one group a run. */
static void orders(gl_state *g, const scene *s)
{
    static scene p;
    static layout l;
    int perm[N];
    uint32_t r = 99;
    for (int i = 0; i < N; i++)
        perm[i] = i;
    for (int i = N - 1; i > 0; i--) {
        int j = (int)(rng(&r) % (uint32_t)(i + 1)), t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int k = 0; k < N; k++) {
            int i = pass == 0 ? perm[k] : N - 1 - k;
            p.tris[k] = s->tris[i];
            p.count[k] = s->count[i];
            p.first_prim[k] = s->first_prim[i];
            l.offset[k] = (uint64_t)i * SLOT;
            l.buffer[k] = 0;
        }
        run_case(g, &p, pass ? "reversed, one buffer" : "shuffled, one buffer", &l, N, 0, 1);
        for (int k = 0; k < N; k++)
            l.buffer[k] = (int)(l.offset[k] / SLOT) % 2;
        run_case(g, &p, pass ? "reversed, alternating" : "shuffled, alternating", &l, N, 0,
                 buffer_runs(&p, &l, N));
    }
}

/* Draws two triangles, both over the centre, at prims prim and prim + 1
 * (gl_PrimitiveID 0 and 1), through a vertex array of the test's own whose
 * record is rec, with OIT_BIND_VERTS holding `tris` of them and
 * OIT_BIND_PRIMS one word, 7, at PRIMS_AT; returns the centre's figures. */
enum { PRIMS_AT = 4096 };
static void draw_record(gl_state *g, oit_draw_rec rec, int tris, uint32_t centre[3])
{
    static uint32_t acc[ACC_WORDS];
    static const GLuint zero = 0, prim = 7;
    oit_triangle t[2];
    uint32_t r = 4242;
    make_triangle(&t[0], 1, &r);
    make_triangle(&t[1], 1, &r);
    glNamedBufferSubData(g->buf[0], 0, sizeof t, t);
    glNamedBufferSubData(g->buf[0], PRIMS_AT, 4, &prim);
    GLuint vao = 0, records = 0;
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &records);
    glNamedBufferStorage(records, sizeof rec, &rec, 0);
    oit_draw_records_attach(vao, records);
    glClearNamedBufferData(g->acc, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, g->acc);
    oit_glsl_raster_begin(g->fbo, W, H);
    glUseProgram(g->prog);
    glBindVertexArray(vao);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, g->buf[0], 0,
                      (GLsizeiptr)(tris * sizeof(oit_triangle)));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, g->buf[0], PRIMS_AT, 4);
    glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 6, 1, 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(g->acc, 0, ACC_WORDS * 4, acc);
    memcpy(centre, &acc[3 * W * H], 3 * sizeof *centre);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &records);
}

/* Records that do not fit their bindings: the vertex stage drops the
 * triangles they would read out of range, and draws the others exactly. */
static void guards(gl_state *g)
{
    static const struct {
        const char *what;
        oit_draw_rec rec;
        int tris;
        uint32_t prim; /* of the one triangle that must be drawn */
    } c[3] = {
        {"its second prim past OIT_BIND_PRIMS", {0, 0x80000000u}, 2, 7},
        {"first vertex 3, drawn from vertex 0", {3, 500}, 2, 501},
        {"its second triangle past OIT_BIND_VERTS", {0, 600}, 1, 600},
    };
    for (int k = 0; k < 3; k++) {
        uint32_t centre[3];
        draw_record(g, c[k].rec, c[k].tris, centre);
        printf("record with %s: centre %u fragments, prims %u\n", c[k].what, centre[0],
               centre[1]);
        CHECK(centre[0] == 1 && centre[1] == c[k].prim,
              "record with %s: the centre got %u fragments, prims summing to %u; want 1, "
              "prim %u (a triangle read out of range was drawn)", c[k].what, centre[0],
              centre[1], c[k].prim);
    }
}

/* Every layout in both kinds of views with the driver's SSBO offset
 * alignment, then with 256 (which all the layouts' offsets keep), then
 * with the driver's again: the same cases a second time in one process. */
static void rounds(gl_state *g, scene *s)
{
    static const uint64_t aligns[3] = {0, 256, 0};
    for (int round = 0; round < 3; round++) {
        oit_gpu_draws_set_align(g->draws, aligns[round]);
        for (int i = 0; i < N; i++)
            oit_gpu_mesh_set_align(g->views[i], aligns[round]);
        for (sourced = 0; sourced < 2; sourced++) {
            snprintf(prefix, sizeof prefix, "round %d, alignment %s%s: ", round + 1,
                     aligns[round] ? "256" : "the driver's", sourced ? ", sourced" : "");
            cases(g, s);
            orders(g, s);
            if (!sourced) /* its prims would overlap the next mesh */
                big_meshes(g);
        }
    }
    prefix[0] = 0;
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    static scene s;
    gl_state g;
    memset(&g, 0, sizeof g);
    if (!make_scene(&s) || !setup(&g, &err)) {
        fprintf(stderr, "FAIL: set-up: %s\n", err.message);
        test_failures++;
    } else {
        rounds(&g, &s);
        guards(&g);
    }
    teardown(&g);
    free_scene(&s);
    return test_gl_verdict(gl);
}
