/* Unit tests of the PLY, OBJ, OFF and STL readers: small files of every
 * flavour are written under $OIT_TEST_TMP and read back; triangle counts,
 * coordinates, colours, attribute bits, bounds, chunking and every error path
 * (status, file name and line/offset in the message) are checked. */
#include "oit/mesh.h"
#include "tests/formats/test_tmp_files.h"
#include "tests/lib/test_check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Reads a file into m; prints the figures. */
static oit_status load(const char *name, const oit_read_desc *desc, oit_mesh *m, oit_error *err)
{
    err->message[0] = '\0';
    oit_status s = oit_mesh_load(tmp_path(name), desc, m, err);
    if (s == OIT_OK)
        printf("%-24s %4zu triangles (%llu faces, %llu vertices, %llu non-finite) attr=%u "
               "bounds [%g %g %g]..[%g %g %g]\n",
               name, m->count, (unsigned long long)m->info.faces_in,
               (unsigned long long)m->info.vertices_in,
               (unsigned long long)m->info.nonfinite_dropped, m->info.attributes,
               m->info.bounds_min[0], m->info.bounds_min[1], m->info.bounds_min[2],
               m->info.bounds_max[0], m->info.bounds_max[1], m->info.bounds_max[2]);
    else
        printf("%-24s %s: %s\n", name, oit_status_name(s), err->message);
    return s;
}

/* text written as name, then read into m, which must succeed. */
static void load_text(const char *name, const char *text, oit_mesh *m)
{
    oit_error err;
    write_text(name, text);
    CHECK(load(name, NULL, m, &err) == OIT_OK, "%s", err.message);
}

static int same_pos(const oit_vertex *v, float x, float y, float z)
{
    return v->pos[0] == x && v->pos[1] == y && v->pos[2] == z;
}

static int same_rgba(const oit_vertex *v, int r, int g, int b, int a)
{
    return v->rgba[0] == r && v->rgba[1] == g && v->rgba[2] == b && v->rgba[3] == a;
}

/* Expects failure with status s and a message naming the file and `where`
 * ("line 7" or "byte offset"). */
static void expect_error(const char *name, const char *text, size_t len, oit_status s,
                         const char *where)
{
    write_bytes(name, text, len ? len : strlen(text));
    oit_mesh m;
    oit_error err;
    oit_status got = load(name, NULL, &m, &err);
    CHECK(got == s, "%s: status %s, expected %s", name, oit_status_name(got), oit_status_name(s));
    CHECK(strstr(err.message, name) != NULL, "%s: message lacks the file name: %s", name,
          err.message);
    CHECK(strstr(err.message, where) != NULL, "%s: message lacks '%s': %s", name, where,
          err.message);
    oit_mesh_free(&m);
}

/* ---- PLY -------------------------------------------------------------- */

/* A unit square (two quads: z=0 and z=1 would be a cube; keep it small):
 * four vertices, one quad, fan-triangulated into (0,1,2) (0,2,3). */
static const char *ply_ascii =
    "ply\n"
    "format ascii 1.0\n"
    "comment unit square with an unknown element and unknown properties\n"
    "element vertex 4\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property list uchar float extra\n"
    "property uchar red\n"
    "property uchar green\n"
    "property uchar blue\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "property list uchar float texcoord\n"
    "end_header\n"
    "0 0 0 2 9 9 255 0 0\n"
    "1 0 0 0 0 255 0\n"
    "1 2 0 1 7 0 0 255\n"
    "0 2 0.5 0 10 20 30\n"
    "0 1\n"
    "4 0 1 2 3 2 0.5 0.5\n";

static void check_square(const oit_mesh *m, const char *what, int alpha)
{
    CHECK(m->count == 2, "%s: %zu triangles", what, m->count);
    if (m->count != 2)
        return;
    const oit_triangle *t = m->tris;
    CHECK(same_pos(&t[0].v[0], 0, 0, 0) && same_pos(&t[0].v[1], 1, 0, 0) &&
              same_pos(&t[0].v[2], 1, 2, 0),
          "%s: first triangle wrong", what);
    CHECK(same_pos(&t[1].v[0], 0, 0, 0) && same_pos(&t[1].v[1], 1, 2, 0) &&
              same_pos(&t[1].v[2], 0, 2, 0.5f),
          "%s: second (fan) triangle wrong", what);
    CHECK(same_rgba(&t[0].v[0], 255, 0, 0, alpha) && same_rgba(&t[0].v[1], 0, 255, 0, alpha) &&
              same_rgba(&t[1].v[2], 10, 20, 30, alpha),
          "%s: colours wrong (%d %d %d %d)", what, t[0].v[0].rgba[0], t[0].v[0].rgba[1],
          t[0].v[0].rgba[2], t[0].v[0].rgba[3]);
    CHECK(m->info.bounds_min[0] == 0 && m->info.bounds_max[1] == 2 && m->info.bounds_max[2] == 0.5f,
          "%s: bounds wrong", what);
}

static void put_f32(unsigned char **p, float f, int be)
{
    unsigned char b[4];
    memcpy(b, &f, 4);
    for (int i = 0; i < 4; i++)
        *(*p)++ = be ? b[3 - i] : b[i];
}

static void put_u32(unsigned char **p, uint32_t u, int be)
{
    for (int i = 0; i < 4; i++)
        *(*p)++ = (unsigned char)(be ? u >> (24 - 8 * i) : u >> (8 * i));
}

/* The same square in binary, with float colours (0..1) and alpha. */
static size_t ply_binary(unsigned char *buf, int be, uint32_t declared_vertices)
{
    unsigned char *p = buf;
    p += sprintf((char *)p,
                 "ply\nformat %s 1.0\nelement vertex %u\nproperty float x\nproperty float y\n"
                 "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
                 "property float alpha\nelement face 1\nproperty list int uint vertex_index\n"
                 "end_header\n",
                 be ? "binary_big_endian" : "binary_little_endian", declared_vertices);
    static const float v[4][7] = {{0, 0, 0, 1, 0, 0, 0.5f},
                                  {1, 0, 0, 0, 1, 0, 0.5f},
                                  {1, 2, 0, 0, 0, 1, 0.5f},
                                  {0, 2, 0.5f, 10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 0.5f}};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 7; k++)
            put_f32(&p, v[i][k], be);
    put_u32(&p, 4, be);
    for (uint32_t i = 0; i < 4; i++)
        put_u32(&p, i, be);
    return (size_t)(p - buf);
}

static void test_ply(void)
{
    oit_mesh m;
    oit_error err;
    load_text("square.ply", ply_ascii, &m);
    check_square(&m, "ascii ply", 255);
    CHECK(m.info.attributes == OIT_ATTR_COLOUR, "attributes %u", m.info.attributes);
    CHECK(m.info.faces_in == 1 && m.info.vertices_in == 4, "faces/vertices");
    oit_mesh_free(&m);

    unsigned char buf[4096];
    for (int be = 0; be < 2; be++) {
        const char *name = be ? "square_be.PLY" : "square_le.ply";
        write_bytes(name, buf, ply_binary(buf, be, 4));
        CHECK(load(name, NULL, &m, &err) == OIT_OK, "%s", err.message);
        check_square(&m, name, 128);
        CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA), "attributes %u",
              m.info.attributes);
        oit_mesh_free(&m);
    }

    /* Per-face colour overrides the vertex colour; a pentagon gives 3
     * triangles; a two-vertex face is skipped. */
    write_text("facecolor.ply",
               "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\n"
               "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
               "element face 2\nproperty list uchar int vertex_indices\nproperty uchar red\n"
               "property uchar green\nproperty uchar blue\nproperty uchar alpha\nend_header\n"
               "0 0 0 1 1 1\n1 0 0 1 1 1\n2 1 0 1 1 1\n1 2 0 1 1 1\n0 1 0 1 1 1\n"
               "5 0 1 2 3 4 200 100 50 25\n"
               "2 0 1 9 9 9 9\n");
    CHECK(load("facecolor.ply", NULL, &m, &err) == OIT_OK, "%s", err.message);
    CHECK(m.count == 3 && m.info.faces_in == 2, "%zu triangles", m.count);
    for (size_t i = 0; i < m.count; i++)
        for (int j = 0; j < 3; j++)
            CHECK(same_rgba(&m.tris[i].v[j], 200, 100, 50, 25), "face colour not applied");
    CHECK(m.count == 3 && same_pos(&m.tris[2].v[0], 0, 0, 0) && same_pos(&m.tris[2].v[1], 1, 2, 0) &&
              same_pos(&m.tris[2].v[2], 0, 1, 0),
          "fan order wrong");
    CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA), "attributes %u",
          m.info.attributes);
    oit_mesh_free(&m);

    const char *head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
    char text[1024];
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", head);
    expect_error("badindex.ply", text, 0, OIT_ERR_FORMAT, "line 13");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1\n", head);
    expect_error("shortface.ply", text, 0, OIT_ERR_FORMAT, "line");
    snprintf(text, sizeof text, "%s0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", head);
    expect_error("badnumber.ply", text, 0, OIT_ERR_FORMAT, "line 11");
    expect_error("badformat.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", 0,
                 OIT_ERR_FORMAT, "line 2");
    expect_error("noply.ply", "plx\n", 0, OIT_ERR_FORMAT, "line 1");
    size_t n = ply_binary(buf, 0, 4);
    expect_error("truncated.ply", (const char *)buf, n - 6, OIT_ERR_FORMAT, "byte offset");
    n = ply_binary(buf, 1, 5);
    expect_error("toomany.ply", (const char *)buf, n, OIT_ERR_FORMAT, "byte offset");

    /* A header claiming four billion vertices in a tiny file fails at once
     * without allocating for them. */
    clock_t t0 = clock();
    n = ply_binary(buf, 0, 4000000000u);
    expect_error("huge.ply", (const char *)buf, n, OIT_ERR_FORMAT, "byte offset");
    snprintf(text, sizeof text,
             "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
             "property float y\nproperty float z\nend_header\n0 0 0\n");
    expect_error("huge_ascii.ply", text, 0, OIT_ERR_FORMAT, "line");
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    printf("4e9-vertex headers refused in %.3f s\n", secs);
    CHECK(secs < 1.0, "took %.3f s", secs);

    snprintf(text, sizeof text,
             "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
             "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "end_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n");
    expect_error("facefirst.ply", text, 0, OIT_ERR_UNSUPPORTED, "line");
}

/* ---- OBJ -------------------------------------------------------------- */

/* load() with stderr caught in log (what the reader warned). */
static oit_status load_warned(const char *name, oit_mesh *m, oit_error *err, char *log,
                              size_t cap)
{
    fflush(stderr);
    int saved = dup(2);
    FILE *f = fopen(tmp_path("stderr.txt"), "w+");
    CHECK(saved >= 0 && f, "cannot redirect stderr");
    if (saved < 0 || !f)
        exit(1);
    dup2(fileno(f), 2);
    oit_status s = load(name, NULL, m, err);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(f);
    size_t n = fread(log, 1, cap - 1, f);
    log[n] = '\0';
    fclose(f);
    printf("%s stderr: %s", name, n ? log : "(nothing)\n");
    return s;
}

/* Bad material input: errors (status, file and line) for what cannot be
 * read, warnings naming the file and line for what is drawn anyway. */
static void test_mtl_errors(void)
{
    oit_mesh m;
    oit_error err;
    char log[4096];
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    char obj[512];

    /* A missing library: the read goes on, the OBJ's line is named, and
     * the first usemtl of a material it would have defined too. */
    snprintf(obj, sizeof obj, "%smtllib nolib.mtl\nusemtl red\nf 1 2 3\nusemtl blue\nf 1 2 3\n",
             tri);
    write_text("nolib.obj", obj);
    CHECK(load_warned("nolib.obj", &m, &err, log, sizeof log) == OIT_OK && m.count == 2, "%s",
          err.message);
    CHECK(strstr(log, "nolib.obj: line 4: material library ") && strstr(log, "nolib.mtl: "),
          "missing library not reported with its line: %s", log);
    CHECK(strstr(log, "nolib.obj: line 5: usemtl red: no such material"),
          "unknown material not reported with its line: %s", log);
    CHECK(!strstr(log, "usemtl blue"), "unknown materials reported more than once: %s", log);
    oit_mesh_free(&m);

    /* An unknown material in a library that was read; "usemtl" alone
     * (no material) is not news. */
    write_text("known.mtl", "newmtl red\nKd 1 0 0\n");
    snprintf(obj, sizeof obj, "mtllib known.mtl\n%susemtl\nf 1 2 3\nusemtl green\nf 1 2 3\n",
             tri);
    write_text("unknown.obj", obj);
    CHECK(load_warned("unknown.obj", &m, &err, log, sizeof log) == OIT_OK && m.count == 2, "%s",
          err.message);
    CHECK(strstr(log, "unknown.obj: line 7: usemtl green: no such material") &&
              !strstr(log, "line 5"),
          "unknown material: %s", log);
    CHECK(m.count == 2 && same_rgba(&m.tris[1].v[0], 255, 255, 255, 255),
          "an unknown material is not the default");
    oit_mesh_free(&m);

    /* Values outside 0..1 are clamped, the first of a library reported. */
    write_text("range.mtl", "newmtl over\nd 1.5\nnewmtl under\nKd 0.5 0.5 0.5\nTr -1\n");
    snprintf(obj, sizeof obj,
             "mtllib range.mtl\n%susemtl over\nf 1 2 3\nusemtl under\nf 1 2 3\n", tri);
    write_text("range_mtl.obj", obj);
    CHECK(load_warned("range_mtl.obj", &m, &err, log, sizeof log) == OIT_OK && m.count == 2, "%s",
          err.message);
    CHECK(strstr(log, "range.mtl: line 2: d 1.5 is outside 0..1; drawn as 1"),
          "d 1.5 not reported: %s", log);
    CHECK(!strstr(log, "line 5"), "more than one range warning a library: %s", log);
    CHECK(m.count == 2 && same_rgba(&m.tris[0].v[0], 255, 255, 255, 255) &&
              same_rgba(&m.tris[1].v[0], 128, 128, 128, 255),
          "d 1.5 or Tr -1 not clamped to opaque");
    oit_mesh_free(&m);
    write_text("tr.mtl", "newmtl a\nTr -1\n");
    snprintf(obj, sizeof obj, "mtllib tr.mtl\n%susemtl a\nf 1 2 3\n", tri);
    write_text("tr.obj", obj);
    CHECK(load_warned("tr.obj", &m, &err, log, sizeof log) == OIT_OK, "%s", err.message);
    CHECK(strstr(log, "tr.mtl: line 2: Tr -1 is outside 0..1; drawn as 0"), "Tr -1: %s", log);
    oit_mesh_free(&m);

    /* "d -halo f" is the specification's option, not a bad number. */
    write_text("halo.mtl", "newmtl a\nd -halo 0.25\n");
    snprintf(obj, sizeof obj, "mtllib halo.mtl\n%susemtl a\nf 1 2 3\n", tri);
    write_text("halo.obj", obj);
    CHECK(load_warned("halo.obj", &m, &err, log, sizeof log) == OIT_OK && m.count == 1 &&
              m.tris[0].v[0].rgba[3] == 64,
          "d -halo 0.25: %s", err.message);
    oit_mesh_free(&m);

    /* Malformed numbers: errors naming the library and its line. */
    static const struct {
        const char *mtl, *line, *what;
    } bad[] = {
        {"newmtl a\nKd 0.5 0.5\n", "line 2", "one or three numbers"},
        {"newmtl a\nKd 1 0 0\nd abc\n", "line 3", "'abc' is not a finite number"},
        {"newmtl a\nTr\n", "line 2", "'Tr' needs a number"},
        {"newmtl a\nKd nan 0 0\n", "line 2", "'nan' is not a finite number"},
        {"newmtl a\nd 1e999\n", "line 2", "not a finite number"},
        {"Kd 1 0 0\nnewmtl a\n", "line 1", "before any 'newmtl'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_text("bad.mtl", bad[i].mtl);
        snprintf(obj, sizeof obj, "mtllib bad.mtl\n%susemtl a\nf 1 2 3\n", tri);
        write_text("badmtl.obj", obj);
        oit_status s = load_warned("badmtl.obj", &m, &err, log, sizeof log);
        CHECK(s == OIT_ERR_FORMAT && strstr(err.message, "bad.mtl: ") &&
                  strstr(err.message, bad[i].line) && strstr(err.message, bad[i].what),
              "bad MTL %zu: %s: %s", i, oit_status_name(s), err.message);
        oit_mesh_free(&m);
    }

    /* A usemtl, then another mtllib (which grows the material table past
     * its first 8): the current material must survive the move (a pointer
     * into the table was read after free; tests/corpus/mtl has the input
     * libFuzzer found). */
    write_text("five.mtl", "newmtl a\nKd 1 0 0\nd 0.5\nnewmtl b\nnewmtl c\nnewmtl d\nnewmtl e\n");
    snprintf(obj, sizeof obj, "mtllib five.mtl\nusemtl a\nmtllib five.mtl\n%sf 1 2 3\n", tri);
    load_text("moved.obj", obj, &m);
    CHECK(m.count == 1 && same_rgba(&m.tris[0].v[0], 255, 0, 0, 128),
          "usemtl before a second mtllib lost its material");
    oit_mesh_free(&m);
}

static void test_obj(void)
{
    oit_mesh m;
    oit_error err;
    write_text("mat.mtl", "# materials\nnewmtl red\nKd 1 0 0\nd 0.5\n"
                          "newmtl glass\n  Kd 0 0 1\n  Tr 0.75\nnewmtl grey\nKd 0.2\n");
    write_text("square.obj",
               "# square, a pentagon and relative indices\n"
               "mtllib mat.mtl\n"
               "o thing\ng group\ns off\n"
               "v 0 0 0\nv 1 0 0\nv 1 2 0\nv 0 2 0.5\n"
               "vt 0 0\nvn 0 0 1\n"
               "usemtl red\n"
               "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
               "usemtl glass\n"
               "f -4//1 -3//1 \\\n -2//1\n"
               "usemtl grey\n"
               "f 1/1 3/1 4/1 # trailing comment\n"
               "usemtl nosuch\n"
               "f 2 3 4\n"
               "f 1 2\n");
    CHECK(load("square.obj", NULL, &m, &err) == OIT_OK, "%s", err.message);
    CHECK(m.count == 5 && m.info.faces_in == 5 && m.info.vertices_in == 4, "%zu triangles",
          m.count);
    if (m.count == 5) {
        const oit_triangle *t = m.tris;
        CHECK(same_pos(&t[1].v[0], 0, 0, 0) && same_pos(&t[1].v[1], 1, 2, 0) &&
                  same_pos(&t[1].v[2], 0, 2, 0.5f),
              "quad fan wrong");
        CHECK(same_rgba(&t[0].v[0], 255, 0, 0, 128), "Kd/d not applied");
        CHECK(same_pos(&t[2].v[0], 0, 0, 0) && same_pos(&t[2].v[2], 1, 2, 0),
              "negative indices or continuation wrong");
        CHECK(same_rgba(&t[2].v[1], 0, 0, 255, 64), "Tr not applied: %d %d %d %d",
              t[2].v[1].rgba[0], t[2].v[1].rgba[1], t[2].v[1].rgba[2], t[2].v[1].rgba[3]);
        CHECK(same_rgba(&t[3].v[0], 51, 51, 51, 255), "single-value Kd not grey");
        CHECK(same_rgba(&t[4].v[0], 255, 255, 255, 255), "unknown material not default");
    }
    /* grey and nosuch have alpha 1 (MTL's default d): opaque triangles */
    CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE),
          "attributes %u", m.info.attributes);
    oit_mesh_free(&m);

    /* Only materials below alpha 1: alpha without opaque triangles. */
    write_text("glass.mtl", "newmtl g\nKd 0 0 1\nd 0.4\n");
    load_text("glass.obj", "mtllib glass.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl g\nf 1 2 3\n", &m);
    CHECK(m.count == 1 && same_rgba(&m.tris[0].v[0], 0, 0, 255, 102), "d 0.4");
    CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA), "attributes %u",
          m.info.attributes);
    oit_mesh_free(&m);

    /* Vertex colours; a missing material library is not fatal. */
    load_text("vcolor.obj",
              "mtllib missing.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\n"
              "v 0 1 0 0 0 1\nusemtl red\nf 1 2 3\n",
              &m);
    CHECK(m.count == 1 && same_rgba(&m.tris[0].v[1], 0, 255, 0, 255), "vertex colour");
    CHECK(m.info.attributes == OIT_ATTR_COLOUR, "attributes %u", m.info.attributes);
    oit_mesh_free(&m);

    expect_error("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 0, OIT_ERR_FORMAT, "line 4");
    expect_error("range.obj", "v 0 0 0\nv 1 0 0\n\nf 1 2 3\nv 0 1 0\n", 0, OIT_ERR_FORMAT,
                 "line 4");
    expect_error("negrange.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 0, OIT_ERR_FORMAT,
                 "line 4");
    expect_error("badv.obj", "v 0 0 0\nv 1 x 0\n", 0, OIT_ERR_FORMAT, "line 2");
    expect_error("badf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", 0, OIT_ERR_FORMAT, "line 4");
    write_text("badlib.mtl", "newmtl a\nKd 1 zero 0\n");
    write_text("badlib.obj", "mtllib badlib.mtl\nv 0 0 0\n");
    oit_status s = load("badlib.obj", NULL, &m, &err);
    CHECK(s == OIT_ERR_FORMAT && strstr(err.message, "badlib.mtl: line 2"), "%s", err.message);
    oit_mesh_free(&m);
}

/* ---- OFF -------------------------------------------------------------- */

static void test_off(void)
{
    oit_mesh m;
    load_text("square.off",
              "OFF # unit square\n\n# counts\n4 1 0\n0 0 0\n1 0 0\n1 2 0\n"
              "0 2 0.5 # last vertex\n4 0 1 2 3\n",
              &m);
    CHECK(m.count == 2 && m.info.attributes == 0, "%zu triangles attr %u", m.count,
          m.info.attributes);
    CHECK(m.count == 2 && same_pos(&m.tris[1].v[2], 0, 2, 0.5f) &&
              same_rgba(&m.tris[1].v[2], 255, 255, 255, 255),
          "plain OFF wrong");
    oit_mesh_free(&m);

    /* COFF with integer vertex colours, a face with float colour (override)
     * and one without (keeps vertex colours). */
    load_text("color.off",
              "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
              "1 2 0 0 0 255 255\n0 2 0 10 20 30 40\n"
              "3 0 1 2 0.0 0.5 1.0 1.0\n3 0 2 3\n",
              &m);
    CHECK(m.count == 2, "%zu triangles", m.count);
    if (m.count == 2) {
        CHECK(same_rgba(&m.tris[0].v[0], 0, 128, 255, 255), "face colour");
        CHECK(same_rgba(&m.tris[1].v[2], 10, 20, 30, 40), "vertex colour");
    }
    /* the first face has alpha 255 at its three corners */
    CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE),
          "attributes %u", m.info.attributes);
    oit_mesh_free(&m);

    load_text("normals.off",
              "CNOFF 3 1 0\n0 0 0 0 0 1 1 0 0\n1 0 0 0 0 1 0 1 0\n"
              "0 1 0 0 0 1 0 0 1\n3 0 1 2\n",
              &m);
    CHECK(m.count == 1 && same_rgba(&m.tris[0].v[1], 0, 255, 0, 255) &&
              same_pos(&m.tris[0].v[1], 1, 0, 0) && m.info.attributes == OIT_ATTR_COLOUR,
          "CNOFF wrong");
    oit_mesh_free(&m);

    /* NaN and inf vertices: triangles that touch them are dropped and counted. */
    load_text("nan.off",
              "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\nnan 0 0\n0 inf 0\n"
              "3 0 1 2\n3 0 1 3\n3 4 1 2\n",
              &m);
    CHECK(m.count == 1 && m.info.nonfinite_dropped == 2 && m.info.faces_in == 3,
          "%zu kept, %llu dropped", m.count, (unsigned long long)m.info.nonfinite_dropped);
    CHECK(m.info.bounds_max[0] == 1 && m.info.bounds_max[1] == 1, "bounds include a dropped vertex");
    oit_mesh_free(&m);

    expect_error("trunc.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", 0, OIT_ERR_FORMAT, "line 4");
    expect_error("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 0, OIT_ERR_FORMAT,
                 "line 6");
    expect_error("counts.off", "OFF\nthree 1 0\n", 0, OIT_ERR_FORMAT, "line 2");
    expect_error("facetrunc.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, OIT_ERR_FORMAT,
                 "line 6");
}

/* ---- STL -------------------------------------------------------------- */

static size_t stl_binary(unsigned char *buf, const char *header, uint32_t n, uint32_t declared)
{
    memset(buf, 0, 84);
    memcpy(buf, header, strlen(header));
    unsigned char *p = buf + 80;
    put_u32(&p, declared, 0);
    for (uint32_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++)
            put_f32(&p, 0, 0); /* normal */
        float v[9] = {0, 0, (float)i, 1, 0, (float)i, 0, 1, (float)i};
        for (int k = 0; k < 9; k++)
            put_f32(&p, v[k], 0);
        *p++ = 0;
        *p++ = 0;
    }
    return (size_t)(p - buf);
}

static void test_stl(void)
{
    oit_mesh m;
    oit_error err;
    unsigned char buf[2048];
    /* Binary, but its header starts with "solid": size decides. */
    write_bytes("solid_binary.stl", buf, stl_binary(buf, "solid fooled you", 3, 3));
    CHECK(load("solid_binary.stl", NULL, &m, &err) == OIT_OK, "%s", err.message);
    CHECK(m.count == 3 && same_pos(&m.tris[2].v[1], 1, 0, 2) && m.info.attributes == 0 &&
              m.info.bounds_max[2] == 2,
          "binary STL wrong");
    oit_mesh_free(&m);

    load_text("ascii.stl",
              "solid square\n  facet normal 0 0 1\n    outer loop\n"
              "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 2 0\n"
              "    endloop\n  endfacet\n  FACET NORMAL 0 0 1\n    OUTER LOOP\n"
              "      VERTEX 0 0 0\n      VERTEX 1 2 0\n      VERTEX 0 2 0.5\n"
              "      vertex 0 1 0.5\n    ENDLOOP\n  ENDFACET\nendsolid square\n",
              &m);
    CHECK(m.count == 3 && same_pos(&m.tris[1].v[2], 0, 2, 0.5f) &&
              same_pos(&m.tris[2].v[2], 0, 1, 0.5f),
          "ascii STL wrong");
    oit_mesh_free(&m);

    expect_error("wrongsize.stl", (const char *)buf, stl_binary(buf, "binary", 3, 4),
                 OIT_ERR_FORMAT, "byte offset 80");
    /* More records than declared: trailing bytes are not silently dropped. */
    expect_error("trailing.stl", (const char *)buf, stl_binary(buf, "binary", 3, 2),
                 OIT_ERR_FORMAT, "declares 2 triangles");
    expect_error("trunc.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", 0,
                 OIT_ERR_FORMAT, "line 4");
    expect_error("badvertex.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n", 0,
                 OIT_ERR_FORMAT, "line 4");
    expect_error("short.stl", "abc", 0, OIT_ERR_FORMAT, "byte offset");
}

/* ---- chunking, budget, dispatch -------------------------------------- */

typedef struct chunk_count {
    size_t calls, total, largest;
} chunk_count;

static oit_status count_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    chunk_count *c = user;
    c->calls++;
    c->total += n;
    if (n > c->largest)
        c->largest = n;
    return OIT_OK;
}

static oit_status stop_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return oit_error_set(err, OIT_ERR_CALLBACK, "stop");
}

static void test_stream(void)
{
    /* A grid of 20x20 quads in OFF: 800 triangles. */
    size_t cap = 64 * 1024, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "OFF\n441 400 0\n");
    for (int y = 0; y <= 20; y++)
        for (int x = 0; x <= 20; x++)
            len += (size_t)snprintf(text + len, cap - len, "%d %d 0\n", x, y);
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 20; x++) {
            int a = y * 21 + x;
            len += (size_t)snprintf(text + len, cap - len, "4 %d %d %d %d\n", a, a + 1, a + 22,
                                    a + 21);
        }
    write_bytes("grid.off", text, len);
    free(text);

    chunk_count cc = {0};
    oit_read_desc desc = {.chunk_triangles = 64};
    oit_mesh_info info;
    oit_error err;
    oit_status s = oit_mesh_read(tmp_path("grid.off"), &desc, count_sink, &cc, &info, &err);
    printf("grid.off: %zu triangles in %zu chunks (largest %zu)\n", cc.total, cc.calls, cc.largest);
    CHECK(s == OIT_OK && cc.total == 800 && info.triangles == 800, "%s", err.message);
    CHECK(cc.calls == 13 && cc.largest == 64, "chunking wrong");
    CHECK(info.bounds_max[0] == 20 && info.bounds_max[1] == 20 && info.bounds_min[0] == 0,
          "bounds wrong");

    s = oit_mesh_read(tmp_path("grid.off"), NULL, stop_sink, NULL, NULL, &err);
    CHECK(s == OIT_ERR_CALLBACK, "sink status not passed through: %s", oit_status_name(s));

    /* 12 KiB minus the 4 KiB input buffer and the 3 KiB chunk leave room for
     * 320 of the 441 vertices (16 bytes each). */
    desc.memory_budget = 12288;
    s = oit_mesh_read(tmp_path("grid.off"), &desc, count_sink, &cc, NULL, &err);
    printf("budget 12 KiB: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_NOMEM && strstr(err.message, "grid.off") && strstr(err.message, "budget"),
          "%s", err.message);

    s = oit_mesh_read(tmp_path("grid.xyz"), NULL, count_sink, &cc, NULL, &err);
    CHECK(s == OIT_ERR_UNSUPPORTED, "unknown extension: %s", oit_status_name(s));
    s = oit_mesh_read(tmp_path("absent.stl"), NULL, count_sink, &cc, NULL, &err);
    CHECK(s == OIT_ERR_IO && strstr(err.message, "absent.stl"), "missing file: %s", err.message);
}

/* Files larger than the 1 MiB input buffer: lines, tokens and long
 * comments (2 MiB, 1.2 MB) straddle buffer refills and force the buffer to grow. */
static void test_large(void)
{
    const int n = 150; /* 151^2 vertices, 2 * 150^2 triangles */
    size_t cap = 8u << 20, len = 0;
    char *off = malloc(cap), *ply = malloc(cap);
    size_t plen = 0;
    len += (size_t)snprintf(off, cap, "OFF\n#");
    memset(off + len, 'x', 2u << 20);
    len += 2u << 20;
    len += (size_t)snprintf(off + len, cap - len, "\n%d %d 0\n", (n + 1) * (n + 1), n * n);
    plen += (size_t)snprintf(ply, cap, "ply\nformat ascii 1.0\ncomment ");
    memset(ply + plen, 'y', 1200000);
    plen += 1200000;
    plen += (size_t)snprintf(ply + plen, cap - plen, "\nelement vertex %d\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "element face %d\nproperty list uchar int vertex_indices\n"
                             "end_header\n", (n + 1) * (n + 1), n * n);
    for (int y = 0; y <= n; y++)
        for (int x = 0; x <= n; x++) {
            len += (size_t)snprintf(off + len, cap - len, "%d.25 %d.5 0.125\n", x, y);
            plen += (size_t)snprintf(ply + plen, cap - plen, "%d.25 %d.5\n0.125 ", x, y);
        }
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            int a = y * (n + 1) + x;
            len += (size_t)snprintf(off + len, cap - len, "4 %d %d %d %d\n", a, a + 1,
                                    a + n + 2, a + n + 1);
            plen += (size_t)snprintf(ply + plen, cap - plen, "4 %d %d\n%d %d ", a, a + 1,
                                     a + n + 2, a + n + 1);
        }
    write_bytes("large.off", off, len);
    write_bytes("large.ply", ply, plen);
    free(off);
    free(ply);
    const char *names[] = {"large.off", "large.ply"};
    for (int i = 0; i < 2; i++) {
        oit_mesh m;
        oit_error err;
        CHECK(load(names[i], NULL, &m, &err) == OIT_OK, "%s", err.message);
        CHECK(m.count == (size_t)2 * n * n, "%s: %zu triangles", names[i], m.count);
        CHECK(m.info.bounds_min[0] == 0.25f && m.info.bounds_max[0] == n + 0.25f &&
                  m.info.bounds_max[1] == n + 0.5f && m.info.bounds_max[2] == 0.125f,
              "%s: bounds wrong", names[i]);
        double area = 0; /* each triangle has area 1/2: catches a shuffled index */
        for (size_t t = 0; t < m.count; t++) {
            const float *p0 = m.tris[t].v[0].pos, *p1 = m.tris[t].v[1].pos, *p2 = m.tris[t].v[2].pos;
            area += fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])) / 2;
        }
        printf("%s: total area %.3f (expected %d)\n", names[i], area, n * n);
        CHECK(fabs(area - n * n) < 1e-6, "%s: area %.3f", names[i], area);
        oit_mesh_free(&m);
    }
}

/* Georeferenced input: positions near 1e7 with centimetre detail keep it,
 * relative to an origin picked from the first vertex (oit_mesh_origin_pick);
 * a model near zero keeps origin 0. Text formats parse doubles, so the same
 * holds for OBJ and OFF as for double PLY. */
static void test_far(void)
{
    oit_mesh m;
    oit_error err;
    write_text("far.obj", "v 10000000.25 -4000000 12\nv 10000000.26 -4000000 12\n"
                          "v 10000000.25 -3999999.99 12.01\nf 1 2 3\n");
    write_text("far.off", "OFF\n3 1 0\n65536 0 -70000.5\n65536.01 0 -70000.5\n"
                          "65536 0.01 -70000.5\n3 0 1 2\n");
    write_text("near.off", "OFF\n3 1 0\n65535 0 0\n65535.01 0 0\n65535 0.01 0\n3 0 1 2\n");
    CHECK(load("far.obj", NULL, &m, &err) == OIT_OK && m.count == 1, "%s", err.message);
    if (m.count == 1) {
        printf("  far.obj origin (%.17g %.17g %.17g)\n", m.info.origin[0], m.info.origin[1],
               m.info.origin[2]);
        CHECK(m.info.origin[0] == 1e7 && m.info.origin[1] == -4e6 && m.info.origin[2] == 0,
              "far.obj: origin not picked from the first vertex");
        const float *a = m.tris[0].v[0].pos, *b = m.tris[0].v[1].pos, *c = m.tris[0].v[2].pos;
        CHECK(a[0] == 0.25f && fabsf(b[0] - 0.26f) < 1e-6f && fabsf(c[1] - 0.01f) < 1e-6f &&
                  c[2] == 12.01f, "far.obj: centimetre detail lost");
    }
    oit_mesh_free(&m);
    CHECK(load("far.off", NULL, &m, &err) == OIT_OK && m.count == 1, "%s", err.message);
    if (m.count == 1)
        CHECK(m.info.origin[0] == 65536 && m.info.origin[1] == 0 && m.info.origin[2] == -70000 &&
                  fabsf(m.tris[0].v[1].pos[0] - 0.01f) < 1e-6f && m.tris[0].v[0].pos[2] == -0.5f,
              "far.off: origin (%g %g %g)", m.info.origin[0], m.info.origin[1], m.info.origin[2]);
    oit_mesh_free(&m);
    CHECK(load("near.off", NULL, &m, &err) == OIT_OK && m.count == 1, "%s", err.message);
    if (m.count == 1)
        CHECK(m.info.origin[0] == 0 && m.tris[0].v[0].pos[0] == 65535.0f,
              "near.off: a model within 2^16 of zero must not move");
    oit_mesh_free(&m);
}

int main(void)
{
    test_ply();
    test_obj();
    test_mtl_errors();
    test_off();
    test_stl();
    test_far();
    test_stream();
    test_large();
    return test_verdict();
}
