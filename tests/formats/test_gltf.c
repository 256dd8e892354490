/* glTF reader: a small scene written as .gltf (embedded base64 buffer) and as
 * .glb under $OIT_TEST_TMP, read back through oit_read_gltf.
 *
 * The scene has a node tree with translation, scale, quaternion rotation and
 * a matrix; an indexed (u16) list with a BLEND material, a non-indexed
 * triangle with normalized u8 COLOR_0, a u8-indexed strip with an OPAQUE
 * material whose alpha must be ignored, a line primitive that must be
 * skipped, an interleaved (strided) position view shared by two primitives,
 * and a second, non-default scene that must not be drawn. Every expected
 * world-space vertex is worked out by hand below. Malformed variants must
 * fail with OIT_ERR_FORMAT and name the file. */
#include "oit/mesh.h"
#include "tests/lib/test_check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* ------------------------------------------------------------ the scene */

static const char scene_json[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,"
    "\"scenes\":[{\"nodes\":[0]},{\"nodes\":[4]}],"
    "\"nodes\":["
    "{\"translation\":[10,0,0],\"children\":[1,2]},"
    "{\"scale\":[2,2,2],\"mesh\":0},"
    "{\"rotation\":[0,0,0.70710678118654752,0.70710678118654752],\"mesh\":1,\"children\":[3]},"
    "{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,5,1],\"mesh\":2},"
    "{\"mesh\":0}],"
    "\"meshes\":["
    "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]},"
    "{\"primitives\":[{\"attributes\":{\"POSITION\":2,\"COLOR_0\":3}}]},"
    "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":4,\"mode\":5,\"material\":1},"
    "{\"attributes\":{\"POSITION\":0},\"mode\":1}]}],"
    "\"materials\":["
    "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.2,0.5]},\"alphaMode\":\"BLEND\"},"
    "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.25,0.25,0.25,0.3]}}],"
    "\"accessors\":["
    "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
    "{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":3,\"componentType\":5121,\"normalized\":true,\"count\":3,\"type\":\"VEC4\"},"
    "{\"bufferView\":4,\"componentType\":5121,\"count\":4,\"type\":\"SCALAR\"}],"
    "\"bufferViews\":["
    "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":64,\"byteStride\":16},"
    "{\"buffer\":0,\"byteOffset\":64,\"byteLength\":12},"
    "{\"buffer\":0,\"byteOffset\":80,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":116,\"byteLength\":12},"
    "{\"buffer\":0,\"byteOffset\":128,\"byteLength\":4}],"
    "\"buffers\":[{\"byteLength\":132BUFFER_URI}]}";

enum { BUF_SIZE = 132 };

static void put_f32(uint8_t *p, float v) { memcpy(p, &v, 4); } /* little-endian host */

static void make_buffer(uint8_t buf[BUF_SIZE])
{
    static const float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    static const float tri[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    static const uint16_t list[6] = {0, 1, 2, 0, 2, 3};
    static const uint8_t colors[12] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0};
    static const uint8_t strip[4] = {1, 2, 0, 3};
    memset(buf, 0xAB, BUF_SIZE); /* stride padding must never be read */
    for (int v = 0; v < 4; v++)
        for (int k = 0; k < 3; k++)
            put_f32(buf + 16 * v + 4 * k, quad[v][k]);
    memcpy(buf + 64, list, sizeof list);
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++)
            put_f32(buf + 80 + 12 * v + 4 * k, tri[v][k]);
    memcpy(buf + 116, colors, sizeof colors);
    memcpy(buf + 128, strip, sizeof strip);
}

/* ------------------------------------------------------- file writers */

static char *base64(const uint8_t *p, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *out = malloc(4 * ((n + 2) / 3) + 1), *o = out;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16 | (i + 1 < n ? p[i + 1] << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        *o++ = tab[v >> 18 & 63];
        *o++ = tab[v >> 12 & 63];
        *o++ = i + 1 < n ? tab[v >> 6 & 63] : '=';
        *o++ = i + 2 < n ? tab[v & 63] : '=';
    }
    *o = 0;
    return out;
}

/* A copy of s with the one occurrence of `from` replaced; a missing or
 * repeated `from` is a bug in the test, reported as a failure. */
static char *replace(const char *s, const char *from, const char *to)
{
    const char *at = strstr(s, from);
    if (!at || strstr(at + 1, from)) {
        fprintf(stderr, "FAIL: test edit \"%s\" matches %s\n", from, at ? "twice" : "nothing");
        test_failures++;
        return strdup(s);
    }
    size_t head = (size_t)(at - s), nf = strlen(from), nt = strlen(to);
    char *out = malloc(strlen(s) - nf + nt + 1);
    memcpy(out, s, head);
    memcpy(out + head, to, nt);
    strcpy(out + head + nt, at + nf);
    return out;
}

static char *embedded_json(const char *json, const uint8_t *buf)
{
    char *b64 = base64(buf, BUF_SIZE);
    char *uri = malloc(strlen(b64) + 64);
    sprintf(uri, ",\"uri\":\"data:application/octet-stream;base64,%s\"", b64);
    char *out = replace(json, "BUFFER_URI", uri);
    free(b64);
    free(uri);
    return out;
}

static void write_file(const char *path, const void *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(p, 1, n, f) != n) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(1);
    }
    fclose(f);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int k = 0; k < 4; k++)
        p[k] = (uint8_t)(v >> (8 * k));
}

/* GLB 2.0: 12-byte header, JSON chunk padded with spaces, BIN chunk padded
 * with zeros. truncate cuts that many bytes off the end. */
static void write_glb(const char *path, const char *json_tpl, const uint8_t *buf, size_t truncate)
{
    char *json = replace(json_tpl, "BUFFER_URI", "");
    size_t nj = (strlen(json) + 3) & ~(size_t)3, nb = (BUF_SIZE + 3) & ~(size_t)3;
    size_t total = 12 + 8 + nj + 8 + nb;
    uint8_t *out = calloc(1, total);
    memcpy(out, "glTF", 4);
    put_u32(out + 4, 2);
    put_u32(out + 8, (uint32_t)total);
    put_u32(out + 12, (uint32_t)nj);
    put_u32(out + 16, 0x4E4F534A);
    memset(out + 20, ' ', nj);
    memcpy(out + 20, json, strlen(json));
    put_u32(out + 20 + nj, (uint32_t)nb);
    put_u32(out + 24 + nj, 0x004E4942);
    memcpy(out + 28 + nj, buf, BUF_SIZE);
    write_file(path, out, total - truncate);
    free(out);
    free(json);
}

/* ------------------------------------------------------------ reading */

typedef struct collect {
    oit_mesh mesh;
    size_t calls, max_chunk;
} collect;

static oit_status collect_sink(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    collect *c = user;
    c->calls++;
    if (n > c->max_chunk)
        c->max_chunk = n;
    return oit_mesh_append(&c->mesh, t, n, err);
}

static oit_status read_path(const char *path, size_t chunk, collect *c, oit_mesh_info *info,
                            oit_error *err)
{
    memset(c, 0, sizeof *c);
    oit_read_desc desc = {.chunk_triangles = chunk};
    return oit_read_gltf(path, &desc, collect_sink, c, info, err);
}

static double srgb(double linear)
{
    double v = linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1 / 2.4) - 0.055;
    return v * 255.0;
}

typedef struct expect {
    float pos[3][3];
    double rgba[4]; /* 0..255 */
} expect;

static void check_scene(const char *label, const collect *c, const oit_mesh_info *info)
{
    const double blend[4] = {srgb(1.0), srgb(0.5), srgb(0.2), 0.5 * 255};
    const double opaque[4] = {srgb(0.25), srgb(0.25), srgb(0.25), 255};
    /* node1: T(10,0,0) * S(2); node2: T(10,0,0) * Rz(90); node3: that * T(0,0,5). */
    const expect want[5] = {
        {{{10, 0, 0}, {12, 0, 0}, {12, 2, 0}}, {blend[0], blend[1], blend[2], blend[3]}},
        {{{10, 0, 0}, {12, 2, 0}, {10, 2, 0}}, {blend[0], blend[1], blend[2], blend[3]}},
        {{{10, 0, 0}, {10, 1, 0}, {9, 0, 0}}, {-1, -1, -1, 255}}, /* per-vertex, below */
        {{{10, 1, 5}, {9, 1, 5}, {10, 0, 5}}, {opaque[0], opaque[1], opaque[2], opaque[3]}},
        {{{10, 0, 5}, {9, 1, 5}, {9, 0, 5}}, {opaque[0], opaque[1], opaque[2], opaque[3]}},
    };
    const uint8_t tri_rgb[3][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}};
    printf("%s: %zu triangles in %zu sink calls (largest %zu), %llu vertices, attributes %u\n", label,
           c->mesh.count, c->calls, c->max_chunk, (unsigned long long)info->vertices_in,
           info->attributes);
    CHECK(c->mesh.count == 5 && info->triangles == 5, "%s: %zu triangles, want 5", label, c->mesh.count);
    /* the OPAQUE material gives alpha 1: opaque triangles (view/render/image/shade.h) */
    CHECK(info->attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE),
          "%s: attributes %u", label, info->attributes);
    CHECK(info->bounds_min[0] == 9 && info->bounds_max[0] == 12 && info->bounds_max[2] == 5,
          "%s: bounds x %g..%g, z max %g", label, info->bounds_min[0], info->bounds_max[0],
          info->bounds_max[2]);
    for (size_t t = 0; t < 5 && t < c->mesh.count; t++)
        for (int v = 0; v < 3; v++) {
            const oit_vertex *got = &c->mesh.tris[t].v[v];
            for (int k = 0; k < 3; k++)
                CHECK(fabsf(got->pos[k] - want[t].pos[v][k]) < 1e-5f,
                      "%s: triangle %zu vertex %d axis %d = %g, want %g", label, t, v, k, got->pos[k],
                      want[t].pos[v][k]);
            for (int k = 0; k < 4; k++) {
                double w = want[t].rgba[k] >= 0 ? want[t].rgba[k] : tri_rgb[v][k];
                CHECK(fabs(got->rgba[k] - w) <= 1.0, "%s: triangle %zu vertex %d channel %d = %u, want %.1f",
                      label, t, v, k, got->rgba[k], w);
            }
            if (t == 0 && v == 0)
                printf("%s: first vertex (%g %g %g) rgba %u %u %u %u\n", label, got->pos[0], got->pos[1],
                       got->pos[2], got->rgba[0], got->rgba[1], got->rgba[2], got->rgba[3]);
        }
}

static void check_fails(const char *dir, const char *file, const char *content, size_t n,
                        oit_status want, const char *why)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    write_file(path, content, n);
    collect c;
    oit_mesh_info info;
    oit_error err = {0};
    oit_status s = read_path(path, 0, &c, &info, &err);
    printf("%-28s %-20s -> %s: %s\n", file, why, oit_status_name(s), err.message);
    CHECK(s == want, "%s (%s): status %s, want %s", file, why, oit_status_name(s), oit_status_name(want));
    CHECK(strstr(err.message, file) != NULL, "%s: message does not name the file: %s", file, err.message);
    oit_mesh_free(&c.mesh);
}

static void check_fails_json(const char *dir, const char *file, const char *from, const char *to,
                             const uint8_t *buf, const char *why)
{
    char *edited = replace(scene_json, from, to);
    char *json = embedded_json(edited, buf);
    check_fails(dir, file, json, strlen(json), OIT_ERR_FORMAT, why);
    free(json);
    free(edited);
}

static void malformed(const char *dir, const uint8_t *buf)
{
    check_fails_json(dir, "overrun.gltf", "\"count\":4,\"type\":\"VEC3\"", "\"count\":5,\"type\":\"VEC3\"",
                     buf, "accessor overrun");
    check_fails_json(dir, "view.gltf", "\"byteOffset\":128,\"byteLength\":4", "\"byteOffset\":128,\"byteLength\":40",
                     buf, "bufferView overrun");
    check_fails_json(dir, "cycle.gltf", "\"mesh\":2}", "\"mesh\":2,\"children\":[0]}", buf, "node cycle");
    check_fails_json(dir, "nomesh.gltf", "\"scale\":[2,2,2],\"mesh\":0", "\"scale\":[2,2,2],\"mesh\":9", buf,
                     "missing mesh");
    check_fails_json(dir, "stride.gltf", "\"byteStride\":16", "\"byteStride\":8", buf, "stride < element");

    uint8_t bad[BUF_SIZE];
    memcpy(bad, buf, BUF_SIZE);
    bad[64 + 10] = 7; /* last u16 list index: 7 of 4 vertices */
    char *json = embedded_json(scene_json, bad);
    check_fails(dir, "index.gltf", json, strlen(json), OIT_ERR_FORMAT, "index out of range");
    check_fails(dir, "cut.gltf", json, strlen(json) / 2, OIT_ERR_FORMAT, "truncated JSON");
    free(json);

    char *ext = replace(scene_json, "BUFFER_URI", ",\"uri\":\"missing.bin\"");
    check_fails(dir, "extbuf.gltf", ext, strlen(ext), OIT_ERR_FORMAT, "missing .bin");
    free(ext);

    char path[1024];
    snprintf(path, sizeof path, "%s/cut.glb", dir);
    write_glb(path, scene_json, buf, 40);
    FILE *f = fopen(path, "rb");
    char glb[4096];
    size_t n = fread(glb, 1, sizeof glb, f);
    fclose(f);
    check_fails(dir, "cut.glb", glb, n, OIT_ERR_FORMAT, "truncated GLB");

    check_fails(dir, "junk.glb", "glTF\2\0\0\0\377\377\377\377junk", 16, OIT_ERR_FORMAT, "bad GLB length");
}

/* tests/corpus/gltf/draco.{gltf,glb}: one KHR_draco_mesh_compression
 * primitive of 2CylinderEngine (its index accessor declares 123 indices),
 * rotated, with a BLEND material; embedded and GLB must agree bit for bit. */
static void check_draco(const char *corpus)
{
    char path[2][1024];
    collect c[2];
    oit_mesh_info info[2];
    for (int i = 0; i < 2; i++) {
        oit_error err = {0};
        snprintf(path[i], sizeof path[i], "%s/draco.%s", corpus, i ? "glb" : "gltf");
        oit_status s = read_path(path[i], 16, &c[i], &info[i], &err);
        CHECK(s == OIT_OK, "%s: %s", path[i], err.message);
        printf("draco %s: %zu triangles, %llu vertices, bounds %g %g %g  %g %g %g, first rgba %u %u %u %u\n",
               i ? "glb" : "gltf", c[i].mesh.count, (unsigned long long)info[i].vertices_in,
               info[i].bounds_min[0], info[i].bounds_min[1], info[i].bounds_min[2], info[i].bounds_max[0],
               info[i].bounds_max[1], info[i].bounds_max[2], c[i].mesh.count ? c[i].mesh.tris[0].v[0].rgba[0] : 0,
               c[i].mesh.count ? c[i].mesh.tris[0].v[0].rgba[1] : 0,
               c[i].mesh.count ? c[i].mesh.tris[0].v[0].rgba[2] : 0,
               c[i].mesh.count ? c[i].mesh.tris[0].v[0].rgba[3] : 0);
    }
    CHECK(c[0].mesh.count == 123 / 3, "draco: %zu triangles, want 41", c[0].mesh.count);
    CHECK(c[0].mesh.count == c[1].mesh.count &&
              !memcmp(c[0].mesh.tris, c[1].mesh.tris, c[0].mesh.count * sizeof(oit_triangle)),
          "draco: .gltf and .glb triangles differ");
    CHECK(c[0].mesh.count && fabs(c[0].mesh.tris[0].v[0].rgba[3] - 0.4 * 255) <= 1.0 &&
              fabs(c[0].mesh.tris[0].v[0].rgba[2] - srgb(0.9)) <= 1.0,
          "draco: material colour not applied");
    CHECK(info[0].attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA), "draco: attributes %u", info[0].attributes);
    oit_mesh_free(&c[0].mesh);
    oit_mesh_free(&c[1].mesh);
}

int main(int argc, char **argv)
{
    const char *dir = getenv("OIT_TEST_TMP");
    if (!dir)
        dir = ".";
    uint8_t buf[BUF_SIZE];
    make_buffer(buf);
    char gltf[1024], glb[1024];
    snprintf(gltf, sizeof gltf, "%s/scene.gltf", dir);
    snprintf(glb, sizeof glb, "%s/scene.glb", dir);
    char *json = embedded_json(scene_json, buf);
    write_file(gltf, json, strlen(json));
    free(json);
    write_glb(glb, scene_json, buf, 0);

    collect c;
    oit_mesh_info info;
    oit_error err = {0};
    const char *paths[2] = {gltf, glb};
    for (int i = 0; i < 2; i++) {
        oit_status s = read_path(paths[i], 2, &c, &info, &err);
        CHECK(s == OIT_OK, "%s: %s", paths[i], err.message);
        CHECK(c.max_chunk <= 2, "%s: chunk of %zu triangles, asked for 2", paths[i], c.max_chunk);
        check_scene(i ? "glb" : "gltf", &c, &info);
        oit_mesh_free(&c.mesh);
    }

    /* Without a default scene every scene is drawn: node 4 adds the quad. */
    char *noscene = replace(scene_json, "\"scene\":0,", "");
    json = embedded_json(noscene, buf);
    char path[1024];
    snprintf(path, sizeof path, "%s/allscenes.gltf", dir);
    write_file(path, json, strlen(json));
    oit_status s = read_path(path, 0, &c, &info, &err);
    printf("all scenes: %zu triangles\n", c.mesh.count);
    CHECK(s == OIT_OK && c.mesh.count == 7, "all scenes: %s, %zu triangles, want 7", err.message, c.mesh.count);
    CHECK(c.mesh.count == 7 && c.mesh.tris[6].v[1].pos[0] == 1.0f, "all scenes: node 4 quad is not drawn untransformed");
    oit_mesh_free(&c.mesh);
    free(json);
    free(noscene);

    /* A NaN in quad vertex 3 spoils the second list triangle and strip triangle 1. */
    uint8_t nan_buf[BUF_SIZE];
    memcpy(nan_buf, buf, BUF_SIZE);
    put_f32(nan_buf + 48, NAN);
    json = embedded_json(scene_json, nan_buf);
    snprintf(path, sizeof path, "%s/nan.gltf", dir);
    write_file(path, json, strlen(json));
    s = read_path(path, 0, &c, &info, &err);
    printf("nan: %zu triangles, %llu dropped\n", c.mesh.count, (unsigned long long)info.nonfinite_dropped);
    CHECK(s == OIT_OK && c.mesh.count == 3 && info.nonfinite_dropped == 2 && info.faces_in == 5,
          "nan: %zu triangles, %llu dropped, %llu faces", c.mesh.count,
          (unsigned long long)info.nonfinite_dropped, (unsigned long long)info.faces_in);
    oit_mesh_free(&c.mesh);
    free(json);

    malformed(dir, buf);
    if (argc > 1)
        check_draco(argv[1]);
    else
        CHECK(0, "usage: test_gltf CORPUS_DIR (tests/corpus/gltf)");
    snprintf(path, sizeof path, "%s/does-not-exist.glb", dir);
    s = read_path(path, 0, &c, &info, &err);
    CHECK(s == OIT_ERR_IO, "missing file: %s", oit_status_name(s));

    return test_verdict();
}
