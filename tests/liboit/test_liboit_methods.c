/* liboit runs every method (oit_renderer_desc.method): each in-core
 * method's image, counts and ambiguity through oit_renderer_draw_pixels
 * are byte for byte what its table renders behind the method interface
 * (view/render/method.h) in the same context, so the tools, which reach every
 * method through liboit, draw what the methods draw; the reference's is
 * liboit-reference.so's, loaded (liboit links no Embree), against the
 * linked table. Also: the list
 * (names unique, stream the one part-file method, the reference the one
 * without GL, every in-core table's flags its entry's), the reference
 * drawn with no GL context current, a borrowed mesh left to its owner,
 * OIT_RENDER_EPSILON_ZERO as a threshold of 0, set_shading and prepare
 * against a renderer made so, and the refusals: an
 * unknown name at create, a method of the other kind of scene, per-pixel
 * figures a method has not, a framebuffer draw of an image-only method. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "view/render/baselines/methods.h"
#include "view/render/image/image.h"
#include "view/render/method.h"
#include "view/render/reference/reference.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 48, H = 36 };

/* Three overlapping coloured quads at different depths, half transparent. */
static void scene(oit_mesh *m)
{
    static const float z[3] = {-0.4f, 0.0f, 0.35f};
    oit_triangle t[6];
    memset(t, 0, sizeof t);
    for (int q = 0; q < 3; q++) {
        float x0 = -0.9f + 0.5f * (float)q, y0 = -0.7f + 0.3f * (float)q, s = 1.1f;
        const float c[4][2] = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
        const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (int k = 0; k < 2; k++)
            for (int v = 0; v < 3; v++) {
                oit_vertex *vx = &t[2 * q + k].v[v];
                vx->pos[0] = c[idx[k][v]][0];
                vx->pos[1] = c[idx[k][v]][1];
                vx->pos[2] = z[q];
                const uint8_t rgba[4] = {(uint8_t)(80 * q + 40), (uint8_t)(200 - 60 * q), 120,
                                         (uint8_t)(90 + 40 * q)};
                memcpy(vx->rgba, rgba, 4);
            }
    }
    *m = (oit_mesh){0};
    CHECK(oit_mesh_append(m, t, 6, NULL) == OIT_OK, "cannot hold the mesh");
    oit_mesh_info_init(&m->info);
    oit_mesh_info_add(&m->info, m->tris, m->count);
    m->info.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
}

static oit_frame_camera camera(void)
{
    return (oit_frame_camera){.eye = {0.3f, 0.2f, 3.0f}, .up = {0, 1, 0}, .fovy_deg = 50.0f,
                              .znear = 0.1f, .zfar = 10.0f};
}

/* The view liboit builds of that camera and shading, for the table. */
static void view_of(const oit_mesh *m, oit_view *v)
{
    memset(v, 0, sizeof *v);
    oit_frame_camera c = camera();
    v->camera.projection = OIT_PROJ_PERSPECTIVE;
    memcpy(v->camera.eye, c.eye, sizeof c.eye);
    memcpy(v->camera.up, c.up, sizeof c.up);
    v->camera.fovy_deg = c.fovy_deg;
    v->camera.znear = c.znear;
    v->camera.zfar = c.zfar;
    v->width = W;
    v->height = H;
    /* model all zero: the identity, as liboit leaves it from oit_frame */
    v->shading.attributes = m->info.attributes;
    v->shading.scene_scale = oit_scene_scale(m->info.bounds_min, m->info.bounds_max);
    v->shading.background[0] = v->shading.background[1] = v->shading.background[2] = 1.0f;
    oit_shading_resolve_defaults(&v->shading);
}

typedef struct pixels {
    float rgba[W * H * 4];
    uint32_t counts[W * H];
    uint8_t ambiguous[W * H];
} pixels;

static const oit_method *table_of(const char *name)
{
    static const oit_method *const tables[] = {
        &oit_method_dfb,  &oit_method_reference, &oit_method_array, &oit_method_stencil,
        &oit_method_unsorted, &oit_method_wboit, &oit_method_pll,   &oit_method_dp,
        &oit_method_ppll4, &oit_method_b3d,      &oit_method_ddp,   &oit_method_guarded,
        &oit_method_f2b,  &oit_method_compute};
    for (size_t i = 0; i < sizeof tables / sizeof *tables; i++)
        if (!strcmp(tables[i]->name, name))
            return tables[i];
    return NULL;
}

/* The method through liboit (desc) and through its table, compared. */
static void compare(oit_gl *gl, const oit_mesh *mesh, const oit_render_method_info *m,
                    oit_renderer_desc desc, const float *threshold, pixels *a, pixels *b)
{
    const oit_method *t = table_of(m->name);
    CHECK(t && t->flags == m->flags, "%s: no table with the listed flags", m->name);
    if (!t)
        return;
    memset(a, 0, sizeof *a);
    memset(b, 0xff, sizeof *b);
    oit_error err = {0};
    oit_scene *scene = NULL;
    oit_renderer *r = NULL;
    oit_draw_stats ds;
    desc.method = m->name;
    oit_frame_camera cam = camera();
    oit_frame fr = {.viewport_width = W, .viewport_height = H, .camera = &cam};
    oit_pixels_desc px = {.rgba = b->rgba, .rgba_bytes = sizeof b->rgba,
                          .counts = m->flags & OIT_RENDER_METHOD_COUNTS ? b->counts : NULL,
                          .ambiguous = m->flags & OIT_RENDER_METHOD_AMBIGUITY ? b->ambiguous
                                                                             : NULL};
    oit_status s = oit_scene_borrow_mesh(mesh, "quads", &scene, &err);
    if (s == OIT_OK)
        s = oit_renderer_create(&desc, &r, &err);
    if (s == OIT_OK)
        s = oit_renderer_draw_pixels(r, scene, &fr, &px, &ds, &err);
    oit_status through_liboit = s;
    CHECK(s == OIT_OK || s == OIT_ERR_UNSUPPORTED || s == OIT_ERR_GL, "%s through liboit: %s",
          m->name, err.message);
    CHECK(s != OIT_OK || (ds.method && !strcmp(ds.method, m->name) && ds.device),
          "%s: the figures name method %s", m->name, ds.method ? ds.method : "(null)");
    oit_renderer_destroy(r);
    oit_scene_close(scene);

    oit_view v;
    view_of(mesh, &v);
    oit_method_options opt = {.max_layers = desc.K ? (int)desc.K : 16, .gl = gl,
                              .threshold = threshold};
    oit_method_state *st = NULL;
    oit_image img = {0};
    oit_frame_stats fs;
    s = oit_method_open(t, mesh, &opt, &st, &err);
    if (s == OIT_OK)
        s = oit_method_render(st, &v, &img, a->counts, a->ambiguous, &fs, &err);
    /* a method this driver cannot run (stencil routing at K=16 on
     * llvmpipe) is refused alike both ways */
    CHECK(s == through_liboit, "%s through its table: %s (liboit: status %d)", m->name,
          err.message, through_liboit);
    if (s == OIT_ERR_UNSUPPORTED || s == OIT_ERR_GL)
        printf("%-10s refused both ways: %s\n", m->name, err.message);
    if (s == OIT_OK)
        memcpy(a->rgba, img.rgba, sizeof a->rgba);
    oit_image_free(&img);
    oit_method_close(st);
    if (s != OIT_OK)
        return;
    printf("%-10s %llu fragments, the same image%s%s\n", m->name,
           (unsigned long long)fs.fragments, px.counts ? ", counts" : "",
           px.ambiguous ? ", ambiguity" : "");
    CHECK(!memcmp(a->rgba, b->rgba, sizeof a->rgba), "%s: liboit's image differs", m->name);
    CHECK(!px.counts || !memcmp(a->counts, b->counts, sizeof a->counts),
          "%s: liboit's counts differ", m->name);
    CHECK(!px.ambiguous || !memcmp(a->ambiguous, b->ambiguous, sizeof a->ambiguous),
          "%s: liboit's ambiguous pixels differ", m->name);
    CHECK(ds.fragments == fs.fragments && ds.gpu_mesh_bytes == fs.gpu_mesh_bytes &&
              ds.fragments_saturated == fs.fragments_saturated,
          "%s: figures %llu/%llu fragments, %llu/%llu mesh bytes", m->name,
          (unsigned long long)ds.fragments, (unsigned long long)fs.fragments,
          (unsigned long long)ds.gpu_mesh_bytes, (unsigned long long)fs.gpu_mesh_bytes);
}

static void check_list(void)
{
    uint32_t n = 0;
    const oit_render_method_info *m = oit_render_methods(&n);
    int part_file = 0, no_gl = 0;
    for (uint32_t i = 0; i < n; i++) {
        for (uint32_t j = 0; j < i; j++)
            CHECK(strcmp(m[i].name, m[j].name), "%s listed twice", m[i].name);
        part_file += !!(m[i].flags & OIT_RENDER_METHOD_PART_FILE);
        no_gl += !(m[i].flags & OIT_RENDER_METHOD_GL);
    }
    CHECK(n == 15 && part_file == 1 && no_gl == 1, "%u methods, %d for part files, %d "
          "without GL", n, part_file, no_gl);
}

/* err's status and that its message has `what`. */
static void refused(oit_status got, oit_status want, const oit_error *err, const char *what)
{
    CHECK(got == want && strstr(err->message, what), "expected status %d naming '%s', got %d: %s",
          want, what, got, err->message);
}

static void check_refusals(oit_gl *gl, const oit_mesh *mesh, pixels *p)
{
    (void)gl;
    oit_error err = {0};
    oit_renderer *r = NULL;
    refused(oit_renderer_create(&(oit_renderer_desc){.method = "dfbb"}, &r, &err),
            OIT_ERR_ARGUMENT, &err, "oit_renderer_desc.method = \"dfbb\"");
    oit_scene *scene = NULL;
    CHECK(oit_scene_borrow_mesh(mesh, NULL, &scene, &err) == OIT_OK, "%s", err.message);
    oit_frame_camera cam = camera();
    oit_frame fr = {.viewport_width = W, .viewport_height = H, .camera = &cam};
    oit_pixels_desc px = {.rgba = p->rgba, .rgba_bytes = sizeof p->rgba};
    static const struct {
        const char *method, *what;
        int counts, framebuffer;
        oit_status want;
    } cases[] = {{"stream", "draws part files", 0, 0, OIT_ERR_UNSUPPORTED},
                 {"array", "oit_pixels_desc.counts", 1, 0, OIT_ERR_UNSUPPORTED},
                 {"wboit", "draws images only", 0, 1, OIT_ERR_UNSUPPORTED}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        CHECK(oit_renderer_create(&(oit_renderer_desc){.method = cases[i].method}, &r, &err) ==
                  OIT_OK, "%s", err.message);
        px.counts = cases[i].counts ? p->counts : NULL;
        oit_status s = cases[i].framebuffer ? oit_renderer_draw(r, scene, &fr, NULL, &err)
                                            : oit_renderer_draw_pixels(r, scene, &fr, &px, NULL,
                                                                       &err);
        refused(s, cases[i].want, &err, cases[i].what);
        oit_renderer_destroy(r);
    }
    oit_scene_close(scene);
}

/* The reference needs no GL: drawn before any context exists. */
static void check_reference_without_gl(const oit_mesh *mesh, pixels *p)
{
    oit_error err = {0};
    oit_scene *scene = NULL;
    oit_renderer *r = NULL;
    oit_frame_camera cam = camera();
    oit_frame fr = {.viewport_width = W, .viewport_height = H, .camera = &cam};
    oit_pixels_desc px = {.rgba = p->rgba, .rgba_bytes = sizeof p->rgba, .counts = p->counts};
    oit_draw_stats ds;
    oit_status s = oit_scene_borrow_mesh(mesh, NULL, &scene, &err);
    if (s == OIT_OK)
        s = oit_renderer_create(&(oit_renderer_desc){.method = "reference"}, &r, &err);
    if (s == OIT_OK)
        s = oit_renderer_draw_pixels(r, scene, &fr, &px, &ds, &err);
    CHECK(s == OIT_OK && ds.fragments > 0 && strstr(ds.device, "Embree"),
          "the reference without GL: %s", s == OIT_OK ? ds.device : err.message);
    CHECK(oit_renderer_gpu_absent(r) != NULL, "the reference claims GPU times");
    oit_renderer_destroy(r);
    oit_scene_close(scene);
}

/* oit_renderer_set_shading keeps the GPU state and draws what a renderer
 * made with that shading draws; oit_renderer_prepare builds what the first
 * draw would, and the draw after it is the same. */
static void check_set_shading(const oit_mesh *mesh, const char *method, pixels *a, pixels *b)
{
    oit_error err = {0};
    oit_scene *scene = NULL;
    oit_renderer *r1 = NULL, *r2 = NULL;
    oit_frame_camera cam = camera();
    oit_frame fr = {.viewport_width = W, .viewport_height = H, .camera = &cam};
    oit_render_shading tl = {.mode = OIT_RENDER_TRANSLUCENT};
    oit_status s = oit_scene_borrow_mesh(mesh, NULL, &scene, &err);
    if (s == OIT_OK)
        s = oit_renderer_create(&(oit_renderer_desc){.method = method}, &r1, &err);
    if (s == OIT_OK)
        s = oit_renderer_prepare(r1, scene, &err);
    if (s == OIT_OK) /* transparent first, then switched */
        s = oit_renderer_draw_image(r1, scene, &fr, NULL, a->rgba, sizeof a->rgba, NULL, &err);
    if (s == OIT_OK)
        s = oit_renderer_set_shading(r1, &tl, 0, &err);
    if (s == OIT_OK)
        s = oit_renderer_draw_image(r1, scene, &fr, NULL, a->rgba, sizeof a->rgba, NULL, &err);
    if (s == OIT_OK)
        s = oit_renderer_create(&(oit_renderer_desc){.method = method, .shading = tl}, &r2, &err);
    if (s == OIT_OK)
        s = oit_renderer_draw_image(r2, scene, &fr, NULL, b->rgba, sizeof b->rgba, NULL, &err);
    CHECK(s == OIT_OK, "%s, set_shading: %s", method, err.message);
    CHECK(s != OIT_OK || !memcmp(a->rgba, b->rgba, sizeof a->rgba),
          "%s: translucent after set_shading differs from a translucent renderer's", method);
    refused(oit_renderer_set_shading(r1, &tl, 2, &err), OIT_ERR_ARGUMENT, &err,
            "oit_renderer_desc.see_through");
    oit_renderer_destroy(r1);
    oit_renderer_destroy(r2);
    oit_scene_close(scene);
}

int main(void)
{
    static pixels a, b;
    oit_mesh mesh;
    scene(&mesh);
    check_list();
    check_reference_without_gl(&mesh, &a);
    oit_gl *gl = test_gl_open();
    uint32_t n = 0;
    const oit_render_method_info *m = oit_render_methods(&n);
    for (uint32_t i = 0; i < n; i++)
        if (!(m[i].flags & OIT_RENDER_METHOD_PART_FILE))
            compare(gl, &mesh, &m[i], (oit_renderer_desc){0}, NULL, &a, &b);
    /* A threshold of exactly 0, and one given, against the table's. */
    static const float zero = 0.0f, some = 0.3f;
    for (uint32_t i = 0; i < n; i++) {
        if (strcmp(m[i].name, "f2b") && strcmp(m[i].name, "guarded") &&
            strcmp(m[i].name, "reference"))
            continue;
        compare(gl, &mesh, &m[i], (oit_renderer_desc){.epsilon = OIT_RENDER_EPSILON_ZERO}, &zero,
                &a, &b);
        compare(gl, &mesh, &m[i], (oit_renderer_desc){.epsilon = some}, &some, &a, &b);
    }
    /* K below 16: stencil routing runs where the driver routes 4 samples */
    for (uint32_t i = 0; i < n; i++)
        if (!strcmp(m[i].name, "stencil") || !strcmp(m[i].name, "array"))
            compare(gl, &mesh, &m[i], (oit_renderer_desc){.K = 4}, NULL, &a, &b);
    check_refusals(gl, &mesh, &a);
    check_set_shading(&mesh, "dfb", &a, &b);
    check_set_shading(&mesh, "wboit", &a, &b);
    /* the scenes borrowed the mesh: it is still whole, and freed once here */
    CHECK(mesh.count == 6 && mesh.tris, "the borrowed mesh changed");
    oit_mesh_free(&mesh);
    oit_gl_destroy(gl);
    return test_verdict();
}
