/* Frames rendered in bands of rows (view/render/gl/band.h) against the same frames
 * whole: every exact method through oit_method_render, with a storage
 * limit (oit_method_options.store_limit) low enough that a 37x53 frame
 * takes 4 to 14 bands, and for the list methods a fragment pool that
 * outgrows it, so that bands split again. A band whose sub-window moved a
 * pixel centre, a row copied to the wrong place, a band drawn twice or
 * not at all, or a part culled by the wrong band shows as pixels off and
 * fragments that do not add up. Perspective and orthographic, transparent
 * and translucent; the stream over the grid part file (argv[1], from
 * test_streamer: many parts, packs whose rectangles start anywhere) with
 * every --pack.
 *
 * Not pixel-exact: a band's projection is the full one's rows scaled in
 * float, so a vertex may snap to the next sub-pixel step and a pixel centre
 * within that step of a silhouette edge gain or lose its fragment (seen: 1
 * to 2 of ~2000 pixels here; the same happens between any two projections
 * of one view). The tolerance admits that many, not a lost band row.
 *
 * usage: test_bands GRID.oitp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/partfile.h"
#include "view/render/gl/band.h"
#include "view/render/baselines/baseline_common.h"
#include "view/render/image/image.h"
#include "view/render/method.h"
#include "view/stream/streamer.h"
#include "view/render/baselines/methods.h"
#include "tools/common/method_run.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "tools/common/methods.h"

enum { W = 37, H = 53, TRIS = 240, QUADS = 10, EDGE_FLIPS = 4 };

/* Most bytes in one storage binding: 11 rows of a 37-pixel frame at 20
 * bytes a pixel (the capture's transparent state); DFB (16) takes 13-row
 * bands, the baselines (48) 4-row ones, whose fragment pools (16 bytes a
 * fragment) overflow it and split again. */
#define LIMIT (11ull * W * 20)

/* Ten tilted quads across the whole scene, one behind the other, so that
 * the list methods' pools (10 layers a pixel) outgrow a band's share of
 * LIMIT, then random small triangles about the origin, some crossing band
 * edges; each with its own colour and alpha. */
static void scene(oit_mesh *m)
{
    static oit_triangle tris[TRIS];
    uint32_t r = 12345u;
    for (int t = 0; t < TRIS; t++) {
        r = r * 1664525u + 1013904223u;
        uint8_t rgba[4] = {(uint8_t)(r >> 24), (uint8_t)(r >> 16), (uint8_t)(r >> 8),
                           (uint8_t)(60 + (r >> 4) % 160)};
        float p[3][3];
        if (t < 2 * QUADS) {
            static const float corner[2][3][2] = {{{-1, -1}, {1, -1}, {1, 1}},
                                                  {{-1, -1}, {1, 1}, {-1, 1}}};
            float z = -0.9f + 1.8f * (float)(t / 2) / (QUADS - 1);
            for (int v = 0; v < 3; v++) {
                p[v][0] = 1.3f * corner[t % 2][v][0];
                p[v][1] = 1.3f * corner[t % 2][v][1];
                p[v][2] = z + 0.1f * corner[t % 2][v][0];
            }
        } else {
            float c[3], size = t % 7 == 0 ? 1.2f : 0.35f;
            for (int k = 0; k < 3; k++) {
                r = r * 1664525u + 1013904223u;
                c[k] = (float)(r >> 8) / 16777216.0f * 2.0f - 1.0f;
            }
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) {
                    r = r * 1664525u + 1013904223u;
                    p[v][k] = c[k] + ((float)(r >> 8) / 16777216.0f - 0.5f) * size;
                }
        }
        for (int v = 0; v < 3; v++) {
            memcpy(tris[t].v[v].pos, p[v], sizeof p[v]);
            memcpy(tris[t].v[v].rgba, rgba, 4);
        }
    }
    memset(m, 0, sizeof *m);
    m->tris = tris;
    m->count = m->capacity = TRIS;
    oit_mesh_info_init(&m->info);
    oit_mesh_info_add(&m->info, m->tris, m->count);
    m->info.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
}

static void make_view(const float lo[3], const float hi[3], int ortho, oit_view *v)
{
    memset(v, 0, sizeof *v);
    oit_camera_default(&v->camera, lo, hi, 30.0f, 20.0f);
    if (ortho) {
        v->camera.projection = OIT_PROJ_ORTHOGRAPHIC;
        v->camera.ortho_height = 1.1f * (hi[1] - lo[1]);
    }
    v->width = W;
    v->height = H;
    v->shading.mode = ortho ? OIT_SHADING_TRANSLUCENT : OIT_SHADING_TRANSPARENT;
    v->shading.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    v->shading.scene_scale = oit_scene_scale(lo, hi);
    oit_shading_resolve_defaults(&v->shading);
}

typedef struct frame {
    oit_image img;
    oit_frame_stats st;
    uint32_t counts[W * H];
    int ok;
} frame;

/* The stream, which liboit runs (the tools' oit_run), in this test's
 * list of the method interface's tables. */
static const oit_method stream = {.name = "stream"};

static oit_status render_stream(const oit_method_options *opt, const oit_view *v, frame *f,
                                oit_error *err)
{
    oit_run *run = NULL;
    oit_run_options ro = {.max_layers = opt->max_layers, .gl = opt->gl, .source = opt->source,
                          .store_limit = opt->store_limit};
    oit_status s = oit_run_open(oit_method_find("stream"), NULL, &ro, &run, err);
    if (s == OIT_OK)
        s = oit_run_render(run, v, &f->img, NULL, NULL, &f->st, err);
    oit_run_close(run);
    return s;
}

static void render(const oit_method *m, const oit_mesh *mesh, const oit_method_options *opt,
                   const oit_view *v, frame *f)
{
    oit_error err = {0};
    oit_method_state *st = NULL;
    memset(f, 0, sizeof *f);
    oit_status s = OIT_OK;
    if (m == &stream) {
        s = render_stream(opt, v, f, &err);
    } else {
        s = oit_method_open(m, mesh, opt, &st, &err);
        if (s == OIT_OK)
            s = oit_method_render(st, v, &f->img, f->counts, NULL, &f->st, &err);
        oit_method_close(st);
    }
    f->ok = s == OIT_OK;
    CHECK(f->ok, "%s (store limit %llu): %s", m->name, (unsigned long long)opt->store_limit,
          err.message);
}

/* The bands the method's frame takes under LIMIT. */
static int bands_of(const oit_method *m, const oit_view *v)
{
    int rows = 0;
    oit_error err = {0};
    /* The stream method has none: liboit bands by the streamer's state
     * itself (oit_renderer_desc.binding_limit). */
    uint64_t px = m->pixel_bytes ? m->pixel_bytes(NULL, v) : oit_streamer_pixel_bytes(v);
    CHECK(oit_band_rows(v, px, LIMIT, &rows, &err) == OIT_OK, "%s", err.message);
    return rows > 0 ? (H + rows - 1) / rows : 0;
}

/* Banded against whole: the same pixels (float rounding of the band's
 * sub-window may move a tie's order or an edge on a pixel or two), the
 * same fragments, layers and counts. */
static void compare(const char *what, const oit_method *m, const oit_view *v, const frame *whole,
                    const frame *banded)
{
    if (!whole->ok || !banded->ok)
        return;
    oit_image_diff d = {0};
    oit_error err = {0};
    CHECK(oit_image_compare(&whole->img, &banded->img, &d, NULL, 0, &err) == OIT_OK, "%s",
          err.message);
    int bands = bands_of(m, v);
    printf("%-24s %2d bands: max_abs %.5f, %llu pixels over 1/255, fragments %llu/%llu, "
           "batches %u/%u\n",
           what, bands, d.max_abs, (unsigned long long)d.pixels_over,
           (unsigned long long)banded->st.fragments, (unsigned long long)whole->st.fragments,
           banded->st.batches, whole->st.batches);
    CHECK(bands >= 4, "%s: %d bands: the limit does not band the frame", what, bands);
    CHECK(d.pixels_over <= EDGE_FLIPS, "%s: %llu pixels off by more than 1/255 (max %g)", what,
          (unsigned long long)d.pixels_over, d.max_abs);
    int64_t lost = (int64_t)whole->st.fragments - (int64_t)banded->st.fragments;
    CHECK(llabs(lost) <= EDGE_FLIPS, "%s: %llu fragments banded, %llu whole", what,
          (unsigned long long)banded->st.fragments, (unsigned long long)whole->st.fragments);
    CHECK(banded->st.max_layers == whole->st.max_layers, "%s: %u layers banded, %u whole", what,
          banded->st.max_layers, whole->st.max_layers);
    CHECK(banded->st.batches >= (uint32_t)bands, "%s: %u batches in %d bands", what,
          banded->st.batches, bands);
    if (m->flags & OIT_RENDER_METHOD_COUNTS) {
        int off = 0;
        for (int i = 0; i < W * H; i++)
            off += whole->counts[i] != banded->counts[i];
        CHECK(off <= EDGE_FLIPS, "%s: %d pixels' fragment counts differ", what, off);
    }
}

/* The scene must make the list methods split their bands: the fragments
 * (16 bytes each) of some band of the baselines' rows pass LIMIT, while
 * those of every single row fit it, in pages of 4 (paged lists). Read from
 * DFB's counts of the frame. */
static void check_deep_enough(const oit_mesh *mesh, oit_method_options *opt, const oit_view *v)
{
    frame *f = calloc(1, sizeof *f);
    opt->store_limit = 0;
    render(&oit_method_dfb, mesh, opt, v, f);
    int rows = 0;
    oit_error err = {0};
    oit_band_rows(v, OIT_BASELINE_PIXEL_BYTES, LIMIT, &rows, &err);
    uint64_t band_most = 0, row_most = 0;
    for (int y0 = 0; f->ok && rows > 0 && y0 < H; y0 += rows) {
        uint64_t band = 0;
        for (int y = y0; y < y0 + rows && y < H; y++) {
            uint64_t row = 0;
            for (int x = 0; x < W; x++) {
                row += (f->counts[y * W + x] + 3) / 4 * 4;
                band += f->counts[y * W + x];
            }
            row_most = row > row_most ? row : row_most;
        }
        band_most = band > band_most ? band : band_most;
    }
    printf("deepest band of %d rows: %llu fragments, deepest row %llu; the limit holds %llu\n",
           rows, (unsigned long long)band_most, (unsigned long long)row_most, LIMIT / 16);
    CHECK(band_most * 16 > LIMIT && row_most * 16 <= LIMIT,
          "the scene does not make the list "
          "pools split: %llu fragments in a band, %llu in a row",
          (unsigned long long)band_most, (unsigned long long)row_most);
    oit_image_free(&f->img);
    free(f);
}

static void check_method(const oit_method *m, const oit_mesh *mesh, oit_method_options *opt,
                         const oit_view *v, const char *what)
{
    frame *whole = calloc(1, sizeof *whole), *banded = calloc(1, sizeof *banded);
    opt->store_limit = 0;
    render(m, mesh, opt, v, whole);
    opt->store_limit = LIMIT;
    render(m, mesh, opt, v, banded);
    compare(what, m, v, whole, banded);
    oit_image_free(&whole->img);
    oit_image_free(&banded->img);
    free(whole);
    free(banded);
}

static void in_core(oit_gl *gl, const oit_mesh *mesh, const oit_view *v, const char *view_name)
{
    static const oit_method *const tables[] = {&oit_method_dfb,   &oit_method_array,
                                               &oit_method_stencil, &oit_method_pll,
                                               &oit_method_ppll4, &oit_method_b3d,
                                               &oit_method_dp,    &oit_method_ddp};
    oit_method_options dfb_opt = {.gl = gl};
    check_deep_enough(mesh, &dfb_opt, v);
    for (size_t i = 0; i < sizeof tables / sizeof *tables; i++) {
        const oit_method *m = tables[i];
        const char *name = m->name;
        /* dual peeling composites its back half back to front: no
         * absorption (dual_peel.h) */
        if (v->shading.mode == OIT_SHADING_TRANSLUCENT && !strcmp(name, "ddp"))
            continue;
        oit_method_options opt = {.max_layers = 8, .gl = gl};
        oit_method_state *probe = NULL;
        oit_error err = {0};
        /* Stencil routing is offered only where the driver routes per
         * sample (capture.h). */
        if (oit_method_open(m, mesh, &opt, &probe, &err) == OIT_ERR_GL) {
            printf("%-24s skipped: %s\n", name, err.message);
            continue;
        }
        oit_method_close(probe);
        char what[64];
        snprintf(what, sizeof what, "%s %s", name, view_name);
        check_method(m, mesh, &opt, v, what);
    }
}

static void streamed(oit_gl *gl, const char *path, const oit_view *v, const char *view_name)
{
    static const struct {
        const char *name;
        oit_render_pack pack;
    } packs[] = {{"auto", OIT_RENDER_PACK_AUTO},
                 {"counted", OIT_RENDER_PACK_COUNTED},
                 {"budget", OIT_RENDER_PACK_BUDGET},
                 {"disjoint", OIT_RENDER_PACK_DISJOINT},
                 {"first-k", OIT_RENDER_PACK_FIRSTK}};
    static const oit_mesh empty;
    for (size_t i = 0; i < sizeof packs / sizeof *packs; i++) {
        oit_run_source so = {.path = path, .desc = {.pack = packs[i].pack}};
        oit_method_options opt = {.max_layers = 8, .source = &so, .gl = gl};
        char what[64];
        snprintf(what, sizeof what, "stream %s %s", packs[i].name, view_name);
        check_method(&stream, &empty, &opt, v, what);
    }
}

int main(int argc, char **argv)
{
    oit_partfile *pf = test_partfile_arg(argc, argv);
    oit_gl *gl = test_gl_open();
    oit_mesh mesh;
    scene(&mesh);
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    for (int ortho = 0; ortho < 2; ortho++) {
        const char *name = ortho ? "ortho translucent" : "persp transparent";
        oit_view v;
        make_view(mesh.info.bounds_min, mesh.info.bounds_max, ortho, &v);
        in_core(gl, &mesh, &v, name);
        make_view(sum.bounds_min, sum.bounds_max, ortho, &v);
        v.shading.attributes = sum.attributes;
        streamed(gl, argv[1], &v, name);
    }
    oit_partfile_close(pf);
    oit_gl_destroy(gl);
    return test_verdict();
}
