/* The assimp reader (formats/assimp_adapter.cpp) through oit_mesh_read, on
 * the samples of tests/corpus/assimp (README there: where they come from).
 *
 * Counts: each sample's triangles equal assimp's own count, two ways, both
 * independent of the adapter's node walk:
 *   - assimp's C API here, with aiProcess_PreTransformVertices (assimp
 *     flattens the node tree itself, a mesh once per instance): the faces
 *     of three indices, and the bounds of their vertices, which must be the
 *     reader's (its origin added back) to 1e-5 of the extent;
 *   - a figure pinned from `assimp info FILE` (Debian's assimp-utils 5.2.5,
 *     its "Faces:" line), for the samples that instance no mesh twice; the
 *     Collada teapot instances its one mesh twice, which `assimp info`
 *     counts once (1024).
 * Colours: the IFC wall of tests/corpus/assimp/wall_glass.ifc, plaster
 * (0.8 0.8 0.7, Transparency 0) behind glass (0.2 0.5 0.8, Transparency 0.6
 * so opacity 0.4), pinned from the file's own numbers as assimp's floats
 * round them (0.7f * 255 is 178.49, so 178); the 3DS cubes, whose
 * material "Transparent" has opacity 0.83 (12 triangles with alpha 212, 48
 * opaque ones). Bad input: a truncated FBX, random bytes named .dae, an IFC
 * without geometry, an IFC on which libassimp itself dies (SIGSEGV), an
 * extension nobody reads: the documented status and a message that names
 * the file. A gzip copy reads as the plain file does;
 * chunks of 7 deliver the same triangles; a small memory budget is refused.
 * usage: test_assimp CORPUS_DIR (tests/corpus/assimp) */
#include "oit/mesh.h"
#include "tests/lib/test_check.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *corpus;
static char tmp_dir[4096];

static const char *at(const char *dir, const char *name)
{
    static char buf[2][4096];
    static int k;
    k ^= 1;
    snprintf(buf[k], sizeof buf[k], "%.3000s/%.1000s", dir, name);
    return buf[k];
}

/* assimp's own count and bounds, with its own flattening of the node tree. */
static long assimp_triangles(const char *path, double lo[3], double hi[3])
{
    const struct aiScene *s =
        aiImportFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (!s)
        return -1;
    long n = 0;
    for (int k = 0; k < 3; k++)
        lo[k] = INFINITY, hi[k] = -INFINITY;
    for (unsigned i = 0; i < s->mNumMeshes; i++) {
        const struct aiMesh *m = s->mMeshes[i];
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            if (m->mFaces[f].mNumIndices != 3)
                continue;
            n++;
            for (int c = 0; c < 3; c++) {
                const struct aiVector3D *v = &m->mVertices[m->mFaces[f].mIndices[c]];
                double p[3] = {v->x, v->y, v->z};
                for (int k = 0; k < 3; k++)
                    lo[k] = fmin(lo[k], p[k]), hi[k] = fmax(hi[k], p[k]);
            }
        }
    }
    aiReleaseImport(s);
    return n;
}

static void check_sample(const char *name, long pinned)
{
    const char *path = at(corpus, name);
    oit_mesh m = {0};
    oit_error err;
    oit_status st = oit_mesh_load(path, NULL, &m, &err);
    CHECK(st == OIT_OK, "%s: %s", name, err.message);
    if (st != OIT_OK)
        return;
    double lo[3], hi[3];
    long own = assimp_triangles(path, lo, hi);
    long got = (long)(m.info.triangles + m.info.nonfinite_dropped);
    CHECK(own > 0, "%s: assimp's C API reads no triangle", name);
    CHECK(got == own, "%s: %ld triangles, assimp's own count is %ld", name, got, own);
    CHECK(got == pinned, "%s: %ld triangles, `assimp info` pinned %ld", name, got, pinned);
    CHECK((long)m.count == (long)m.info.triangles, "%s: %zu delivered, info says %llu", name,
          m.count, (unsigned long long)m.info.triangles);
    double ext = 0;
    for (int k = 0; k < 3; k++)
        ext = fmax(ext, hi[k] - lo[k]);
    for (int k = 0; k < 3; k++) {
        double a = m.info.bounds_min[k] + m.info.origin[k], b = m.info.bounds_max[k] + m.info.origin[k];
        CHECK(fabs(a - lo[k]) <= 1e-5 * ext && fabs(b - hi[k]) <= 1e-5 * ext,
              "%s: axis %d bounds %g..%g, assimp's %g..%g", name, k, a, b, lo[k], hi[k]);
    }
    printf("%s: %ld triangles (assimp: %ld, pinned %ld), attributes %u\n", name, got, own,
           pinned, m.info.attributes);
    oit_mesh_free(&m);
}

/* Triangles of m whose three vertices have colour rgba. */
static size_t count_rgba(const oit_mesh *m, const uint8_t rgba[4])
{
    size_t n = 0;
    for (size_t i = 0; i < m->count; i++) {
        int all = 1;
        for (int v = 0; v < 3; v++)
            all &= memcmp(m->tris[i].v[v].rgba, rgba, 4) == 0;
        n += (size_t)all;
    }
    return n;
}

static void check_colours(void)
{
    oit_mesh m = {0};
    oit_error err;
    if (oit_mesh_load(at(corpus, "wall_glass.ifc"), NULL, &m, &err) == OIT_OK) {
        const uint8_t glass[4] = {51, 128, 204, 102}, plaster[4] = {204, 204, 178, 255};
        CHECK(count_rgba(&m, glass) == 12, "wall_glass.ifc: %zu glass triangles, want 12",
              count_rgba(&m, glass));
        CHECK(count_rgba(&m, plaster) == 12, "wall_glass.ifc: %zu plaster triangles, want 12",
              count_rgba(&m, plaster));
        CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE),
              "wall_glass.ifc: attributes %u", m.info.attributes);
    } else {
        CHECK(0, "wall_glass.ifc: %s", err.message);
    }
    oit_mesh_free(&m);
    if (oit_mesh_load(at(corpus, "cubes_with_alpha.3DS"), NULL, &m, &err) == OIT_OK) {
        size_t translucent = 0, opaque = 0;
        for (size_t i = 0; i < m.count; i++) {
            uint8_t a = m.tris[i].v[0].rgba[3];
            translucent += a == 212;
            opaque += a == 255;
        }
        CHECK(translucent == 12 && opaque == 48,
              "cubes_with_alpha.3DS: %zu triangles of alpha 212, %zu of 255 (want 12, 48)",
              translucent, opaque);
    } else {
        CHECK(0, "cubes_with_alpha.3DS: %s", err.message);
    }
    oit_mesh_free(&m);
    /* no material in the file: assimp's stand-in gives no colour */
    if (oit_mesh_load(at(corpus, "box.3mf"), NULL, &m, &err) == OIT_OK)
        CHECK(m.info.attributes == 0, "box.3mf: attributes %u, want none", m.info.attributes);
    oit_mesh_free(&m);
}

static int write_file(const char *path, const void *bytes, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(bytes, 1, n, f) == n;
    return (f && fclose(f) == 0) && ok;
}

static void *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    rewind(f);
    void *b = size > 0 ? malloc((size_t)size) : NULL;
    if (b && fread(b, 1, (size_t)size, f) != (size_t)size) {
        free(b);
        b = NULL;
    }
    fclose(f);
    *n = (size_t)size;
    return b;
}

static oit_status drop(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    (void)t, (void)err;
    *(size_t *)user += n;
    return OIT_OK;
}

/* path must fail with want, naming the file and saying needle. */
static void expect_failure(const char *path, oit_status want, const char *needle)
{
    size_t got = 0;
    oit_error err;
    oit_mesh_info info;
    oit_status st = oit_mesh_read(path, NULL, drop, &got, &info, &err);
    CHECK(st == want, "%s: status %d, want %d (%s)", path, (int)st, (int)want,
          st ? err.message : "read");
    if (st == OIT_OK)
        return;
    CHECK(strncmp(err.message, path, strlen(path)) == 0, "the message does not start with %s: %s",
          path, err.message);
    CHECK(strstr(err.message, needle) != NULL, "%s: the message lacks '%s': %s", path, needle,
          err.message);
    printf("refused: %s\n", err.message);
}

static void check_bad_input(void)
{
    size_t n = 0;
    unsigned char *fbx = slurp(at(corpus, "box.fbx"), &n);
    CHECK(fbx != NULL, "cannot read box.fbx");
    if (!fbx)
        return;
    const char *trunc = at(tmp_dir, "truncated.fbx");
    CHECK(write_file(trunc, fbx, n / 2), "cannot write %s", trunc);
    expect_failure(trunc, OIT_ERR_FORMAT, "assimp cannot read it:");
    free(fbx);
    unsigned char noise[4096];
    unsigned x = 12345;
    for (size_t i = 0; i < sizeof noise; i++)
        noise[i] = (unsigned char)((x = x * 1103515245u + 12345u) >> 16);
    const char *dae = at(tmp_dir, "noise.dae");
    CHECK(write_file(dae, noise, sizeof noise), "cannot write %s", dae);
    expect_failure(dae, OIT_ERR_FORMAT, "assimp cannot read it:");
    expect_failure(at(corpus, "empty_site.ifc"), OIT_ERR_FORMAT, "no geometry");
    /* assimp itself dies on it: the import's child process does, not us */
    expect_failure(at(corpus, "crashes_assimp.ifc"), OIT_ERR_FORMAT, "assimp crashed reading it");
    const char *xyz = at(tmp_dir, "mesh.xyz");
    CHECK(write_file(xyz, noise, 16), "cannot write %s", xyz);
    expect_failure(xyz, OIT_ERR_UNSUPPORTED, "unknown mesh format '.xyz'");
    const char *empty = at(tmp_dir, "empty.fbx");
    CHECK(write_file(empty, "", 0), "cannot write %s", empty);
    expect_failure(empty, OIT_ERR_FORMAT, "empty");
    expect_failure(at(tmp_dir, "missing.fbx"), OIT_ERR_IO, "cannot open");
}

/* The teapot read in chunks of 7 and in one piece; under a 1 KiB budget. */
static void check_chunks_and_budget(void)
{
    const char *path = at(corpus, "teapot_instancenodes.DAE");
    size_t whole = 0, chunked = 0;
    oit_error err;
    oit_mesh_info a, b;
    oit_read_desc small = {.chunk_triangles = 7};
    CHECK(oit_mesh_read(path, NULL, drop, &whole, &a, &err) == OIT_OK, "%s", err.message);
    CHECK(oit_mesh_read(path, &small, drop, &chunked, &b, &err) == OIT_OK, "%s", err.message);
    CHECK(whole == chunked && whole == a.triangles && whole > 0,
          "teapot: %zu triangles whole, %zu in chunks of 7", whole, chunked);
    oit_read_desc tight = {.memory_budget = 1024};
    size_t got = 0;
    CHECK(oit_mesh_read(path, &tight, drop, &got, &a, &err) == OIT_ERR_NOMEM,
          "teapot within 1 KiB: %s", got ? "read" : err.message);
}

/* wall_glass.ifc gzip-compressed (wall_glass.ifc.gz in the corpus). */
static void check_gzip(void)
{
    oit_mesh plain = {0}, gz = {0};
    oit_error err;
    CHECK(oit_mesh_load(at(corpus, "wall_glass.ifc"), NULL, &plain, &err) == OIT_OK, "%s",
          err.message);
    CHECK(oit_mesh_load(at(corpus, "wall_glass.ifc.gz"), NULL, &gz, &err) == OIT_OK, "%s",
          err.message);
    CHECK(plain.count == gz.count && plain.count > 0 &&
              memcmp(plain.tris, gz.tris, plain.count * sizeof *plain.tris) == 0,
          "wall_glass.ifc.gz: %zu triangles, the plain file %zu, or they differ", gz.count,
          plain.count);
    oit_mesh_free(&plain);
    oit_mesh_free(&gz);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_assimp CORPUS_DIR\n");
        return 2;
    }
    corpus = argv[1];
    const char *t = getenv("OIT_TEST_TMP");
    snprintf(tmp_dir, sizeof tmp_dir, "%s", t && *t ? t : "/tmp");
    check_sample("box.fbx", 12);
    check_sample("kwxport_test_vcolors.dae", 12);
    check_sample("teapot_instancenodes.DAE", 2048);
    check_sample("box.3mf", 12);
    check_sample("cubes_with_alpha.3DS", 60);
    check_sample("wall_glass.ifc", 24);
    check_colours();
    check_bad_input();
    check_chunks_and_budget();
    check_gzip();
    return test_verdict();
}
