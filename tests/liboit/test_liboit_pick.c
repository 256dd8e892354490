/* oit_renderer_pick: the layers at a pixel are the reference's hits and
 * compose to the exact image. On three models (oitgen's quads, a 10K
 * plant of closed solids, the OBJ assembly with opaque MTL boxes), at
 * every other pixel of a 40x40 view that the reference's ambiguity mask
 * leaves (edges, where rays and rasterization may differ):
 *
 * - the walk's layers (method dfb) and the reference's own (Embree, method
 *   reference) are the same triangles in the same order, at the same depth;
 * - composited (C += T a c over the layers, then T (1 - a) of the last over
 *   white) they give the reference's pixel within 1e-4, and every layer's
 *   transmittance is the product of (1 - alpha) of the layers before it;
 * - they give DFB's pixel (GL) within 1.5/255, and each layer's point lies
 *   its depth from the eye;
 * - the model's part file (oitprep) lists the same source triangles, each
 *   with its part; in core the part is OIT_PICK_NO_PART;
 * - a model matrix: the pick of a frame with one lists what the pick of
 *   the mesh placed beforehand lists, and composes to DFB's pixel with it;
 * - capacity: a call with less room gets the front layers and the count;
 *   a pixel outside the view and a NULL count are refused.
 *
 * usage: test_liboit_pick OITGEN OITPREP CORPUS WORKDIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "view/render/image/view.h"

enum { W = 40, H = 40, MAXL = 4096 };

typedef struct model {
    const char *mesh, *part_file;
    oit_scene *in_core, *parts;
    oit_frame_camera cam;
    float *ref_rgba, *dfb_rgba;
    uint8_t *ambiguous;
} model;

static oit_renderer *renderer(const char *method)
{
    oit_renderer *r = NULL;
    oit_error err = {0};
    CHECK(oit_renderer_create(&(oit_renderer_desc){.method = method}, &r, &err) == OIT_OK,
          "create %s: %s", method ? method : "(default)", err.message);
    return r;
}

static void frame_of(const model *m, oit_frame *f)
{
    memset(f, 0, sizeof *f);
    f->viewport_width = W;
    f->viewport_height = H;
    f->camera = &m->cam;
}

/* m's in-core scene and the default camera of its bounds. */
static void open_model_scene(model *m, const char *path)
{
    oit_error err = {0};
    CHECK(oit_scene_open(path, NULL, &m->in_core, &err) == OIT_OK, "%s", err.message);
    oit_scene_info info;
    CHECK(oit_scene_get_info(m->in_core, &info, &err) == OIT_OK, "%s", err.message);
    oit_camera c;
    oit_camera_default(&c, info.bounds_min, info.bounds_max, 30.0f, 25.0f);
    m->cam = (oit_frame_camera){.fovy_deg = c.fovy_deg, .znear = c.znear, .zfar = c.zfar};
    memcpy(m->cam.eye, c.eye, sizeof c.eye);
    memcpy(m->cam.target, c.target, sizeof c.target);
    memcpy(m->cam.up, c.up, sizeof c.up);
}

static void open_model(model *m)
{
    open_model_scene(m, m->mesh);
    oit_error err = {0};
    CHECK(oit_scene_open(m->part_file, NULL, &m->parts, &err) == OIT_OK, "%s", err.message);
}

/* The reference's image and ambiguity mask (no GL), DFB's image (GL). */
static void draw_images(model *m, oit_renderer *ref, oit_renderer *dfb)
{
    size_t px = (size_t)W * H;
    m->ref_rgba = calloc(px * 4, sizeof(float));
    m->dfb_rgba = calloc(px * 4, sizeof(float));
    m->ambiguous = calloc(px, 1);
    CHECK(m->ref_rgba && m->dfb_rgba && m->ambiguous, "out of memory");
    oit_frame f;
    frame_of(m, &f);
    oit_error err = {0};
    oit_pixels_desc d = {.rgba = m->ref_rgba, .rgba_bytes = px * 4 * sizeof(float),
                         .ambiguous = m->ambiguous};
    CHECK(oit_renderer_draw_pixels(ref, m->in_core, &f, &d, NULL, &err) == OIT_OK, "%s",
          err.message);
    d = (oit_pixels_desc){.rgba = m->dfb_rgba, .rgba_bytes = px * 4 * sizeof(float)};
    CHECK(oit_renderer_draw_pixels(dfb, m->in_core, &f, &d, NULL, &err) == OIT_OK, "%s",
          err.message);
}

static size_t pick(oit_renderer *r, oit_scene *s, const model *m, int x, int y,
                   oit_pick_layer *out)
{
    oit_frame f;
    frame_of(m, &f);
    size_t n = 0;
    oit_error err = {0};
    CHECK(oit_renderer_pick(r, s, &f, x, y, out, MAXL, &n, &err) == OIT_OK, "pick %d,%d: %s", x,
          y, err.message);
    CHECK(n <= MAXL, "pick %d,%d: %zu layers", x, y, n);
    return n;
}

/* The layers composited over white; checks each transmittance on the way. */
static void composite(const oit_pick_layer *l, size_t n, float rgb[3], const char *what)
{
    double C[3] = {0, 0, 0}, T[3] = {1, 1, 1};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            CHECK(fabs(l[i].transmittance[c] - T[c]) <= 1e-5, "%s: layer %zu's transmittance "
                  "%g, the layers before leave %g", what, i, l[i].transmittance[c], T[c]);
            C[c] += T[c] * l[i].alpha * l[i].colour[c];
            T[c] *= 1.0 - l[i].alpha;
        }
    for (int c = 0; c < 3; c++)
        rgb[c] = (float)(C[c] + T[c]);
}

static int same_layers(const oit_pick_layer *a, size_t na, const oit_pick_layer *b, size_t nb)
{
    if (na != nb)
        return 0;
    for (size_t i = 0; i < na; i++)
        if (a[i].source_triangle != b[i].source_triangle ||
            fabs(a[i].depth - b[i].depth) > 1e-5 * fabs(a[i].depth))
            return 0;
    return 1;
}

static void check_pixel(const model *m, oit_renderer *walk, oit_renderer *ref, int x, int y,
                        oit_pick_layer *a, oit_pick_layer *b, unsigned *compared)
{
    size_t na = pick(walk, m->in_core, m, x, y, a);
    size_t nb = pick(ref, m->in_core, m, x, y, b);
    CHECK(same_layers(a, na, b, nb), "%s %d,%d: the walk's %zu layers are not the "
          "reference's %zu", m->mesh, x, y, na, nb);
    for (size_t i = 0; i < na; i++) {
        CHECK(a[i].part == OIT_PICK_NO_PART, "%s: a part in core", m->mesh);
        double d2 = 0.0;
        for (int k = 0; k < 3; k++)
            d2 += (a[i].point[k] - m->cam.eye[k]) * (a[i].point[k] - m->cam.eye[k]);
        CHECK(fabs(sqrt(d2) - a[i].depth) <= 1e-4 * a[i].depth, "%s %d,%d: layer %zu's point "
              "lies %g from the eye, its depth is %g", m->mesh, x, y, i, sqrt(d2), a[i].depth);
    }
    float rgb[3];
    composite(a, na, rgb, m->mesh);
    const float *r = m->ref_rgba + ((size_t)y * W + x) * 4, *d = m->dfb_rgba + ((size_t)y * W + x) * 4;
    for (int c = 0; c < 3; c++) {
        CHECK(fabsf(rgb[c] - r[c]) <= 1e-4f, "%s %d,%d: the layers compose to %g, the "
              "reference's pixel is %g", m->mesh, x, y, rgb[c], r[c]);
        CHECK(fabsf(rgb[c] - d[c]) <= 1.5f / 255.0f, "%s %d,%d: the layers compose to %g, "
              "DFB's pixel is %g", m->mesh, x, y, rgb[c], d[c]);
    }
    size_t np = pick(walk, m->parts, m, x, y, b);
    CHECK(np == na, "%s %d,%d: %zu layers in the part file, %zu in core", m->mesh, x, y, np, na);
    for (size_t i = 0; i < na; i++)
        CHECK(b[i].source_triangle == a[i].source_triangle && b[i].part != OIT_PICK_NO_PART,
              "%s %d,%d: part file layer %zu is source %llu (part %u), in core %llu", m->mesh,
              x, y, i, (unsigned long long)b[i].source_triangle, b[i].part,
              (unsigned long long)a[i].source_triangle);
    *compared += na > 0;
}

static void check_model(model *m, oit_renderer *walk, oit_renderer *ref, oit_renderer *dfb)
{
    open_model(m);
    draw_images(m, ref, dfb);
    oit_pick_layer *a = malloc(MAXL * sizeof *a), *b = malloc(MAXL * sizeof *b);
    CHECK(a && b, "out of memory");
    unsigned compared = 0, skipped = 0, deepest = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 1; x < W; x += 2) {
            if (m->ambiguous[y * W + x]) {
                skipped++;
                continue;
            }
            check_pixel(m, walk, ref, x, y, a, b, &compared);
            size_t n = pick(walk, m->in_core, m, x, y, a);
            deepest = n > deepest ? (unsigned)n : deepest;
        }
    printf("%s: %u pixels with layers compared, %u on the ambiguity mask skipped, deepest %u\n",
           m->mesh, compared, skipped, deepest);
    CHECK(compared >= 50 && deepest >= 3, "%s: too little compared (%u pixels, %u deep)",
          m->mesh, compared, deepest);
    free(a);
    free(b);
    free(m->ref_rgba);
    free(m->dfb_rgba);
    free(m->ambiguous);
    oit_scene_close(m->in_core);
    oit_scene_close(m->parts);
}

/* Less room than layers: the front ones and the whole count; refusals. */
static void check_capacity(oit_renderer *walk, const char *mesh)
{
    model m = {.mesh = mesh, .part_file = mesh};
    oit_error err = {0};
    CHECK(oit_scene_open(mesh, NULL, &m.in_core, &err) == OIT_OK, "%s", err.message);
    oit_scene_info info;
    CHECK(oit_scene_get_info(m.in_core, &info, &err) == OIT_OK, "%s", err.message);
    oit_camera c;
    oit_camera_default(&c, info.bounds_min, info.bounds_max, 0.0f, 0.0f);
    m.cam = (oit_frame_camera){.fovy_deg = c.fovy_deg, .znear = c.znear, .zfar = c.zfar};
    memcpy(m.cam.eye, c.eye, sizeof c.eye);
    memcpy(m.cam.target, c.target, sizeof c.target);
    memcpy(m.cam.up, c.up, sizeof c.up);
    oit_frame f;
    frame_of(&m, &f);
    oit_pick_layer all[64], two[2];
    size_t n = 0, n2 = 0;
    CHECK(oit_renderer_pick(walk, m.in_core, &f, W / 2, H / 2, all, 64, &n, &err) == OIT_OK,
          "%s", err.message);
    CHECK(n >= 3, "the quads' centre has %zu layers", n);
    CHECK(oit_renderer_pick(walk, m.in_core, &f, W / 2, H / 2, two, 2, &n2, &err) == OIT_OK &&
              n2 == n && !memcmp(two, all, sizeof two),
          "room for 2 of %zu layers: count %zu, or not the front two", n, n2);
    CHECK(oit_renderer_pick(walk, m.in_core, &f, W, 0, all, 64, &n, &err) == OIT_ERR_ARGUMENT &&
              strstr(err.message, "outside"),
          "a pixel outside the view: %s", err.message);
    CHECK(oit_renderer_pick(walk, m.in_core, &f, 0, 0, all, 64, NULL, &err) == OIT_ERR_ARGUMENT,
          "a NULL count");
    oit_scene_close(m.in_core);
}

/* A model matrix (a turn about y, a scale and a shift): the pick of the
 * frame with it lists what the pick of the mesh placed beforehand lists,
 * and composes to DFB's pixel of the frame with it (GL) wherever the
 * placed mesh's layers are the reference's own. */
static void check_model_matrix(oit_renderer *walk, oit_renderer *ref, oit_renderer *dfb,
                               const char *mesh)
{
    static const float M[16] = {0.8f, 0, -0.6f, 0, 0, 1.5f, 0, 0, 0.6f, 0, 0.8f, 0,
                                0.25f, -0.5f, 0.1f, 1};
    oit_mesh placed = {0};
    oit_error err = {0};
    CHECK(oit_mesh_load(mesh, NULL, &placed, &err) == OIT_OK, "%s", err.message);
    for (size_t i = 0; i < placed.count; i++)
        for (int v = 0; v < 3; v++) {
            float *p = placed.tris[i].v[v].pos, q[3];
            for (int k = 0; k < 3; k++)
                q[k] = (float)((double)M[k] * p[0] + (double)M[4 + k] * p[1] +
                               (double)M[8 + k] * p[2] + M[12 + k]);
            memcpy(p, q, sizeof q);
        }
    oit_mesh_info_init(&placed.info);
    oit_mesh_info_add(&placed.info, placed.tris, placed.count);
    placed.info.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    model m = {.mesh = mesh, .part_file = mesh};
    open_model_scene(&m, mesh);
    oit_scene *pre = NULL;
    CHECK(oit_scene_borrow_mesh(&placed, "placed", &pre, &err) == OIT_OK, "%s", err.message);
    oit_frame f, g;
    frame_of(&m, &f);
    frame_of(&m, &g);
    memcpy(g.model, M, sizeof M);
    size_t px = (size_t)W * H;
    float *img = calloc(px * 4, sizeof(float));
    CHECK(img != NULL, "out of memory");
    oit_pixels_desc d = {.rgba = img, .rgba_bytes = px * 4 * sizeof(float)};
    CHECK(oit_renderer_draw_pixels(dfb, m.in_core, &g, &d, NULL, &err) == OIT_OK, "%s",
          err.message);
    oit_pick_layer a[64], b[64], c[64];
    unsigned compared = 0;
    for (int y = 1; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            size_t na = 0, nb = 0, nc = 0;
            CHECK(oit_renderer_pick(walk, m.in_core, &g, x, y, a, 64, &na, &err) == OIT_OK &&
                      oit_renderer_pick(walk, pre, &f, x, y, b, 64, &nb, &err) == OIT_OK &&
                      oit_renderer_pick(ref, pre, &f, x, y, c, 64, &nc, &err) == OIT_OK,
                  "pick %d,%d: %s", x, y, err.message);
            CHECK(same_layers(a, na, b, nb), "%d,%d: with the model matrix %zu layers, placed "
                  "beforehand %zu, or another order", x, y, na, nb);
            if (!same_layers(b, nb, c, nc) || na == 0)
                continue; /* an edge of the placed mesh */
            float rgb[3];
            composite(a, na, rgb, "model matrix");
            for (int k = 0; k < 3; k++)
                CHECK(fabsf(rgb[k] - img[((size_t)y * W + x) * 4 + k]) <= 1.5f / 255.0f,
                      "%d,%d: the layers compose to %g, DFB's pixel with the model is %g", x, y,
                      rgb[k], img[((size_t)y * W + x) * 4 + k]);
            compared++;
        }
    printf("model matrix: %u pixels with layers compared\n", compared);
    CHECK(compared >= 20, "model matrix: %u pixels compared", compared);
    free(img);
    oit_scene_close(pre);
    oit_scene_close(m.in_core);
    oit_mesh_free(&placed);
}

static void run(const char *cmd)
{
    printf("%s\n", cmd);
    fflush(stdout);
    CHECK(system(cmd) == 0, "failed: %s", cmd);
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s OITGEN OITPREP CORPUS WORKDIR\n", argv[0]);
        return 2;
    }
    const char *gen = argv[1], *prep = argv[2], *corpus = argv[3], *dir = argv[4];
    char meshes[3][512], parts[3][512], cmd[4096];
    snprintf(meshes[0], sizeof meshes[0], "%s/pick_quads.ply", dir);
    snprintf(meshes[1], sizeof meshes[1], "%s/pick_plant.ply", dir);
    snprintf(meshes[2], sizeof meshes[2], "%s/obj/assembly.obj", corpus);
    snprintf(cmd, sizeof cmd, "%s quads --count 24 -o %s >/dev/null", gen, meshes[0]);
    run(cmd);
    snprintf(cmd, sizeof cmd, "%s plant --triangles 10000 -o %s >/dev/null", gen, meshes[1]);
    run(cmd);
    static const char *stems[3] = {"pick_quads", "pick_plant", "pick_assembly"};
    for (int i = 0; i < 3; i++) {
        snprintf(parts[i], sizeof parts[i], "%s/%s.oitp", dir, stems[i]);
        snprintf(cmd, sizeof cmd, "%s %s -o %s 2>/dev/null", prep, meshes[i], parts[i]);
        run(cmd);
    }
    oit_gl *gl = test_gl_open();
    oit_renderer *walk = renderer("dfb"), *ref = renderer("reference"), *dfb = renderer("dfb");
    for (int i = 0; i < 3; i++) {
        model m = {.mesh = meshes[i], .part_file = parts[i]};
        check_model(&m, walk, ref, dfb);
    }
    check_capacity(walk, meshes[0]);
    check_model_matrix(walk, ref, dfb, meshes[0]);
    oit_renderer_destroy(walk);
    oit_renderer_destroy(ref);
    oit_renderer_destroy(dfb);
    return test_gl_verdict(gl);
}
