/* Unit test of the streaming PLY writer: exact content round trip (with and
 * without colours, across many buffer flushes), error paths (bad index,
 * unwritable path) and that no half file or temporary survives a failure. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "formats/ply_writer.h"
#include "tests/lib/scene_ply_check.h"
#include "tests/lib/test_check.h"


static char tmpdir[512];

static void path_in_tmp(char *out, size_t n, const char *name)
{
    snprintf(out, n, "%s/%s", tmpdir, name);
}

static int exists(const char *path)
{
    return access(path, F_OK) == 0;
}

static int no_temporaries(const char *path)
{
    char a[600], b[600];
    snprintf(a, sizeof a, "%s.tmp", path);
    snprintf(b, sizeof b, "%s.faces.tmp", path);
    return !exists(a) && !exists(b);
}

/* Vertex i sits at (i, -i/2, i*0.25) with colour (i, 2i, 3i, 255-i) mod 256;
 * face j is (j, j+1, j+2) mod nv with colour (j, 7j, 0, 9). */
static void round_trip(int vrgba, int frgba, size_t nv, size_t nf)
{
    char path[600];
    path_in_tmp(path, sizeof path, "writer_round_trip.ply");
    oit_ply_writer_desc d = {.path = path, .vertex_rgba = vrgba, .face_rgba = frgba,
                             .comment = "unit test"};
    oit_ply_writer *w;
    oit_error err = {0};
    CHECK(!oit_ply_writer_open(&d, &w, &err), "open: %s", err.message);
    enum { CHUNK = 1000 };
    float xyz[3 * CHUNK];
    uint8_t rgba[4 * CHUNK];
    uint32_t idx[3 * CHUNK];
    for (size_t i0 = 0; i0 < nv; i0 += CHUNK) {
        size_t n = nv - i0 < CHUNK ? nv - i0 : CHUNK;
        for (size_t k = 0; k < n; k++) {
            size_t i = i0 + k;
            xyz[3 * k] = (float)i, xyz[3 * k + 1] = -0.5f * (float)i, xyz[3 * k + 2] = 0.25f * (float)i;
            rgba[4 * k] = (uint8_t)i, rgba[4 * k + 1] = (uint8_t)(2 * i);
            rgba[4 * k + 2] = (uint8_t)(3 * i), rgba[4 * k + 3] = (uint8_t)(255 - i);
        }
        uint32_t first = 0;
        CHECK(!oit_ply_writer_add_vertices(w, xyz, rgba, n, &first, &err), "vertices: %s", err.message);
        CHECK(first == i0, "first index %u, expected %zu", first, i0);
    }
    for (size_t j0 = 0; j0 < nf; j0 += CHUNK) {
        size_t n = nf - j0 < CHUNK ? nf - j0 : CHUNK;
        for (size_t k = 0; k < n; k++) {
            size_t j = j0 + k;
            for (int c = 0; c < 3; c++)
                idx[3 * k + c] = (uint32_t)((j + c) % nv);
            rgba[4 * k] = (uint8_t)j, rgba[4 * k + 1] = (uint8_t)(7 * j), rgba[4 * k + 2] = 0, rgba[4 * k + 3] = 9;
        }
        CHECK(!oit_ply_writer_add_faces(w, idx, rgba, n, &err), "faces: %s", err.message);
    }
    oit_ply_writer_stats st = {0};
    CHECK(!oit_ply_writer_close(w, &st, &err), "close: %s", err.message);
    CHECK(no_temporaries(path), "temporaries left next to %s", path);
    test_ply p;
    int bad = test_ply_load(&p, path);
    CHECK(!bad, "load: %s", p.why);
    printf("round trip vrgba=%d frgba=%d: %zu vertices %zu faces, %zu bytes (header %zu)\n", vrgba,
           frgba, p.vertices, p.faces, p.file_bytes, p.header_bytes);
    CHECK(p.vertices == nv && p.faces == nf, "counts %zu %zu, expected %zu %zu", p.vertices, p.faces, nv, nf);
    CHECK(st.vertices == nv && st.faces == nf && st.bytes == p.file_bytes,
          "stats %llu %llu %llu vs file %zu", (unsigned long long)st.vertices,
          (unsigned long long)st.faces, (unsigned long long)st.bytes, p.file_bytes);
    CHECK(p.vertex_rgba == vrgba && p.face_rgba == frgba, "colour properties %d %d", p.vertex_rgba, p.face_rgba);
    size_t wrong = 0;
    for (size_t i = 0; !bad && i < nv; i++) {
        wrong += p.xyz[3 * i] != (float)i || p.xyz[3 * i + 1] != -0.5f * (float)i ||
                 p.xyz[3 * i + 2] != 0.25f * (float)i;
        wrong += vrgba && (p.vrgba[4 * i] != (uint8_t)i || p.vrgba[4 * i + 3] != (uint8_t)(255 - i));
    }
    for (size_t j = 0; !bad && j < nf; j++) {
        wrong += p.idx[3 * j] != j % nv || p.idx[3 * j + 2] != (j + 2) % nv;
        wrong += frgba && (p.frgba[4 * j + 1] != (uint8_t)(7 * j) || p.frgba[4 * j + 3] != 9);
    }
    CHECK(wrong == 0, "%zu values differ after the round trip", wrong);
    test_ply_free(&p);
    remove(path);
}

/* A writer of a plain PLY named name in the scratch folder (its path in
 * path[600]), with no file of that name there before. */
static oit_ply_writer *open_fresh(const char *name, char *path)
{
    path_in_tmp(path, 600, name);
    remove(path);
    oit_ply_writer_desc d = {.path = path};
    oit_ply_writer *w = NULL;
    oit_error err = {0};
    CHECK(!oit_ply_writer_open(&d, &w, &err), "open: %s", err.message);
    return w;
}

static void bad_index_leaves_nothing(void)
{
    char path[600];
    oit_ply_writer *w = open_fresh("writer_bad_index.ply", path);
    oit_error err = {0};
    float xyz[9] = {0};
    uint32_t idx[3] = {0, 1, 3};
    oit_ply_writer_add_vertices(w, xyz, NULL, 3, NULL, &err);
    oit_status s = oit_ply_writer_add_faces(w, idx, NULL, 1, &err);
    printf("bad index: %s\n", err.message);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, path), "status %d, message '%s'", s, err.message);
    CHECK(oit_ply_writer_close(w, NULL, &err) != OIT_OK, "close after a failure succeeded");
    CHECK(!exists(path) && no_temporaries(path), "files left after a failed write");
}

static void abort_leaves_nothing(void)
{
    char path[600];
    oit_ply_writer *w = open_fresh("writer_abort.ply", path);
    oit_error err = {0};
    float xyz[3] = {1, 2, 3};
    oit_ply_writer_add_vertices(w, xyz, NULL, 1, NULL, &err);
    oit_ply_writer_abort(w);
    CHECK(!exists(path) && no_temporaries(path), "files left after abort");
}

static void unwritable_path_is_named(void)
{
    char path[600];
    path_in_tmp(path, sizeof path, "no-such-dir/out.ply");
    oit_ply_writer_desc d = {.path = path};
    oit_ply_writer *w = (oit_ply_writer *)&d;
    oit_error err = {0};
    oit_status s = oit_ply_writer_open(&d, &w, &err);
    printf("unwritable: %s\n", err.message);
    CHECK(s == OIT_ERR_IO && w == NULL && strstr(err.message, "no-such-dir/out.ply"),
          "status %d, message '%s'", s, err.message);
}

int main(void)
{
    const char *t = getenv("OIT_TEST_TMP");
    snprintf(tmpdir, sizeof tmpdir, "%s", t ? t : "/tmp");
    round_trip(0, 0, 5, 3);
    round_trip(1, 1, 5, 3);
    /* Several times the 1 MiB write buffers, so flushes and the face append
     * loop run many times. */
    round_trip(1, 0, 150000, 300000);
    round_trip(0, 1, 70001, 140003);
    bad_index_leaves_nothing();
    abort_leaves_nothing();
    unwritable_path_is_named();
    return test_verdict();
}
