/* oit_renderer_draw_image: the frame resolved in memory through the
 * capture's own resolve, bit for bit the image the streamer (a part file)
 * or DFB (in core) renders of the same camera, shading and background
 * (the images oitstream writes), in transparent and translucent shading,
 * perspective and orthographic, each pack mode, over a coloured background
 * and the default white. Its oit_draw_stats carry the streamer's own
 * figures of the frame (order and pack time aside, which are clocks): the
 * second pass, the capture that ran and was asked for, the automatic
 * mode's choice, the readers; its per-pixel counts are DFB's. A program the caller deleted while current
 * (the streamer's here) is not bound again when liboit gives the GL state
 * back. Bad inputs fail with the documented status.
 *
 * usage: test_liboit_image FILE.oitp (a part file, e.g. from test_streamer) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "partfile/triangles.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "view/stream/streamer.h"
#include "tests/lib/test_check.h"
#include "tests/liboit/part_scene.h"
#include "tools/common/method_run.h"

enum { W = 96, H = 72 };

/* oit_camera_default's view, or the same orthographic (as high as the
 * frustum at the target). */
static oit_camera camera_of(const oit_scene_info *info, int ortho)
{
    oit_camera cam;
    oit_camera_default(&cam, info->bounds_min, info->bounds_max, 35.0f, 25.0f);
    if (ortho) {
        double d = 0.0;
        for (int k = 0; k < 3; k++)
            d += pow((double)cam.target[k] - cam.eye[k], 2.0);
        cam.projection = OIT_PROJ_ORTHOGRAPHIC;
        cam.ortho_height = (float)(2.0 * sqrt(d) * tan(22.5 * 3.14159265358979323846 / 180.0));
        cam.znear = 0.0f;
    }
    return cam;
}

/* The tools' view of the scene: their shading resolved as liboit resolves
 * its descriptor's (zero: defaults) over the scene's attributes. */
static oit_view tool_view(const oit_scene_info *info, const oit_camera *cam, int translucent,
                          const float *bg)
{
    oit_view v = {.camera = *cam, .width = W, .height = H};
    v.shading.mode = translucent ? OIT_SHADING_TRANSLUCENT : OIT_SHADING_TRANSPARENT;
    if (bg)
        memcpy(v.shading.background, bg, sizeof v.shading.background);
    v.shading.attributes = info->attributes;
    v.shading.scene_scale = oit_scene_scale(info->bounds_min, info->bounds_max);
    oit_shading_resolve_defaults(&v.shading);
    return v;
}

static void compare_bytes(const char *name, const float *got, const oit_image *want)
{
    size_t n = (size_t)W * H * 4, differ = 0, first = n;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&got[i], &want->rgba[i], sizeof *got) != 0 && differ++ == 0)
            first = i;
    CHECK(differ == 0, "%s: %zu of %zu floats differ from the tool's image, first at pixel "
          "%zu channel %zu: %.9g against %.9g", name, differ, n, first / 4, first % 4,
          first < n ? got[first] : 0.0, first < n ? want->rgba[first] : 0.0);
    double lit = 0.0;
    for (size_t i = 0; i < n; i++)
        lit += fabs(want->rgba[i] - want->rgba[i % 4]);
    CHECK(lit > 0.0, "%s: the image is uniform: nothing was drawn", name);
}

/* One part-file case: liboit's image and figures against the streamer's. */
static void check_stream(oit_scene *scene, oit_partfile *pf, const oit_scene_info *info,
                         oit_render_pack pack, int translucent, int ortho, const float *bg)
{
    char name[160];
    snprintf(name, sizeof name, "pack %d%s%s%s", (int)pack, translucent ? " translucent" : "",
             ortho ? " ortho" : "", bg ? " coloured background" : "");
    oit_error err = {0};
    oit_renderer_desc rd = {.pack = pack, .read_on_draw_thread = 1,
                            .cache_budget = OIT_RENDER_CACHE_OFF};
    rd.shading.mode = translucent ? OIT_RENDER_TRANSLUCENT : OIT_RENDER_TRANSPARENT;
    oit_renderer *r = NULL;
    CHECK(oit_renderer_create(&rd, &r, &err) == OIT_OK, "%s: %s", name, err.message);
    oit_camera cam = camera_of(info, ortho);
    oit_frame_camera fc = oit_run_camera(&cam);
    oit_frame f = {.viewport_width = W, .viewport_height = H, .camera = &fc};
    float *got = malloc((size_t)W * H * 4 * sizeof *got);
    oit_draw_stats st = {0};
    CHECK(oit_renderer_draw_image(r, scene, &f, bg, got, (size_t)W * H * 4 * sizeof *got, &st,
                                  &err) == OIT_OK, "%s: %s", name, err.message);

    /* The streamer as the tools drive it, with the descriptor liboit
     * resolved (K the scene's: 16 at most). */
    static const oit_render_pack modes[] = {OIT_RENDER_PACK_AUTO, OIT_RENDER_PACK_COUNTED, OIT_RENDER_PACK_BUDGET,
                                          OIT_RENDER_PACK_DISJOINT, OIT_RENDER_PACK_FIRSTK};
    oit_streamer_desc sd = {.K = info->K < 16 ? (int)info->K : 16, .pack = modes[pack],
                            .reader_threads = OIT_STREAM_READ_INLINE,
                            .cache_budget = OIT_STREAM_CACHE_OFF};
    oit_streamer *s = NULL;
    oit_image want = {0};
    oit_frame_stats fs = {0};
    oit_stream_frame_stats ss = {0};
    oit_view v = tool_view(info, &cam, translucent, bg);
    CHECK(oit_streamer_create(pf, &sd, &s, &err) == OIT_OK &&
              oit_streamer_render(s, &v, &want, &fs, &ss, &err) == OIT_OK,
          "%s: streamer: %s", name, err.message);
    compare_bytes(name, got, &want);
    printf("%s: %llu fragments, %u packs, second pass %llu pixels in %u packs, capture %s "
           "(asked %s), auto first-k %u\n", name, (unsigned long long)st.fragments, st.packs,
           (unsigned long long)st.second_pass_pixels, st.second_pass_packs,
           st.capture ? st.capture : "-", st.capture_asked ? st.capture_asked : "-",
           st.auto_first_k);
    CHECK(st.fragments == fs.fragments && st.packs == ss.packs && st.batches == fs.batches &&
              st.second_pass_pixels == fs.second_pass_pixels &&
              st.second_pass_packs == fs.second_pass_packs && st.capture_k == fs.capture_k &&
              st.auto_first_k == (uint32_t)ss.first_k &&
              st.front_first == (uint32_t)ss.front_first && st.reader_threads == 0 &&
              st.capture && fs.capture && !strcmp(st.capture, fs.capture) &&
              st.capture_asked && !strcmp(st.capture_asked, "auto") && st.order_ms >= 0.0 &&
              st.pack_ms >= 0.0 && st.budget_source && st.budget_source[0],
          "%s: figures: fragments %llu/%llu, packs %u/%u, second pass %llu/%llu in %u/%u, "
          "capture %s/%s K %u/%u, auto first-k %u/%d, front first %u/%d, readers %u, "
          "budget source %s", name, (unsigned long long)st.fragments,
          (unsigned long long)fs.fragments, st.packs, ss.packs,
          (unsigned long long)st.second_pass_pixels,
          (unsigned long long)fs.second_pass_pixels, st.second_pass_packs,
          fs.second_pass_packs, st.capture ? st.capture : "NULL",
          fs.capture ? fs.capture : "NULL", st.capture_k, fs.capture_k, st.auto_first_k,
          ss.first_k, st.front_first, ss.front_first, st.reader_threads,
          st.budget_source ? st.budget_source : "NULL");
    /* the automatic mode's choice, as the streamer made it: a first draw
     * takes the seed, with no costs yet; a fixed pack reports none */
    CHECK((st.choice == NULL) == (ss.choice_path == NULL) &&
              (!st.choice || (!strcmp(st.choice, ss.choice_path) && st.choice_why &&
                              !strcmp(st.choice_why, "seed") && st.choice_first_k_ms == -1.0 &&
                              st.choice_counted_ms == -1.0)) &&
              (st.choice != NULL) == (modes[pack] == OIT_RENDER_PACK_AUTO),
          "%s: choice %s (%s; %.1f, %.1f), the streamer's %s", name,
          st.choice ? st.choice : "NULL", st.choice_why ? st.choice_why : "NULL",
          st.choice_first_k_ms, st.choice_counted_ms,
          ss.choice_path ? ss.choice_path : "NULL");
    oit_image_free(&want);
    /* The streamer's program, deleted while current, stays the caller's
     * for the next case's draw: liboit must not bind it again. */
    oit_streamer_destroy(s);
    oit_renderer_destroy(r);
    free(got);
}

/* oit_frame.camera drives oit_renderer_draw too: blended over a target
 * cleared to the background, the frame equals the resolved image (within
 * the blend's float arithmetic, where the resolve pass computes in its own
 * order), and a wrong camera (the eye moved) would not. */
static void check_draw_camera(oit_scene *scene, const oit_scene_info *info)
{
    oit_error err = {0};
    oit_renderer *r = NULL;
    CHECK(oit_renderer_create(NULL, &r, &err) == OIT_OK, "draw camera: %s", err.message);
    oit_camera cam = camera_of(info, 1);
    oit_frame_camera fc = oit_run_camera(&cam);
    oit_frame f = {.viewport_width = W, .viewport_height = H, .camera = &fc};
    const float bg[4] = {0.2f, 0.4f, 0.6f, 1.0f};
    size_t n = (size_t)W * H * 4;
    float *img = malloc(n * sizeof *img), *fb = malloc(n * sizeof *fb);
    CHECK(oit_renderer_draw_image(r, scene, &f, bg, img, n * sizeof *img, NULL, &err) == OIT_OK,
          "draw camera: image: %s", err.message);
    GLuint tex, fbo;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, W, H);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE); /* the streamer's resolve leaves it off */
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, bg);
    f.framebuffer = fbo;
    CHECK(oit_renderer_draw(r, scene, &f, NULL, &err) == OIT_OK, "draw camera: %s",
          err.message);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof *fb), fb);
    double worst = 0.0;
    for (int y = 0; y < H; y++) /* GL rows bottom first, the image's top first */
        for (int x = 0; x < W * 3; x++) {
            double d = fabs(fb[((size_t)(H - 1 - y) * W) * 4 + (x / 3) * 4 + x % 3] -
                            img[((size_t)y * W) * 4 + (x / 3) * 4 + x % 3]);
            worst = d > worst ? d : worst;
        }
    printf("draw camera: blended against resolved, max %.3g\n", worst);
    CHECK(worst < 1e-5, "draw camera: the blended frame differs from the image by %g", worst);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    free(img);
    free(fb);
    oit_renderer_destroy(r);
}

/* The stream's per-pixel fragment counts (oit_pixels_desc.counts, the
 * viewer's heat map): in each pack mode those DFB gives the file's
 * triangles in core, pixel for pixel, adding up to the draw's fragments. */
static void check_counts(oit_scene *scene, oit_partfile *pf, const oit_scene_info *info)
{
    oit_error err = {0};
    oit_mesh mesh = {0};
    CHECK(oit_partfile_load_mesh(pf, &mesh, &err) == OIT_OK, "counts: load: %s", err.message);
    oit_camera cam = camera_of(info, 0);
    oit_view v = tool_view(info, &cam, 0, NULL);
    size_t n = (size_t)W * H;
    uint32_t *want = calloc(n, sizeof *want), *got = malloc(n * sizeof *got);
    float *rgba = malloc(n * 4 * sizeof *rgba);
    oit_dfb *d = NULL;
    oit_gpu_mesh *gm = NULL;
    oit_image img = {0};
    oit_frame_stats fs = {0};
    CHECK(oit_dfb_create(&d, &err) == OIT_OK &&
              oit_gpu_mesh_create(mesh.tris, mesh.count, 0, &gm, &err) == OIT_OK &&
              oit_dfb_render(d, (const oit_gpu_mesh *const[]){gm}, 1, &v, &img, want, &fs,
                             &err) == OIT_OK,
          "counts: DFB: %s", err.message);
    /* the last in bands of 20 rows, each band's counts in its rows (but
     * for a pixel centre on a silhouette at a band's edge) */
    static const oit_render_pack packs[] = {OIT_RENDER_PACK_AUTO, OIT_RENDER_PACK_COUNTED,
                                            OIT_RENDER_PACK_FIRSTK, OIT_RENDER_PACK_BUDGET,
                                            OIT_RENDER_PACK_AUTO};
    size_t cases = sizeof packs / sizeof *packs;
    for (size_t k = 0; k < cases; k++) {
        oit_renderer *r = NULL;
        oit_renderer_desc rd = {.pack = packs[k], .read_on_draw_thread = 1};
        size_t allowed = 0;
        if (k == cases - 1) {
            rd.binding_limit = (uint64_t)W * oit_streamer_pixel_bytes(&v) * 20;
            allowed = n / 200;
        }
        oit_frame_camera fc = oit_run_camera(&cam);
        oit_frame f = {.viewport_width = W, .viewport_height = H, .camera = &fc};
        oit_pixels_desc px = {.rgba = rgba, .rgba_bytes = n * 4 * sizeof *rgba, .counts = got};
        oit_draw_stats st = {0};
        memset(got, 0xff, n * sizeof *got);
        oit_status s = oit_renderer_create(&rd, &r, &err);
        if (s == OIT_OK)
            s = oit_renderer_draw_pixels(r, scene, &f, &px, &st, &err);
        CHECK(s == OIT_OK, "counts, pack %d: %s", (int)packs[k], err.message);
        size_t differ = 0, first = n;
        uint64_t sum = 0;
        for (size_t i = 0; s == OIT_OK && i < n; i++) {
            sum += got[i];
            if (got[i] != want[i] && differ++ == 0)
                first = i;
        }
        CHECK(s != OIT_OK || (differ <= allowed && sum == st.fragments && sum > 0 &&
                              (allowed || sum == fs.fragments)),
              "counts, pack %d%s: %zu of %zu pixels differ from DFB's (first %zu: %u against "
              "%u); they add up to %llu, the draw's fragments %llu, DFB's %llu",
              (int)packs[k], allowed ? " in bands" : "", differ, n, first,
              first < n ? got[first] : 0,
              first < n ? want[first] : 0, (unsigned long long)sum,
              (unsigned long long)st.fragments, (unsigned long long)fs.fragments);
        oit_renderer_destroy(r);
    }
    oit_image_free(&img);
    oit_gpu_mesh_destroy(gm);
    oit_dfb_destroy(d);
    oit_mesh_free(&mesh);
    free(want);
    free(got);
    free(rgba);
}

/* The file's triangles in core: liboit's image against DFB's. */
static void check_in_core(oit_partfile *pf, const oit_scene_info *info)
{
    oit_error err = {0};
    oit_mesh mesh = {0};
    CHECK(oit_partfile_load_mesh(pf, &mesh, &err) == OIT_OK, "load: %s", err.message);
    float *pos = NULL;
    uint8_t *rgba = NULL;
    mesh_soup(&mesh, &pos, &rgba);
    oit_scene_mesh_desc md = {.positions = pos, .vertex_count = mesh.count * 3,
                              .colours = (info->attributes & OIT_ATTR_COLOUR) ? rgba : NULL};
    oit_scene *core = NULL;
    CHECK(oit_scene_create_mesh(&md, &core, &err) == OIT_OK, "in core: %s", err.message);
    oit_renderer *r = NULL;
    CHECK(oit_renderer_create(NULL, &r, &err) == OIT_OK, "in core: %s", err.message);
    oit_camera cam = camera_of(info, 0);
    oit_frame_camera fc = oit_run_camera(&cam);
    oit_frame f = {.viewport_width = W, .viewport_height = H, .camera = &fc};
    float *got = malloc((size_t)W * H * 4 * sizeof *got);
    oit_draw_stats st = {0};
    CHECK(oit_renderer_draw_image(r, core, &f, NULL, got, (size_t)W * H * 4 * sizeof *got, &st,
                                  &err) == OIT_OK, "in core: %s", err.message);
    oit_dfb *d = NULL;
    oit_gpu_mesh *gm = NULL;
    oit_image want = {0};
    oit_frame_stats fs = {0};
    oit_view v = tool_view(info, &cam, 0, NULL);
    CHECK(oit_dfb_create(&d, &err) == OIT_OK &&
              oit_gpu_mesh_create(mesh.tris, mesh.count, 0, &gm, &err) == OIT_OK &&
              oit_dfb_render(d, (const oit_gpu_mesh *const[]){gm}, 1, &v, &want, NULL, &fs,
                             &err) == OIT_OK,
          "in core: DFB: %s", err.message);
    compare_bytes("in core", got, &want);
    CHECK(st.fragments == fs.fragments && st.capture == NULL && st.order_ms == 0.0,
          "in core: fragments %llu (DFB %llu), capture %s", (unsigned long long)st.fragments,
          (unsigned long long)fs.fragments, st.capture ? st.capture : "NULL");
    oit_image_free(&want);
    oit_gpu_mesh_destroy(gm);
    oit_dfb_destroy(d);
    oit_renderer_destroy(r);
    oit_scene_close(core);
    oit_mesh_free(&mesh);
    free(pos);
    free(rgba);
    free(got);
}

static void check_errors(oit_scene *scene, const oit_scene_info *info)
{
    oit_error err = {0};
    oit_renderer *r = NULL;
    /* K's range is the capture's (OIT_CAPTURE_K_MIN/MAX), checked from
     * liboit/desc_ranges.h, named in liboit's spelling. */
    static const uint32_t ks[] = {1, 2, 16, 17};
    for (int i = 0; i < 4; i++) {
        oit_status ks_s = oit_renderer_create(&(oit_renderer_desc){.K = ks[i]}, &r, &err);
        int in = ks[i] >= 2 && ks[i] <= 16;
        CHECK(in ? ks_s == OIT_OK
                 : ks_s == OIT_ERR_ARGUMENT && strstr(err.message, "oit_renderer_desc.K = ") &&
                       strstr(err.message, "expected 0 (the scene's K) or 2..16"),
              "K %u: %d %s", ks[i], ks_s, in ? "" : err.message);
        oit_renderer_destroy(r);
        r = NULL;
    }
    CHECK(oit_renderer_create(NULL, &r, &err) == OIT_OK, "%s", err.message);
    oit_camera cam = camera_of(info, 0);
    oit_frame_camera fc = oit_run_camera(&cam);
    oit_frame f = {.viewport_width = W, .viewport_height = H, .camera = &fc};
    float px[4];
    oit_status s = oit_renderer_draw_image(r, scene, &f, NULL, px, sizeof px, NULL, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "bytes"), "small buffer: %d %s", s,
          err.message);
    float *big = malloc((size_t)W * H * 4 * sizeof *big);
    oit_frame_camera bad = fc;
    memcpy(bad.target, bad.eye, sizeof bad.target);
    f.camera = &bad;
    s = oit_renderer_draw_image(r, scene, &f, NULL, big, (size_t)W * H * 16, NULL, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "oit_frame.camera"),
          "eye = target: %d %s", s, err.message);
    bad = fc;
    bad.fovy_deg = 180.0f;
    s = oit_renderer_draw_image(r, scene, &f, NULL, big, (size_t)W * H * 16, NULL, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "fovy"), "fovy 180: %d %s", s,
          err.message);
    f.camera = &fc;
    f.depth_texture = 1;
    s = oit_renderer_draw_image(r, scene, &f, NULL, big, (size_t)W * H * 16, NULL, &err);
    CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "depth_texture"),
          "depth texture: %d %s", s, err.message);
    free(big);
    oit_renderer_destroy(r);
}

int main(int argc, char **argv)
{
    part_scene ps = open_part_scene(argc, argv);
    const float bg[3] = {0.2f, 0.4f, 0.6f};
    check_errors(ps.scene, &ps.info);
    check_stream(ps.scene, ps.pf, &ps.info, OIT_RENDER_PACK_AUTO, 0, 0, NULL);
    check_stream(ps.scene, ps.pf, &ps.info, OIT_RENDER_PACK_AUTO, 1, 0, bg);
    check_stream(ps.scene, ps.pf, &ps.info, OIT_RENDER_PACK_FIRSTK, 0, 1, bg);
    check_stream(ps.scene, ps.pf, &ps.info, OIT_RENDER_PACK_COUNTED, 0, 0, bg);
    check_stream(ps.scene, ps.pf, &ps.info, OIT_RENDER_PACK_BUDGET, 0, 0, NULL);
    check_draw_camera(ps.scene, &ps.info);
    check_in_core(ps.pf, &ps.info);
    check_counts(ps.scene, ps.pf, &ps.info);
    oit_partfile_close(ps.pf);
    oit_scene_close(ps.scene);
    return test_gl_verdict(ps.gl);
}
