/* Every method's GPU figure counts the mesh it holds (view/render/method.h,
 * oit_frame_stats.gpu_bytes_peak): each method of the registry but the
 * stream (a part file; tests/tools/oitstream/test_stats_gpu.sh checks its
 * ring and capture) renders the same few visible quads twice through
 * oit_run_open/_render, once with N and once with 4N more triangles
 * lying outside the view (clipped: no fragment, so the method's own
 * per-pixel and per-fragment buffers are the same for both). An in-core GL
 * method holds its mesh on the GPU for as long as it is open, so:
 *   - gpu_mesh_bytes is at least the triangles' vertex bytes, computed here
 *     from the triangle count and the vertex layout (three vertices a
 *     triangle, each 3 floats of position and 4 bytes of colour; the mesh
 *     is a soup, so there is no index buffer), and at most gpu_bytes_peak;
 *   - the 3N triangles more raise gpu_bytes_peak by at least their bytes.
 * A method that leaves its mesh out (the figure of its own buffers alone,
 * 52 KB for a 1M-triangle mesh at 32x32 before) fails both. The reference
 * (Embree, no GL) holds nothing on the GPU: 0 and 0. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "tools/common/method_run.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "tools/common/methods.h"

enum { W = 32, H = 24, QUADS = 4, N = 20000 };

/* The vertex layout every GL method uploads (view/render/gl/gpu_mesh.h), spelt
 * out here rather than taken from sizeof(oit_triangle). */
#define VERTEX_BYTES (3 * sizeof(float) + 4)
#define TRIANGLE_BYTES (3 * VERTEX_BYTES)

static void put(oit_triangle *t, const float p[3][3], uint8_t alpha)
{
    for (int v = 0; v < 3; v++) {
        memcpy(t->v[v].pos, p[v], sizeof p[v]);
        const uint8_t rgba[4] = {200, (uint8_t)(40 * v), 90, alpha};
        memcpy(t->v[v].rgba, rgba, 4);
    }
}

/* QUADS quads across [-1, 1]^2, one behind the other, then `hidden`
 * small triangles far to the side (x about 1000), outside any view of the
 * quads. The view frames the quads alone. */
static void scene(oit_mesh *m, size_t hidden, oit_view *view)
{
    size_t n = 2 * QUADS + hidden;
    m->tris = calloc(n, sizeof *m->tris);
    m->count = m->capacity = m->tris ? n : 0;
    static const float corner[2][3][2] = {{{-1, -1}, {1, -1}, {1, 1}}, {{-1, -1}, {1, 1}, {-1, 1}}};
    for (size_t t = 0; t < m->count; t++) {
        float p[3][3];
        for (int v = 0; v < 3; v++) {
            if (t < 2 * QUADS) {
                p[v][0] = corner[t % 2][v][0];
                p[v][1] = corner[t % 2][v][1];
                p[v][2] = -0.5f + 0.3f * (float)(t / 2);
            } else {
                p[v][0] = 1000.0f + 0.01f * (float)(t % 1000) + (v == 1 ? 0.5f : 0.0f);
                p[v][1] = 0.01f * (float)(t / 1000) + (v == 2 ? 0.5f : 0.0f);
                p[v][2] = 0.0f;
            }
        }
        put(&m->tris[t], (const float(*)[3])p, 100);
    }
    oit_mesh_info_init(&m->info);
    oit_mesh_info_add(&m->info, m->tris, m->count);
    m->info.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    const float lo[3] = {-1, -1, -0.5f}, hi[3] = {1, 1, 0.5f};
    memset(view, 0, sizeof *view);
    oit_camera_default(&view->camera, lo, hi, 20.0f, 15.0f);
    view->width = W;
    view->height = H;
    view->shading.mode = OIT_SHADING_TRANSPARENT;
    view->shading.attributes = m->info.attributes;
    view->shading.scene_scale = oit_scene_scale(lo, hi);
    oit_shading_resolve_defaults(&view->shading);
}

/* One frame of method m on mesh; 0 with *skip set where the driver does
 * not offer it (stencil routing). */
static int frame_of(oit_gl *gl, const oit_render_method_info *m, const oit_mesh *mesh, const oit_view *v,
                    oit_frame_stats *st, int *skip)
{
    oit_run_options opt = {.max_layers = 4, .gl = gl};
    oit_run *state = NULL;
    oit_image img = {0};
    oit_error err = {0};
    memset(st, 0, sizeof *st);
    oit_status s = oit_run_open(m, mesh, &opt, &state, &err);
    if (s == OIT_ERR_UNSUPPORTED || s == OIT_ERR_GL) {
        printf("%-10s skipped: %s\n", m->name, err.message);
        *skip = 1;
        return 0;
    }
    if (s == OIT_OK)
        s = oit_run_render(state, v, &img, NULL, NULL, st, &err);
    oit_image_free(&img);
    oit_run_close(state);
    CHECK(s == OIT_OK, "%s: %s", m->name, err.message);
    return s == OIT_OK;
}

static void check_method(oit_gl *gl, const oit_render_method_info *m, const oit_mesh small[1],
                         const oit_mesh large[1], const oit_view *v)
{
    oit_frame_stats a, b;
    int skip = 0;
    if (!frame_of(gl, m, small, v, &a, &skip) || !frame_of(gl, m, large, v, &b, &skip))
        return;
    uint64_t tris_a = small->count * TRIANGLE_BYTES, tris_b = large->count * TRIANGLE_BYTES;
    printf("%-10s %zu triangles: peak %llu (mesh %llu); %zu: peak %llu (mesh %llu); "
           "fragments %llu/%llu\n", m->name, small->count, (unsigned long long)a.gpu_bytes_peak,
           (unsigned long long)a.gpu_mesh_bytes, large->count,
           (unsigned long long)b.gpu_bytes_peak, (unsigned long long)b.gpu_mesh_bytes,
           (unsigned long long)a.fragments, (unsigned long long)b.fragments);
    CHECK(a.fragments > 0 && a.fragments == b.fragments, "%s: %llu and %llu fragments: the "
          "hidden triangles must add none", m->name, (unsigned long long)a.fragments,
          (unsigned long long)b.fragments);
    if (!(m->flags & OIT_RENDER_METHOD_GL)) {
        CHECK(a.gpu_bytes_peak == 0 && a.gpu_mesh_bytes == 0 && b.gpu_bytes_peak == 0,
              "%s: no GL, yet %llu GPU bytes (%llu mesh)", m->name,
              (unsigned long long)a.gpu_bytes_peak, (unsigned long long)a.gpu_mesh_bytes);
        return;
    }
    CHECK(a.gpu_mesh_bytes >= tris_a && b.gpu_mesh_bytes >= tris_b,
          "%s: gpu_mesh_bytes %llu and %llu, the triangles alone take %llu and %llu", m->name,
          (unsigned long long)a.gpu_mesh_bytes, (unsigned long long)b.gpu_mesh_bytes,
          (unsigned long long)tris_a, (unsigned long long)tris_b);
    CHECK(a.gpu_bytes_peak >= a.gpu_mesh_bytes && b.gpu_bytes_peak >= b.gpu_mesh_bytes,
          "%s: gpu_bytes_peak below the mesh it holds", m->name);
    CHECK(b.gpu_bytes_peak >= a.gpu_bytes_peak + (tris_b - tris_a),
          "%s: %zu more triangles raised gpu_bytes_peak by %lld bytes, their vertices take %llu",
          m->name, large->count - small->count,
          (long long)(b.gpu_bytes_peak - a.gpu_bytes_peak),
          (unsigned long long)(tris_b - tris_a));
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_mesh small = {0}, large = {0};
    oit_view v;
    scene(&small, N, &v);
    scene(&large, 4 * N, &v);
    CHECK(small.count && large.count, "cannot hold the scenes");
    char names[OIT_METHOD_NAMES_MAX];
    oit_method_names(names, sizeof names);
    int tried = 0;
    for (char *save = NULL, *name = strtok_r(names, "|", &save); name && small.count;
         name = strtok_r(NULL, "|", &save)) {
        const oit_render_method_info *m = oit_method_find(name);
        if (!m || (m->flags & OIT_RENDER_METHOD_PART_FILE))
            continue;
        check_method(gl, m, &small, &large, &v);
        tried++;
    }
    CHECK(tried >= 10, "only %d methods in the registry", tried);
    free(small.tris);
    free(large.tris);
    oit_gl_destroy(gl);
    return test_verdict();
}
