/* liboit against DFB: a part file drawn through the public API into an FBO
 * the test owns, pre-cleared to a known colour, must equal DFB's image of the
 * same triangles with that colour as background (dst = C + T * clear), in
 * transparent and translucent shading (per-channel T) and at a viewport
 * offset; pixels outside the viewport stay untouched; the caller's GL state
 * comes back; bad inputs fail with the documented status. The same file's
 * triangles as an in-core scene (oit_scene_create_mesh) pass the same
 * checks through the same oit_renderer_draw, and both again through
 * orthographic, off-centre and infinite-far projection matrices.
 * Linear-light compositing into an sRGB (GL_SRGB8_ALPHA8) target stores the
 * bytes of DFB's linear-mode image (check_linear_srgb_target).
 *
 * usage: test_liboit FILE.oitp (a part file, e.g. from test_streamer) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/image.h"
#include "partfile/triangles.h"
#include "tests/lib/test_check.h"
#include "tests/liboit/caller_fbo.h"
#include "tests/liboit/part_scene.h"

enum { W = 160, H = 120, PAD_X = 8, PAD_Y = 4, FW = W + 2 * PAD_X, FH = H + 2 * PAD_Y };
static const float kClear[4] = {0.2f, 0.4f, 0.6f, 1.0f};

enum { PROJ_DEFAULT, PROJ_ORTHO, PROJ_OFFCENTRE, PROJ_INFINITE };
static const char *const kProjName[] = {"", " ortho", " off-centre", " infinite far"};

/* The default perspective, or the same view orthographic (the volume as
 * high as the frustum at the target, its near plane behind the eye),
 * off-centre (a window shifted right and down) or with an infinite far
 * plane. */
static void camera_for(const oit_scene_info *info, oit_camera *cam, int proj)
{
    oit_camera_default(cam, info->bounds_min, info->bounds_max, 35.0f, 25.0f);
    double dist = 0.0, ty = tan(0.5 * cam->fovy_deg * 3.14159265358979323846 / 180.0);
    for (int k = 0; k < 3; k++)
        dist += pow((double)cam->target[k] - cam->eye[k], 2.0);
    dist = sqrt(dist);
    double a = (double)W / H;
    if (proj == PROJ_ORTHO) {
        cam->projection = OIT_PROJ_ORTHOGRAPHIC;
        cam->ortho_height = (float)(2.0 * dist * ty);
        cam->znear = (float)(cam->znear - 0.5 * dist);
    } else if (proj == PROJ_OFFCENTRE) {
        cam->window[0] = (float)(-0.7 * ty * a);
        cam->window[1] = (float)(1.3 * ty * a);
        cam->window[2] = (float)(-1.2 * ty);
        cam->window[3] = (float)(0.8 * ty);
    } else if (proj == PROJ_INFINITE) {
        cam->zfar = INFINITY;
    }
}

/* The W x H view from camera_for's camera, and the caller's frame of it:
 * its matrices, drawing into a W x H viewport at the origin. */
static void view_and_frame(const oit_scene_info *info, int proj, oit_view *v, oit_frame *f)
{
    *v = (oit_view){0};
    camera_for(info, &v->camera, proj);
    v->width = W;
    v->height = H;
    *f = (oit_frame){0};
    oit_camera_view_matrix(&v->camera, f->view);
    oit_camera_proj_matrix(&v->camera, (float)W / H, f->projection);
    f->viewport_width = W;
    f->viewport_height = H;
}

/* DFB's image of the whole file with the clear colour as background. */
static int reference(oit_partfile *pf, const oit_view *v, oit_image *out,
                     oit_frame_stats *fs)
{
    oit_error err = {0};
    oit_mesh mesh = {0};
    oit_dfb *d = NULL;
    oit_gpu_mesh *gm = NULL;
    oit_status s = oit_partfile_load_mesh(pf, &mesh, &err);
    if (s == OIT_OK)
        s = oit_dfb_create(&d, &err);
    if (s == OIT_OK)
        s = oit_gpu_mesh_create(mesh.tris, mesh.count, 0, &gm, &err);
    if (s == OIT_OK) {
        const oit_gpu_mesh *list[1] = {gm};
        s = oit_dfb_render(d, list, 1, v, out, NULL, fs, &err);
    }
    oit_gpu_mesh_destroy(gm);
    oit_dfb_destroy(d);
    oit_mesh_free(&mesh);
    CHECK(s == OIT_OK, "reference: %s", err.message);
    return s == OIT_OK;
}

/* Compares the viewport of the target with ref; the border must still hold
 * the clear colour. */
static void compare(const char *name, const caller_fbo *t, const oit_image *ref)
{
    viewport_diff d = caller_fbo_compare(name, t, PAD_X, PAD_Y, ref, kClear, 0,
                                         COVER_R | COVER_G | COVER_B);
    CHECK(d.pct <= 0.1, "%s: %.4f%% of pixels differ from DFB by more than 1/255", name, d.pct);
    CHECK(d.cov >= 10.0, "%s: only %.1f%% of the frame is covered: the view misses the scene",
          name, d.cov);
    CHECK(d.border_bad == 0, "%s: %llu pixels outside the viewport changed", name,
          (unsigned long long)d.border_bad);
}

static void check_state_restored(GLuint fbo)
{
    GLint bound = 0, vp[4], src = 0, blend = 0, prog = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_BLEND_SRC_RGB, &src);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    blend = glIsEnabled(GL_BLEND);
    CHECK((GLuint)bound == fbo && vp[0] == 1 && vp[1] == 2 && vp[2] == 3 && vp[3] == 4 &&
              src == GL_SRC_ALPHA && blend && prog == 0,
          "GL state not restored: fbo %d viewport %d,%d,%d,%d blend %d src 0x%x program %d",
          bound, vp[0], vp[1], vp[2], vp[3], blend, src, prog);
}

/* The GPU time of an earlier draw arrives within a few draws (timestamp
 * queries read without waiting), its phases adding up to it; a part file
 * reports the memory it chose: a total only where the driver says how
 * much is free (none on llvmpipe), the ring and the capture always. */
static void check_gpu_stats(const char *name, oit_renderer *r, oit_scene *scene,
                            const oit_frame *f, int part_file)
{
    oit_error err = {0};
    oit_draw_stats st = {0};
    int draws = 2; /* the caller's */
    /* liboit blends over what a target holds */
    caller_fbo scratch = caller_fbo_make(FW, FH, kClear);
    oit_frame g = *f;
    g.framebuffer = scratch.fbo;
    for (int i = 0; i < 8 && st.gpu_frame == 0; i++, draws++)
        CHECK(oit_renderer_draw(r, scene, &g, &st, &err) == OIT_OK, "%s: %s", name,
              err.message);
    caller_fbo_free(&scratch);
    double sum = 0;
    for (int p = 0; p < OIT_DRAW_GPU_PHASES; p++)
        sum += st.gpu_phase_ms[p];
    printf("%s: draw %llu took %.3f ms on the GPU; budget %llu (ring %llu, cache %llu, "
           "capture %llu, driver free %llu)\n", name, (unsigned long long)st.gpu_frame,
           st.gpu_ms, (unsigned long long)st.gpu_budget, (unsigned long long)st.ring_budget,
           (unsigned long long)st.cache_budget, (unsigned long long)st.capture_budget,
           (unsigned long long)st.gpu_free_bytes);
    CHECK(st.gpu_frame >= 1 && st.gpu_frame <= (uint64_t)draws + 1 && st.gpu_ms > 0 &&
              fabs(sum - st.gpu_ms) <= 1e-6 * (1 + st.gpu_ms),
          "%s: GPU figures of draw %llu: %.6f ms, phases %.6f", name,
          (unsigned long long)st.gpu_frame, st.gpu_ms, sum);
    CHECK(!part_file || (st.ring_budget > 0 && st.capture_budget > 0 &&
                         (st.gpu_budget == 0) == (st.gpu_free_bytes == 0)),
          "%s: budget %llu, ring %llu, capture %llu, driver free %llu", name,
          (unsigned long long)st.gpu_budget, (unsigned long long)st.ring_budget,
          (unsigned long long)st.capture_budget, (unsigned long long)st.gpu_free_bytes);
    /* The resolved descriptor says what the figures say. */
    oit_renderer_desc rd;
    oit_renderer_get_desc(r, &rd);
    uint64_t cache = st.cache_budget ? st.cache_budget : OIT_RENDER_CACHE_OFF;
    printf("%s: resolved K %u, ring %llu, cache %llu, total %llu, capture %d, alpha %g, "
           "scene scale %g\n", name, rd.K, (unsigned long long)rd.upload_budget,
           (unsigned long long)rd.cache_budget, (unsigned long long)rd.gpu_budget,
           (int)rd.capture, (double)rd.shading.alpha, (double)rd.shading.scene_scale);
    CHECK(rd.shading.alpha > 0.0f && rd.shading.absorption > 0.0f &&
              rd.shading.scene_scale > 0.0f,
          "%s: shading defaults not resolved: alpha %g, absorption %g, scene scale %g", name,
          (double)rd.shading.alpha, (double)rd.shading.absorption,
          (double)rd.shading.scene_scale);
    CHECK(!part_file || (rd.K >= 2 && rd.K <= 16 && rd.upload_budget == st.ring_budget &&
                         rd.cache_budget == cache && rd.gpu_budget == st.gpu_budget &&
                         !rd.read_on_draw_thread),
          "%s: resolved K %u, ring %llu (stats %llu), cache %llu (stats %llu), total %llu "
          "(stats %llu), on the draw thread %d", name, rd.K,
          (unsigned long long)rd.upload_budget, (unsigned long long)st.ring_budget,
          (unsigned long long)rd.cache_budget, (unsigned long long)st.cache_budget,
          (unsigned long long)rd.gpu_budget, (unsigned long long)st.gpu_budget,
          rd.read_on_draw_thread);
    CHECK(!part_file || !st.capture_slots ||
              (int)rd.capture == (!strcmp(st.capture_slots, "stencil")
                                      ? (int)OIT_RENDER_CAPTURE_STENCIL
                                      : (int)OIT_RENDER_CAPTURE_ARRAY),
          "%s: resolved capture %d, the draw's slots %s", name, (int)rd.capture,
          st.capture_slots);
}

static void draw_and_compare_proj(const char *base, oit_scene *scene, oit_partfile *pf,
                                  oit_render_shading_mode mode, oit_render_pack pack, int proj)
{
    char name[128];
    snprintf(name, sizeof name, "%s%s", base, kProjName[proj]);
    oit_error err = {0};
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);
    oit_renderer_desc rd = {0};
    rd.shading.mode = mode;
    rd.pack = pack;
    oit_renderer *r = NULL;
    if (oit_renderer_create(&rd, &r, &err) != OIT_OK) {
        CHECK(0, "%s: oit_renderer_create: %s", name, err.message);
        return;
    }
    oit_renderer_desc given;
    oit_renderer_get_desc(r, &given); /* before any draw: as given */
    CHECK(given.K == rd.K && given.upload_budget == 0 && given.cache_budget == 0 &&
              given.pack == pack && given.shading.mode == mode && given.shading.alpha == 0.0f,
          "%s: the descriptor before a draw is not the one given: K %u ring %llu cache %llu "
          "pack %d alpha %g", name, given.K, (unsigned long long)given.upload_budget,
          (unsigned long long)given.cache_budget, (int)given.pack, (double)given.shading.alpha);
    oit_view v;
    oit_frame f;
    view_and_frame(&info, proj, &v, &f);
    f.viewport_x = PAD_X;
    f.viewport_y = PAD_Y;
    caller_fbo t = caller_fbo_make(FW, FH, kClear);
    f.framebuffer = t.fbo;

    /* A caller's state that the draw must give back. */
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(1, 2, 3, 4);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(0);
    oit_draw_stats st = {0};
    oit_status s = oit_renderer_draw(r, scene, &f, &st, &err);
    CHECK(s == OIT_OK, "%s: draw: %s", name, err.message);
    check_state_restored(0);
    glDisable(GL_BLEND);
    printf("%s: %.2f ms, %llu fragments, max %u layers, %llu overflow, %u packs, %llu parts "
           "drawn, %llu culled, %llu bytes uploaded, %llu draw calls\n", name, st.ms,
           (unsigned long long)st.fragments, st.max_layers,
           (unsigned long long)st.overflow_pixels, st.packs,
           (unsigned long long)st.parts_drawn, (unsigned long long)st.parts_culled,
           (unsigned long long)st.bytes_uploaded, (unsigned long long)st.draw_calls);

    /* Again into a fresh target: the parts now come from the residency
     * cache (nothing uploaded), and the image must not change. */
    caller_fbo t2 = caller_fbo_make(FW, FH, kClear);
    f.framebuffer = t2.fbo;
    oit_draw_stats st2 = {0};
    if (s == OIT_OK && info.in_core) {
        /* An in-core scene is uploaded once, at its first draw. */
        s = oit_renderer_draw(r, scene, &f, &st2, &err);
        CHECK(s == OIT_OK, "%s: second draw: %s", name, err.message);
        CHECK(st.bytes_uploaded == info.triangles * sizeof(oit_triangle) &&
                  st2.bytes_uploaded == 0 && st2.fragments == st.fragments && st.packs >= 1,
              "%s: in core: uploaded %llu then %llu bytes for %llu triangles; %llu then %llu "
              "fragments", name, (unsigned long long)st.bytes_uploaded,
              (unsigned long long)st2.bytes_uploaded, (unsigned long long)info.triangles,
              (unsigned long long)st.fragments, (unsigned long long)st2.fragments);
    } else if (s == OIT_OK) {
        s = oit_renderer_draw(r, scene, &f, &st2, &err);
        CHECK(s == OIT_OK, "%s: second draw: %s", name, err.message);
        printf("%s: second draw: %llu bytes uploaded, %llu parts from the cache, %llu bytes "
               "resident, %llu draw calls\n", name, (unsigned long long)st2.bytes_uploaded,
               (unsigned long long)st2.cache_hits, (unsigned long long)st2.cache_bytes,
               (unsigned long long)st2.draw_calls);
        /* Everything from the cache: one multi-draw a pack and geometry
         * pass (the counted capture has two: count, then store), however
         * many parts the pack holds. */
        CHECK(st.draw_calls >= st.packs && st2.draw_calls >= st2.packs &&
                  st2.draw_calls <= 2 * (uint64_t)st2.packs && st2.parts_drawn > 2 * st2.packs,
              "%s: %llu draw calls for %u packs (second draw %llu for %u packs, %llu parts)",
              name, (unsigned long long)st.draw_calls, st.packs,
              (unsigned long long)st2.draw_calls, st2.packs,
              (unsigned long long)st2.parts_drawn);
        CHECK(st.bytes_uploaded > 0 && st2.bytes_uploaded == 0 &&
                  st2.cache_hits == st2.parts_drawn && st2.cache_bytes > 0,
              "%s: second draw uploaded %llu bytes (first %llu), %llu of %llu parts cached",
              name, (unsigned long long)st2.bytes_uploaded,
              (unsigned long long)st.bytes_uploaded, (unsigned long long)st2.cache_hits,
              (unsigned long long)st2.parts_drawn);
    }
    /* More draws, into a target of their own. */
    if (s == OIT_OK)
        check_gpu_stats(name, r, scene, &f, !info.in_core);

    oit_image ref = {0};
    oit_frame_stats rs = {0};
    v.shading = (oit_shading){0};
    v.shading.mode = (oit_shading_mode)mode;
    v.shading.attributes = info.attributes;
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += pow((double)info.bounds_max[k] - info.bounds_min[k], 2.0);
    v.shading.scene_scale = (float)sqrt(d2);
    memcpy(v.shading.background, kClear, sizeof v.shading.background);
    if (s == OIT_OK && reference(pf, &v, &ref, &rs)) {
        printf("%s: DFB %llu fragments\n", name, (unsigned long long)rs.fragments);
        CHECK(st.fragments == rs.fragments, "%s: %llu fragments, DFB %llu: lost or extra "
              "triangles", name, (unsigned long long)st.fragments,
              (unsigned long long)rs.fragments);
        CHECK(st.overflow_pixels == 0, "%s: %llu overflow pixels", name,
              (unsigned long long)st.overflow_pixels);
        compare(name, &t, &ref);
        compare(name, &t2, &ref);
    }
    oit_image_free(&ref);
    caller_fbo_free(&t);
    caller_fbo_free(&t2);
    oit_renderer_destroy(r);
}

/* Linear light into the caller's sRGB framebuffer (liboit.h, Result): a
 * GL_SRGB8_ALPHA8 target holding kClear's bytes, drawn with
 * OIT_RENDER_COLOUR_LINEAR, must hold the bytes of DFB's linear-mode image
 * over kClear (within one 8-bit step: the target stores the blend's
 * encoding in 8 bits) on all but 0.1% of pixels; GL_FRAMEBUFFER_SRGB comes
 * back as the caller set it (off here, on in the second draw); the same
 * target drawn in the default sRGB space differs (the option is live). */
static void check_linear_srgb_target(oit_scene *scene, oit_partfile *pf)
{
    oit_error err = {0};
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);
    oit_view v;
    oit_frame f;
    view_and_frame(&info, PROJ_DEFAULT, &v, &f);
    uint8_t *got[2] = {malloc((size_t)W * H * 4), malloc((size_t)W * H * 4)};
    for (int space = 0; space < 2; space++) {
        oit_renderer_desc rd = {0};
        rd.shading.colour_space = space ? OIT_RENDER_COLOUR_LINEAR : OIT_RENDER_COLOUR_SRGB;
        oit_renderer *r = NULL;
        if (oit_renderer_create(&rd, &r, &err) != OIT_OK) {
            CHECK(0, "linear sRGB target: oit_renderer_create: %s", err.message);
            free(got[0]);
            free(got[1]);
            return;
        }
        GLuint tex, fbo;
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_SRGB8_ALPHA8, W, H);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        GLint enc = 0;
        glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &enc);
        CHECK(enc == GL_SRGB, "the GL_SRGB8_ALPHA8 target's encoding is 0x%x", enc);
        /* The last renderer's programs are gone: a deleted current program
         * cannot be restored (see draw_and_compare's caller state). */
        glUseProgram(0);
        glDisable(GL_FRAMEBUFFER_SRGB); /* the clear stores kClear's bytes as given */
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, kClear);
        f.framebuffer = fbo;
        oit_status s = oit_renderer_draw(r, scene, &f, NULL, &err);
        CHECK(s == OIT_OK, "linear sRGB target: draw: %s", err.message);
        CHECK(!glIsEnabled(GL_FRAMEBUFFER_SRGB), "GL_FRAMEBUFFER_SRGB left enabled");
        if (space) {
            /* The caller's enable survives too. */
            glEnable(GL_FRAMEBUFFER_SRGB);
            glClearNamedFramebufferfv(fbo, GL_COLOR, 0, kClear); /* encoded: not read */
            s = oit_renderer_draw(r, scene, &f, NULL, &err);
            CHECK(s == OIT_OK && glIsEnabled(GL_FRAMEBUFFER_SRGB),
                  "GL_FRAMEBUFFER_SRGB not restored to enabled: %s", err.message);
            glDisable(GL_FRAMEBUFFER_SRGB);
            glClearNamedFramebufferfv(fbo, GL_COLOR, 0, kClear);
            s = oit_renderer_draw(r, scene, &f, NULL, &err);
        }
        glGetTextureImage(tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, W * H * 4, got[space]);
        CHECK(glGetError() == GL_NO_ERROR, "linear sRGB target: a GL error");
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
        oit_renderer_destroy(r);
    }
    oit_image ref = {0};
    oit_frame_stats rs = {0};
    v.shading = (oit_shading){0};
    v.shading.attributes = info.attributes;
    v.shading.colour_space = OIT_COLOUR_LINEAR;
    v.shading.scene_scale = 1.0f;
    memcpy(v.shading.background, kClear, sizeof v.shading.background);
    if (reference(pf, &v, &ref, &rs)) {
        uint64_t over = 0, differ = 0;
        int max_d = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const uint8_t *p = got[1] + ((size_t)y * W + x) * 4;
                const uint8_t *q = got[0] + ((size_t)y * W + x) * 4;
                const float *rr = ref.rgba + ((size_t)(H - 1 - y) * W + x) * 4;
                int d = 0, dq = 0;
                for (int c = 0; c < 3; c++) {
                    int want = (int)lrintf(fminf(fmaxf(rr[c], 0.0f), 1.0f) * 255.0f);
                    d = abs(p[c] - want) > d ? abs(p[c] - want) : d;
                    dq = abs(q[c] - p[c]) > dq ? abs(q[c] - p[c]) : dq;
                }
                max_d = d > max_d ? d : max_d;
                over += d > 1;
                differ += dq > 1;
            }
        double pct = 100.0 * (double)over / (W * H), pd = 100.0 * (double)differ / (W * H);
        printf("linear into an sRGB target: max %d steps from DFB (linear), %.4f%% pixels over "
               "1 step; the sRGB-space draw differs on %.1f%%\n", max_d, pct, pd);
        CHECK(pct <= 0.1, "linear sRGB target: %.4f%% of pixels more than 1/255 from DFB", pct);
        CHECK(pd >= 10.0, "linear and sRGB compositing differ on only %.1f%% of pixels", pd);
    }
    oit_image_free(&ref);
    free(got[0]);
    free(got[1]);
}

static void draw_and_compare(const char *name, oit_scene *scene, oit_partfile *pf,
                             oit_render_shading_mode mode, oit_render_pack pack)
{
    draw_and_compare_proj(name, scene, pf, mode, pack, PROJ_DEFAULT);
}

/* The caller's projection matrix classified back (liboit.h): the same
 * fields as the camera it was made from. */
static void check_classify(oit_scene *scene)
{
    oit_error err = {0};
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);
    for (int proj = PROJ_ORTHO; proj <= PROJ_INFINITE; proj++) {
        oit_camera c;
        camera_for(&info, &c, proj);
        float m[16];
        oit_camera_proj_matrix(&c, (float)W / H, m);
        printf("projection%s: m[8] %g m[9] %g m[10] %g m[11] %g m[14] %g m[15] %g\n",
               kProjName[proj], m[8], m[9], m[10], m[11], m[14], m[15]);
        CHECK(proj == PROJ_ORTHO ? m[11] == 0.0f && m[15] == 1.0f
                                 : m[11] == -1.0f && m[15] == 0.0f,
              "projection%s: not of its kind", kProjName[proj]);
        CHECK(proj != PROJ_OFFCENTRE || (m[8] != 0.0f && m[9] != 0.0f),
              "off-centre projection with m[8] = %g, m[9] = %g", m[8], m[9]);
        CHECK(proj != PROJ_INFINITE || (m[10] == -1.0f && m[14] == -2.0f * c.znear),
              "infinite far: m[10] = %g, m[14] = %g", m[10], m[14]);
    }
}

static void check_errors(oit_scene *scene)
{
    oit_error err = {0};
    oit_scene *none = NULL;
    const char *bad = "/nonexistent/liboit-missing.oitp";
    oit_status s = oit_scene_open(bad, NULL, &none, &err);
    printf("missing file: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_IO && none == NULL && strstr(err.message, bad),
          "missing file gave %s: %s", oit_status_name(s), err.message);

    oit_renderer *r = NULL;
    oit_renderer_desc rd = {.K = 32};
    s = oit_renderer_create(&rd, &r, &err);
    CHECK(s == OIT_ERR_ARGUMENT && r == NULL, "K=32 gave %s", oit_status_name(s));

    rd.K = 0;
    rd.epsilon = 1.0f;
    s = oit_renderer_create(&rd, &r, &err);
    printf("epsilon 1: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_ARGUMENT && r == NULL && strstr(err.message, "epsilon"),
          "epsilon = 1 gave %s", oit_status_name(s));

    rd.epsilon = 0.0f;
    /* The budgets take oitstream's ranges: 0 (default) or >= 64K; the
     * cache also OIT_RENDER_CACHE_OFF. */
    const struct { uint64_t upload, cache; oit_status want; } budgets[] = {
        {1024, 0, OIT_ERR_ARGUMENT}, {0, 65535, OIT_ERR_ARGUMENT},
        {65536, OIT_RENDER_CACHE_OFF, OIT_OK}, {0, 65536, OIT_OK}};
    for (size_t i = 0; i < sizeof budgets / sizeof *budgets; i++) {
        rd.upload_budget = budgets[i].upload;
        rd.cache_budget = budgets[i].cache;
        s = oit_renderer_create(&rd, &r, &err);
        printf("upload %llu, cache %llu: %s%s%s\n", (unsigned long long)budgets[i].upload,
               (unsigned long long)budgets[i].cache, oit_status_name(s), s ? ": " : "",
               s ? err.message : "");
        CHECK(s == budgets[i].want && (s == OIT_OK) == (r != NULL) &&
                  (s == OIT_OK || strstr(err.message, budgets[i].upload ? "upload_budget"
                                                                        : "cache_budget")),
              "budgets %llu/%llu gave %s", (unsigned long long)budgets[i].upload,
              (unsigned long long)budgets[i].cache, oit_status_name(s));
        oit_renderer_destroy(r);
        r = NULL;
    }
    /* oit_renderer_desc_check, the check oit_renderer_create runs: the
     * error names the field, never a tool's flag. */
    oit_renderer_desc cd = {.upload_budget = 1000};
    s = oit_renderer_desc_check(&cd, &err);
    printf("check: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_ARGUMENT &&
              !strncmp(err.message, "oit_renderer_desc.upload_budget = 1000:", 39) &&
              !strstr(err.message, "--"),
          "upload_budget 1000 unnamed gave %s: %s", oit_status_name(s), err.message);
    cd = (oit_renderer_desc){.cache_budget = 1000};
    s = oit_renderer_desc_check(&cd, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "oit_renderer_desc.cache_budget = 1000") &&
              strstr(err.message, "OIT_RENDER_CACHE_OFF (no cache)"),
          "cache_budget 1000 gave %s: %s", oit_status_name(s), err.message);
    cd = (oit_renderer_desc){.epsilon = 0.5f, .upload_budget = 65536, .K = 16,
                             .cache_budget = OIT_RENDER_CACHE_OFF};
    s = oit_renderer_desc_check(&cd, &err);
    CHECK(s == OIT_OK, "a good descriptor was refused: %s", err.message);
    cd.epsilon = -0.0001f;
    s = oit_renderer_desc_check(&cd, &err);
    CHECK(s == OIT_ERR_ARGUMENT && !strncmp(err.message, "oit_renderer_desc.epsilon = ", 28),
          "epsilon < 0 gave %s: %s", oit_status_name(s), err.message);
    rd.upload_budget = rd.cache_budget = 0;
    rd.pack = (oit_render_pack)99;
    s = oit_renderer_create(&rd, &r, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "pack"), "pack 99 gave %s",
          oit_status_name(s));
    rd.pack = OIT_RENDER_PACK_AUTO;
    s = oit_renderer_create(&rd, &r, &err);
    CHECK(s == OIT_OK, "renderer: %s", err.message);
    oit_frame f = {0};
    for (int i = 0; i < 4; i++)
        f.view[i * 5] = 1.0f;
    f.projection[0] = f.projection[5] = f.projection[15] = 1.0f; /* orthographic */
    f.projection[10] = -1.0f;
    f.projection[11] = -0.5f; /* but neither kind: m[11] -0.5, m[15] 1 */
    f.viewport_width = f.viewport_height = 8;
    s = oit_renderer_draw(r, scene, &f, NULL, &err);
    printf("neither projection: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "m[11] = -0.5"),
          "a projection neither perspective nor orthographic gave %s: %s",
          oit_status_name(s), err.message);
    f.projection[11] = 0.0f;
    f.projection[4] = 0.25f; /* skewed */
    s = oit_renderer_draw(r, scene, &f, NULL, &err);
    printf("skewed projection: %s: %s\n", oit_status_name(s), err.message);
    CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "projection[4]"),
          "a skewed projection gave %s: %s", oit_status_name(s), err.message);
    oit_renderer_destroy(r);
}

/* Draws scene with model (NULL: none) into a fresh target and reads the
 * viewport back (rows bottom up); returns NULL on failure. */
static float *draw_read_stats(oit_renderer *r, oit_scene *scene, const oit_camera *cam,
                              const float *model, const char *name, oit_draw_stats *st)
{
    oit_error err = {0};
    oit_frame f = {0};
    oit_camera_view_matrix(cam, f.view);
    oit_camera_proj_matrix(cam, (float)W / H, f.projection);
    if (model)
        memcpy(f.model, model, sizeof f.model);
    f.viewport_x = PAD_X;
    f.viewport_y = PAD_Y;
    f.viewport_width = W;
    f.viewport_height = H;
    caller_fbo t = caller_fbo_make(FW, FH, kClear);
    f.framebuffer = t.fbo;
    /* As draw_and_compare: the program DFB's reference left current was
     * deleted with it, and no caller expects that restored. */
    glUseProgram(0);
    oit_status s = oit_renderer_draw(r, scene, &f, st, &err);
    CHECK(s == OIT_OK, "%s: draw: %s", name, err.message);
    float *px = caller_fbo_read(&t);
    caller_fbo_free(&t);
    if (s != OIT_OK) {
        free(px);
        return NULL;
    }
    return px;
}

static float *draw_read(oit_renderer *r, oit_scene *scene, const oit_camera *cam,
                        const float *model, const char *name)
{
    return draw_read_stats(r, scene, cam, model, name, NULL);
}

/* Percent of viewport pixels of a and b more than 1/255 apart, and of a's
 * differing from the clear colour (covered). */
static double differ(const float *a, const float *b, double *covered)
{
    uint64_t over = 0, cov = 0;
    for (int y = PAD_Y; y < PAD_Y + H; y++)
        for (int x = PAD_X; x < PAD_X + W; x++) {
            const float *p = a + ((size_t)y * FW + x) * 4, *q = b + ((size_t)y * FW + x) * 4;
            double d = 0.0, c = 0.0;
            for (int k = 0; k < 3; k++) {
                d = fmax(d, fabs((double)p[k] - q[k]));
                c += fabs((double)p[k] - kClear[k]);
            }
            over += d > 1.0 / 255.0;
            cov += c > 1.0 / 255.0;
        }
    *covered = 100.0 * (double)cov / (W * H);
    return 100.0 * (double)over / (W * H);
}

/* oit_frame.model: a non-uniformly scaled, translated model through the
 * model matrix, as an in-core scene and as the part file (culled and
 * ordered through it), gives the image of the vertices transformed
 * beforehand; without the matrix the image is far from it. */
static void check_model(oit_partfile *pf, oit_scene *file_scene, const oit_scene_info *info)
{
    oit_error err = {0};
    oit_mesh mesh = {0};
    if (oit_partfile_load_mesh(pf, &mesh, &err) != OIT_OK) {
        CHECK(0, "model: %s", err.message);
        return;
    }
    static const float model[16] = {2.0f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1.25f, 0,
                                    3.0f, -2.0f, 1.5f, 1.0f};
    size_t nv = mesh.count * 3;
    float *pos = malloc(nv * 3 * sizeof *pos), *scaled = malloc(nv * 3 * sizeof *scaled);
    uint8_t *rgba = malloc(nv * 4);
    for (size_t t = 0; t < mesh.count; t++)
        for (int c = 0; c < 3; c++) {
            const float *p = mesh.tris[t].v[c].pos;
            float *o = pos + (t * 3 + c) * 3, *q = scaled + (t * 3 + c) * 3;
            memcpy(o, p, 12);
            for (int k = 0; k < 3; k++)
                q[k] = model[k] * p[0] + model[4 + k] * p[1] + model[8 + k] * p[2] + model[12 + k];
            memcpy(rgba + (t * 3 + c) * 4, mesh.tris[t].v[c].rgba, 4);
        }
    oit_mesh_free(&mesh);
    const uint8_t *colours = (info->attributes & OIT_ATTR_COLOUR) ? rgba : NULL;
    oit_scene_mesh_desc md = {.positions = pos, .vertex_count = nv, .colours = colours,
                              .name = "model arrays"};
    oit_scene_mesh_desc ms = {.positions = scaled, .vertex_count = nv, .colours = colours,
                              .name = "pre-scaled arrays"};
    oit_scene *plain = NULL, *pre = NULL;
    oit_renderer *r = NULL;
    oit_renderer_desc rd = {0};
    if (oit_scene_create_mesh(&md, &plain, &err) != OIT_OK ||
        oit_scene_create_mesh(&ms, &pre, &err) != OIT_OK ||
        oit_renderer_create(&rd, &r, &err) != OIT_OK) {
        CHECK(0, "model: %s", err.message);
        goto done;
    }
    oit_scene_info si;
    oit_scene_get_info(pre, &si, &err);
    /* The last view: close up on a corner, so that the part file's parts
     * are culled through the model matrix (planes taken to model space). */
    for (int proj = PROJ_DEFAULT; proj <= PROJ_ORTHO + 1; proj++) {
        oit_camera cam;
        camera_for(&si, &cam, proj <= PROJ_ORTHO ? proj : PROJ_DEFAULT);
        if (proj > PROJ_ORTHO)
            for (int k = 0; k < 3; k++) {
                float to = si.bounds_max[k] - 0.2f * (si.bounds_max[k] - si.bounds_min[k]);
                float sh = to - cam.target[k];
                cam.target[k] += sh;
                cam.eye[k] += sh + 0.6f * (cam.target[k] - cam.eye[k] - sh);
            }
        oit_draw_stats fst = {0};
        float *want = draw_read(r, pre, &cam, NULL, "pre-scaled");
        float *core = draw_read(r, plain, &cam, model, "in-core model");
        float *file = draw_read_stats(r, file_scene, &cam, model, "part file model", &fst);
        float *none = draw_read(r, plain, &cam, NULL, "no model");
        if (want && core && file && none) {
            double cov = 0.0, c2 = 0.0, c3 = 0.0;
            double pc = differ(core, want, &cov), pf_ = differ(file, want, &c2);
            double pn = differ(none, want, &c3);
            const char *pn_ = proj <= PROJ_ORTHO ? kProjName[proj] : " close up";
            printf("model matrix%s: in core %.4f%%, part file %.4f%% pixels over 1/255 from "
                   "pre-scaled vertices (%.1f%% covered, %llu of %llu parts culled); without "
                   "it %.2f%%\n", pn_, pc, pf_, cov, (unsigned long long)fst.parts_culled,
                   (unsigned long long)(fst.parts_culled + fst.parts_drawn), pn);
            CHECK(proj <= PROJ_ORTHO || fst.parts_culled > 0,
                  "model matrix close up: no part culled, the planes are not tested");
            CHECK(pc <= 0.1 && pf_ <= 0.1 && cov >= 10.0,
                  "model matrix%s: %.4f%% / %.4f%% of pixels differ from pre-scaled vertices",
                  pn_, pc, pf_);
            CHECK(pn > 5.0, "model matrix%s: the image without it differs on only %.2f%%", pn_,
                  pn);
        }
        free(want);
        free(core);
        free(file);
        free(none);
    }
    /* Not affine: refused, saying why. */
    {
        oit_camera cam;
        camera_for(&si, &cam, PROJ_DEFAULT);
        oit_frame f = {0};
        oit_camera_view_matrix(&cam, f.view);
        oit_camera_proj_matrix(&cam, (float)W / H, f.projection);
        memcpy(f.model, model, sizeof f.model);
        f.model[3] = 0.5f;
        f.viewport_width = f.viewport_height = 8;
        oit_status s = oit_renderer_draw(r, plain, &f, NULL, &err);
        printf("projective model: %s: %s\n", oit_status_name(s), err.message);
        CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "affine"),
              "a projective model matrix gave %s", oit_status_name(s));
        f.model[3] = 0.0f;
        f.model[0] = 0.0f; /* x collapses: singular */
        s = oit_renderer_draw(r, plain, &f, NULL, &err);
        CHECK(s == OIT_ERR_UNSUPPORTED && strstr(err.message, "singular"),
              "a singular model matrix gave %s", oit_status_name(s));
    }
done:
    oit_renderer_destroy(r);
    oit_scene_close(plain);
    oit_scene_close(pre);
    free(pos);
    free(scaled);
    free(rgba);
}

int main(int argc, char **argv)
{
    part_scene ps = open_part_scene(argc, argv);
    oit_error err = {0};
    printf("scene: %llu triangles, %llu parts, K %u\n", (unsigned long long)ps.info.triangles,
           (unsigned long long)ps.info.parts, ps.info.K);
    CHECK(ps.info.triangles > 0 && ps.info.parts > 0, "empty scene");
    check_errors(ps.scene);
    draw_and_compare("transparent", ps.scene, ps.pf, OIT_RENDER_TRANSPARENT, OIT_RENDER_PACK_AUTO);
    draw_and_compare("translucent", ps.scene, ps.pf, OIT_RENDER_TRANSLUCENT, OIT_RENDER_PACK_AUTO);
    /* Each packing oitstream --pack offers, first-k and counted exact. */
    draw_and_compare("first-k", ps.scene, ps.pf, OIT_RENDER_TRANSPARENT, OIT_RENDER_PACK_FIRSTK);
    draw_and_compare("counted", ps.scene, ps.pf, OIT_RENDER_TRANSPARENT, OIT_RENDER_PACK_COUNTED);
    check_linear_srgb_target(ps.scene, ps.pf);
    /* Every projection a viewer uses, through the caller's matrices. */
    check_classify(ps.scene);
    for (int proj = PROJ_ORTHO; proj <= PROJ_INFINITE; proj++)
        draw_and_compare_proj("transparent", ps.scene, ps.pf, OIT_RENDER_TRANSPARENT,
                              OIT_RENDER_PACK_AUTO, proj);
    draw_and_compare_proj("translucent", ps.scene, ps.pf, OIT_RENDER_TRANSLUCENT,
                          OIT_RENDER_PACK_AUTO, PROJ_ORTHO);
    check_model(ps.pf, ps.scene, &ps.info);

    /* The same triangles as an in-core scene from arrays (a soup with
     * per-vertex colour), through the same draw: DFB's image, the caller's
     * border and GL state kept as for the part file. */
    oit_mesh mesh = {0};
    if (oit_partfile_load_mesh(ps.pf, &mesh, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    float *pos = NULL;
    uint8_t *rgba = NULL;
    mesh_soup(&mesh, &pos, &rgba);
    oit_scene_mesh_desc md = {.positions = pos, .vertex_count = mesh.count * 3,
                              .colours = (ps.info.attributes & OIT_ATTR_COLOUR) ? rgba : NULL,
                              .name = "grid arrays"};
    oit_scene *core = NULL;
    if (oit_scene_create_mesh(&md, &core, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    free(pos);
    free(rgba);
    oit_mesh_free(&mesh);
    oit_scene_info ci;
    oit_scene_get_info(core, &ci, &err);
    CHECK(ci.in_core == 1 && ci.parts == 0 && ci.triangles == ps.info.triangles &&
              !ps.info.in_core,
          "in-core info: in_core %u, %llu parts, %llu triangles (file %llu)", ci.in_core,
          (unsigned long long)ci.parts, (unsigned long long)ci.triangles,
          (unsigned long long)ps.info.triangles);
    /* The reference shades with the file's attributes; the arrays carry
     * colour and alpha exactly when the file does. */
    CHECK(ci.attributes == ps.info.attributes, "in-core attributes %u, file %u", ci.attributes,
          ps.info.attributes);
    draw_and_compare("in-core transparent", core, ps.pf, OIT_RENDER_TRANSPARENT,
                     OIT_RENDER_PACK_AUTO);
    draw_and_compare("in-core translucent", core, ps.pf, OIT_RENDER_TRANSLUCENT,
                     OIT_RENDER_PACK_AUTO);
    for (int proj = PROJ_ORTHO; proj <= PROJ_INFINITE; proj++)
        draw_and_compare_proj("in-core transparent", core, ps.pf, OIT_RENDER_TRANSPARENT,
                              OIT_RENDER_PACK_AUTO, proj);
    oit_scene_close(core);

    oit_partfile_close(ps.pf);
    oit_scene_close(ps.scene);
    oit_gl_destroy(ps.gl);
    return test_verdict();
}
