/* liboit at 2048x2048 (2^22 pixels): the part file streamed and the same
 * triangles in core, transparent (one storage binding holds the state: the
 * end pass alone passes 65535 work groups of 64) and translucent (48 bytes
 * a pixel: drawn in two bands, each captured and blended in turn), into a
 * caller's framebuffer at an offset, against DFB's image of the file. A
 * translucent draw with a depth texture that occludes the lowest rows
 * (depth 0) and nothing above (1) checks that each band reads the opaque
 * depth at its own rows with its own projection: the occluded rows keep
 * the clear colour, the others DFB's image. A viewport wider than the GL
 * renders fails, naming the limit.
 *
 * usage: test_liboit_sizes FILE.oitp (a part file, e.g. from test_streamer) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "partfile/triangles.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "tests/lib/test_check.h"
#include "tests/liboit/caller_fbo.h"
#include "tests/liboit/part_scene.h"

enum {
    W = 2048,
    H = 2048,
    PAD_X = 8,
    PAD_Y = 4,
    FW = W + 2 * PAD_X,
    FH = H + 2 * PAD_Y,
    OCCLUDED = 1100 /* GL rows of the viewport behind depth 0: into both bands */
};
static const float kClear[4] = {0.2f, 0.4f, 0.6f, 1.0f};

/* Cleared to kClear; with_depth: a depth texture, 0 in the viewport's
 * first OCCLUDED rows, 1 elsewhere. */
static caller_fbo target_make(int with_depth)
{
    caller_fbo t = caller_fbo_make(FW, FH, kClear);
    if (with_depth) {
        float *d = malloc(sizeof *d * FW * FH);
        for (int y = 0; y < FH; y++)
            for (int x = 0; x < FW; x++)
                d[(size_t)y * FW + x] = y < PAD_Y + OCCLUDED ? 0.0f : 1.0f;
        glCreateTextures(GL_TEXTURE_2D, 1, &t.depth);
        glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, FW, FH);
        glTextureSubImage2D(t.depth, 0, 0, 0, FW, FH, GL_DEPTH_COMPONENT, GL_FLOAT, d);
        free(d);
    }
    return t;
}

/* The default view from twice as far (the scene on a tenth of the frame:
 * fewer fragments to wait for on llvmpipe). */
static void view_of(const oit_scene_info *info, oit_shading_mode mode, oit_view *v)
{
    *v = (oit_view){0};
    oit_camera *c = &v->camera;
    oit_camera_default(c, info->bounds_min, info->bounds_max, 35.0f, 25.0f);
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->target[k] + 2.0f * (c->eye[k] - c->target[k]);
    c->znear *= 0.5f;
    c->zfar *= 2.0f;
    v->width = W;
    v->height = H;
    v->shading.mode = mode;
    v->shading.attributes = info->attributes;
    v->shading.scene_scale = oit_scene_scale(info->bounds_min, info->bounds_max);
    memcpy(v->shading.background, kClear, sizeof v->shading.background);
}

/* DFB's image of the file: its colour buffer (16 bytes a pixel) fits one
 * binding at this size, so it is not banded. */
static int reference(const oit_mesh *mesh, const oit_view *v, oit_image *out, oit_frame_stats *fs)
{
    if (out->rgba)
        return 1; /* made for an earlier case */
    oit_error err = {0};
    oit_dfb *d = NULL;
    oit_gpu_mesh *gm = NULL;
    oit_status s = oit_dfb_create(&d, &err);
    if (s == OIT_OK)
        s = oit_gpu_mesh_create(mesh->tris, mesh->count, 0, &gm, &err);
    if (s == OIT_OK) {
        const oit_gpu_mesh *list[1] = {gm};
        s = oit_dfb_render(d, list, 1, v, out, NULL, fs, &err);
    }
    oit_gpu_mesh_destroy(gm);
    oit_dfb_destroy(d);
    glUseProgram(0); /* liboit gives back the program current at a draw: not a deleted one */
    CHECK(s == OIT_OK, "reference: %s", err.message);
    return s == OIT_OK;
}

/* The viewport against ref (the rows below `occluded` against the clear
 * colour instead): at most 0.01% of pixels over 1/255; the border keeps
 * the clear colour. */
static void compare(const char *name, const caller_fbo *t, const oit_image *ref, int occluded)
{
    viewport_diff d = caller_fbo_compare(name, t, PAD_X, PAD_Y, ref, kClear, occluded,
                                         COVER_R | COVER_B);
    CHECK(d.pct <= 0.01, "%s: %.4f%% of pixels differ from DFB by more than 1/255", name, d.pct);
    CHECK(d.cov >= 2.0, "%s: only %.1f%% of the frame is covered", name, d.cov);
    CHECK(d.border_bad == 0, "%s: %llu pixels outside the viewport changed", name,
          (unsigned long long)d.border_bad);
}

/* DFB's image of each shading, made once. */
typedef struct refs {
    oit_image img[2];
    oit_frame_stats st[2];
} refs;

static void draw_and_compare(const char *name, oit_scene *scene, const oit_mesh *mesh, refs *refs,
                             oit_render_shading_mode mode, int with_depth)
{
    oit_error err = {0};
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);
    oit_renderer_desc rd = {0};
    rd.shading.mode = mode;
    oit_renderer *r = NULL;
    if (oit_renderer_create(&rd, &r, &err) != OIT_OK) {
        CHECK(0, "%s: oit_renderer_create: %s", name, err.message);
        return;
    }
    oit_view v;
    view_of(&info, (oit_shading_mode)mode, &v);
    oit_frame f = {0};
    oit_camera_view_matrix(&v.camera, f.view);
    oit_camera_proj_matrix(&v.camera, (float)W / H, f.projection);
    f.viewport_x = PAD_X;
    f.viewport_y = PAD_Y;
    f.viewport_width = W;
    f.viewport_height = H;
    caller_fbo t = target_make(with_depth);
    f.framebuffer = t.fbo;
    f.depth_texture = t.depth;
    oit_draw_stats st = {0};
    oit_status s = oit_renderer_draw(r, scene, &f, &st, &err);
    CHECK(s == OIT_OK, "%s: draw: %s", name, err.message);
    printf("%s: %.0f ms, %llu fragments, max %u layers, %u packs\n", name, st.ms,
           (unsigned long long)st.fragments, st.max_layers, st.packs);
    oit_image *ref = &refs->img[mode];
    const oit_frame_stats *rs = &refs->st[mode];
    if (s == OIT_OK && reference(mesh, &v, ref, &refs->st[mode])) {
        /* The camera liboit makes of the matrices rounds apart from v's:
         * a few edge pixels gain or lose a fragment. */
        uint64_t most = rs->fragments + rs->fragments / 10000, least = 2 * rs->fragments - most;
        CHECK(with_depth ? st.fragments < least : st.fragments >= least && st.fragments <= most,
              "%s: %llu fragments, DFB %llu", name, (unsigned long long)st.fragments,
              (unsigned long long)rs->fragments);
        compare(name, &t, ref, with_depth ? OCCLUDED : 0);
    }
    caller_fbo_free(&t);
    oit_renderer_destroy(r);
}

/* One pixel wider than GL_MAX_FRAMEBUFFER_WIDTH: no band can be that wide. */
static void check_too_wide(oit_scene *scene)
{
    GLint most = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &most);
    oit_error err = {0};
    oit_renderer *r = NULL;
    CHECK(oit_renderer_create(NULL, &r, &err) == OIT_OK, "%s", err.message);
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);
    oit_view v;
    view_of(&info, OIT_SHADING_TRANSPARENT, &v);
    oit_frame f = {.viewport_width = most + 1, .viewport_height = 16};
    oit_camera_view_matrix(&v.camera, f.view);
    oit_camera_proj_matrix(&v.camera, (float)f.viewport_width / 16, f.projection);
    oit_status s = r ? oit_renderer_draw(r, scene, &f, NULL, &err) : OIT_ERR_ARGUMENT;
    printf("viewport %dx16: %s\n", most + 1, err.message);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "GL_MAX_FRAMEBUFFER_WIDTH"),
          "a viewport %d wide: status %d, \"%s\"", most + 1, (int)s, err.message);
    oit_renderer_destroy(r);
}

int main(int argc, char **argv)
{
    part_scene ps = open_part_scene(argc, argv);
    oit_error err = {0};
    oit_mesh mesh = {0};
    if (oit_partfile_load_mesh(ps.pf, &mesh, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    check_too_wide(ps.scene);
    refs refs = {0};
    draw_and_compare("stream transparent", ps.scene, &mesh, &refs, OIT_RENDER_TRANSPARENT, 0);
    draw_and_compare("stream translucent", ps.scene, &mesh, &refs, OIT_RENDER_TRANSLUCENT, 0);
    draw_and_compare("stream translucent, depth", ps.scene, &mesh, &refs, OIT_RENDER_TRANSLUCENT, 1);

    /* The same triangles in core: DFB through liboit, its state banded. */
    float *pos = NULL;
    uint8_t *rgba = NULL;
    mesh_soup(&mesh, &pos, &rgba);
    oit_scene_mesh_desc md = {.positions = pos,
                              .vertex_count = mesh.count * 3,
                              .colours = (ps.info.attributes & OIT_ATTR_COLOUR) ? rgba : NULL,
                              .name = "grid arrays"};
    oit_scene *core = NULL;
    CHECK(oit_scene_create_mesh(&md, &core, &err) == OIT_OK, "%s", err.message);
    free(pos);
    free(rgba);
    if (core) {
        draw_and_compare("in-core translucent, depth", core, &mesh, &refs, OIT_RENDER_TRANSLUCENT,
                         1);
        oit_scene_close(core);
    }
    for (int i = 0; i < 2; i++)
        oit_image_free(&refs.img[i]);
    oit_mesh_free(&mesh);
    oit_partfile_close(ps.pf);
    oit_scene_close(ps.scene);
    oit_gl_destroy(ps.gl);
    return test_verdict();
}
