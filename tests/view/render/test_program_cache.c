/* The program binary cache (view/render/gl/program_cache.h): a program loaded
 * from an entry draws and computes what the compiled one does; an entry
 * with flipped bytes, cut short, or of another program is built again and
 * written again, never used; a folder that cannot hold entries works
 * without; two sources never share an entry; the folder setting resolves
 * as documented. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "view/render/gl/glsl_bindings.h"
#include "view/render/gl/program_cache.h"
#include "tests/lib/test_files.h"
#include "tests/lib/test_gl.h"

#define SIZE 32
#define N_OUT 4096

static const char version[] = "#version 450 core\n" OIT_GLSL_BINDINGS;
static const char vs_src[] =
    "void main() {\n"
    "    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";
/* A colour that depends on the pixel through float arithmetic, so a wrong
 * or half-loaded program shows in the image. TINT is what two otherwise
 * equal programs differ in. */
static const char fs_src[] =
    "layout(location = 0) out vec4 colour;\n"
    "void main() {\n"
    "    vec2 p = gl_FragCoord.xy;\n"
    "    colour = vec4(fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453),\n"
    "                  p.x / 32.0, p.y / 32.0, TINT);\n"
    "}\n";
static const char cs_src[] =
    "layout(local_size_x = 64) in;\n"
    "layout(std430, binding = OIT_BIND_OUT) buffer Out { uint v[]; };\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    v[i] = i * 2654435761u ^ (i >> 3) ^ uint(TINT * 1000.0);\n"
    "}\n";

typedef struct sources {
    const char *vs[3], *fs[4], *cs[4];
} sources;

static sources make_sources(const char *tint)
{
    sources s = {{version, vs_src, NULL},
                 {version, tint, fs_src, NULL},
                 {version, tint, cs_src, NULL}};
    return s;
}

static const char tint_a[] = "#define TINT 0.25\n", tint_b[] = "#define TINT 0.75\n";

/* The image prog draws (SIZE x SIZE RGBA floats). */
static void draw(GLuint prog, float *rgba)
{
    GLuint tex = 0, fbo = 0, vao = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, SIZE, SIZE);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, SIZE, SIZE);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, SIZE * SIZE * 16, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
}

/* What prog computes (N_OUT words). */
static void compute(GLuint prog, uint32_t *out)
{
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, N_OUT * 4, NULL, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, buf);
    glUseProgram(prog);
    glDispatchCompute(N_OUT / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf, 0, N_OUT * 4, out);
    glDeleteBuffers(1, &buf);
}

/* A program's results, to compare a cached build with a compiled one. */
typedef struct results {
    float rgba[SIZE * SIZE * 4];
    uint32_t words[N_OUT];
} results;

/* Builds the graphics and the compute program of tint through pc (NULL:
 * compiled) and runs both. */
static int build_run(oit_program_cache *pc, const char *tint, results *r)
{
    sources s = make_sources(tint);
    oit_error err = {0};
    GLuint g = 0, c = 0;
    oit_status st = oit_program_cache_build(pc, "test graphics", s.vs, s.fs, NULL, &g, &err);
    if (st == OIT_OK)
        st = oit_program_cache_build(pc, "test compute", NULL, NULL, s.cs, &c, &err);
    CHECK(st == OIT_OK, "build %s: %s", tint, err.message);
    if (st == OIT_OK) {
        draw(g, r->rgba);
        compute(c, r->words);
    }
    glUseProgram(0);
    glDeleteProgram(g);
    glDeleteProgram(c);
    return st == OIT_OK;
}

static int same(const results *a, const results *b)
{
    return !memcmp(a->rgba, b->rgba, sizeof a->rgba) && !memcmp(a->words, b->words, sizeof a->words);
}

/* The entries in dir, their names in names[0..) (up to 8). */
static int list_entries(const char *dir, char names[8][256])
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (e->d_name[0] != '.' && n < 8)
            snprintf(names[n++], 256, "%s", e->d_name);
    if (d)
        closedir(d);
    return n;
}

static void path_of(const char *dir, const char *name, char out[4096])
{
    snprintf(out, 4096, "%s/%s", dir, name);
}

static void write_bytes(const char *path, const uint8_t *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(b, 1, n, f);
        fclose(f);
    }
}

static oit_program_cache_stats stats_since(const oit_program_cache *pc,
                                           oit_program_cache_stats before)
{
    oit_program_cache_stats s = oit_program_cache_get_stats(pc);
    s.hits -= before.hits;
    s.misses -= before.misses;
    s.rejected -= before.rejected;
    s.written -= before.written;
    return s;
}

/* Every entry of dir damaged by `damage`, then one build: both programs
 * are rejected, built, right, and written again; the next build loads. */
typedef void (*damage_fn)(const char *path, uint8_t *b, size_t n);

static void flip(const char *path, uint8_t *b, size_t n)
{
    for (size_t i = n / 2; i < n; i += 97)
        b[i] ^= 0x5a;
    write_bytes(path, b, n);
}

static void flip_header(const char *path, uint8_t *b, size_t n)
{
    b[9] ^= 1; /* within the key's second hash */
    write_bytes(path, b, n);
}

static void truncate_half(const char *path, uint8_t *b, size_t n)
{
    write_bytes(path, b, n / 2);
}

/* A whole entry with bytes after it: not what was written. */
static void append(const char *path, uint8_t *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(b, 1, n, f);
        fwrite("tail", 1, 4, f);
        fclose(f);
    }
}

/* Flipped bytes under a checksum made to match (program_cache.h's
 * layout): the entry passes every check of ours and reaches the driver,
 * which must refuse it (Mesa's binaries carry their own hash). */
#define HEAD 40
static void forge(const char *path, uint8_t *b, size_t n)
{
    if (n <= HEAD + 64)
        return;
    for (size_t i = HEAD + 16; i < n; i += 53)
        b[i] ^= 0xa5;
    uint64_t sum = oit_program_cache_checksum(b + HEAD, n - HEAD);
    memcpy(b + 24, &sum, sizeof sum);
    write_bytes(path, b, n);
}

static void damaged(oit_program_cache *pc, const char *dir, const results *want,
                    damage_fn damage, int by_driver, const char *what)
{
    char names[8][256], path[4096];
    int n = list_entries(dir, names);
    CHECK(n == 2, "%s: %d entries before, expected 2", what, n);
    for (int i = 0; i < n; i++) {
        path_of(dir, names[i], path);
        size_t size = 0;
        uint8_t *b = test_read_file(path, &size);
        if (b)
            damage(path, b, size);
        free(b);
    }
    oit_program_cache_stats before = oit_program_cache_get_stats(pc);
    results *r = calloc(1, sizeof *r);
    if (r && build_run(pc, tint_a, r))
        CHECK(same(r, want), "%s: the rebuilt programs give other results", what);
    oit_program_cache_stats s = stats_since(pc, before);
    unsigned caught = by_driver ? s.refused : s.rejected, other = by_driver ? s.rejected : s.refused;
    CHECK(caught == 2 && other == 0 && s.hits == 0 && s.written == 2,
          "%s: rejected %u, refused %u, hits %u, written %u (expected 2 %s, 0, 2)", what,
          s.rejected, s.refused, s.hits, s.written, by_driver ? "refused" : "rejected");
    before = oit_program_cache_get_stats(pc);
    if (r && build_run(pc, tint_a, r))
        CHECK(same(r, want), "%s: the rewritten entries give other results", what);
    s = stats_since(pc, before);
    CHECK(s.hits == 2, "%s: the rewritten entries were not loaded (%u hits)", what, s.hits);
    free(r);
}

/* The entry of tint b put where tint a's belongs: a's build must not take
 * it (it would compute b's results). */
static void wrong_key(oit_program_cache *pc, const char *dir, const results *want_a)
{
    char names[8][256], path[4096];
    int n = list_entries(dir, names);
    CHECK(n == 2, "wrong key: %d entries of a, expected 2", n);
    char a_names[2][256];
    for (int i = 0; i < 2 && i < n; i++)
        snprintf(a_names[i], 256, "%s", names[i]);
    results *r = calloc(1, sizeof *r);
    if (!r)
        return;
    build_run(pc, tint_b, r); /* b's entries written beside a's */
    n = list_entries(dir, names);
    CHECK(n == 4, "two sources share an entry: %d entries for 4 programs", n);
    /* b's graphics entry over a's graphics entry, and b's compute over a's
     * compute: the names that are not a's are b's, in some order, so try
     * each of b's over each of a's */
    for (int i = 0; i < n; i++) {
        if (!strcmp(names[i], a_names[0]) || !strcmp(names[i], a_names[1]))
            continue;
        char from[4096];
        path_of(dir, names[i], from);
        size_t size = 0;
        uint8_t *b = test_read_file(from, &size);
        for (int j = 0; j < 2 && b; j++) {
            path_of(dir, a_names[j], path);
            write_bytes(path, b, size);
        }
        free(b);
        oit_program_cache_stats before = oit_program_cache_get_stats(pc);
        if (build_run(pc, tint_a, r))
            CHECK(same(r, want_a), "an entry of another program was used");
        oit_program_cache_stats s = stats_since(pc, before);
        CHECK(s.rejected == 2 && s.hits == 0,
              "another program's entry: rejected %u, hits %u (expected 2, 0)", s.rejected,
              s.hits);
    }
    free(r);
}

static void not_a_folder(const char *dir, const results *want)
{
    char file[4096], below[4400];
    path_of(dir, "a-file", file);
    write_bytes(file, (const uint8_t *)"x", 1);
    snprintf(below, sizeof below, "%s/cache", file);
    oit_program_cache *pc = NULL;
    oit_error err = {0};
    CHECK(oit_program_cache_open(below, &pc, &err) == OIT_OK, "%s", err.message);
    CHECK(pc == NULL, "a cache on %s, below a file", below);
    results *r = calloc(1, sizeof *r);
    if (r && build_run(pc, tint_a, r))
        CHECK(same(r, want), "without a cache: other results");
    oit_program_cache_close(pc);
    free(r);
}

/* A folder that cannot be written (where permissions bind: not as root). */
static void read_only(const char *dir, const results *want)
{
    char ro[4096];
    path_of(dir, "read-only", ro);
    mkdir(ro, 0755);
    chmod(ro, 0555);
    char probe[4400];
    snprintf(probe, sizeof probe, "%s/probe", ro);
    FILE *f = fopen(probe, "wb");
    if (f) {
        fclose(f);
        unlink(probe);
        printf("read-only folder: writable here (root?), case skipped\n");
        return;
    }
    oit_program_cache *pc = NULL;
    oit_error err = {0};
    CHECK(oit_program_cache_open(ro, &pc, &err) == OIT_OK, "%s", err.message);
    results *r = calloc(1, sizeof *r);
    if (r && build_run(pc, tint_a, r))
        CHECK(same(r, want), "read-only folder: other results");
    oit_program_cache_stats s = oit_program_cache_get_stats(pc);
    CHECK(s.written == 0 && s.misses == 2, "read-only folder: written %u, misses %u", s.written,
          s.misses);
    oit_program_cache_close(pc);
    chmod(ro, 0755);
    free(r);
}

static void folders(void)
{
    char out[256];
    unsetenv("OIT_PROGRAM_CACHE");
    setenv("XDG_CACHE_HOME", "/x/cache", 1);
    setenv("HOME", "/home/u", 1);
    oit_program_cache_folder(NULL, out, sizeof out);
    CHECK(!strcmp(out, "/x/cache/oit"), "XDG_CACHE_HOME: %s", out);
    setenv("XDG_CACHE_HOME", "relative", 1);
    oit_program_cache_folder(NULL, out, sizeof out);
    CHECK(!strcmp(out, "/home/u/.cache/oit"), "a relative XDG_CACHE_HOME: %s", out);
    setenv("OIT_PROGRAM_CACHE", "/e", 1);
    oit_program_cache_folder(NULL, out, sizeof out);
    CHECK(!strcmp(out, "/e"), "OIT_PROGRAM_CACHE: %s", out);
    oit_program_cache_folder("/given", out, sizeof out);
    CHECK(!strcmp(out, "/given"), "the caller's folder: %s", out);
    oit_program_cache_folder("off", out, sizeof out);
    CHECK(out[0] == '\0', "off: %s", out);
    setenv("OIT_PROGRAM_CACHE", "off", 1);
    oit_program_cache_folder(NULL, out, sizeof out);
    CHECK(out[0] == '\0', "OIT_PROGRAM_CACHE=off: %s", out);
    oit_program_cache *pc = NULL;
    oit_error err = {0};
    CHECK(oit_program_cache_open(NULL, &pc, &err) == OIT_OK && pc == NULL,
          "OIT_PROGRAM_CACHE=off opened a cache");
    unsetenv("OIT_PROGRAM_CACHE");
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    GLint formats = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    printf("program binary formats: %d\n", formats);
    char dir[] = "/tmp/oit-program-cache-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    results *compiled = calloc(1, sizeof *compiled), *loaded = calloc(1, sizeof *loaded);
    if (!compiled || !loaded)
        return 1;
    build_run(NULL, tint_a, compiled);
    oit_program_cache *pc = NULL;
    oit_error err = {0};
    CHECK(oit_program_cache_open(dir, &pc, &err) == OIT_OK, "%s", err.message);
    if (formats > 0 && pc) {
        CHECK(!strcmp(oit_program_cache_dir(pc), dir), "folder %s", oit_program_cache_dir(pc));
        build_run(pc, tint_a, loaded);
        oit_program_cache_stats s = oit_program_cache_get_stats(pc);
        CHECK(s.misses == 2 && s.written == 2 && s.hits == 0,
              "first build: misses %u, written %u, hits %u", s.misses, s.written, s.hits);
        CHECK(same(loaded, compiled), "a program built through the cache differs");
        memset(loaded, 0, sizeof *loaded);
        build_run(pc, tint_a, loaded);
        s = oit_program_cache_get_stats(pc);
        CHECK(s.hits == 2, "second build: %u hits, expected 2", s.hits);
        CHECK(same(loaded, compiled), "a program loaded from an entry differs from the compiled");
        damaged(pc, dir, compiled, flip, 0, "flipped bytes");
        damaged(pc, dir, compiled, flip_header, 0, "a flipped key");
        damaged(pc, dir, compiled, truncate_half, 0, "truncated");
        damaged(pc, dir, compiled, append, 0, "bytes appended");
        damaged(pc, dir, compiled, forge, 1, "a forged checksum");
        wrong_key(pc, dir, compiled);
    } else {
        CHECK(formats == 0 && pc == NULL, "formats %d but cache %p", formats, (void *)pc);
        printf("no program binary format: the cache is off, its cases skipped\n");
    }
    oit_program_cache_close(pc);
    not_a_folder(dir, compiled);
    read_only(dir, compiled);
    folders();
    free(compiled);
    free(loaded);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "%s", cmd);
    return test_gl_verdict(gl);
}
