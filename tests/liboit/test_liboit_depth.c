/* liboit with the caller's opaque depth (oit_frame.depth_texture).
 *
 * The caller draws an opaque occluder (a quad through the scene's centre,
 * facing the camera, covering the left part of the view) with depth into an
 * FBO with a colour and a depth texture, then liboit draws the transparent
 * scene into the same FBO, the depth texture given. The reference is DFB's
 * image (liboit's in-core path, no depth texture) of the transparent
 * triangles plus the occluder as alpha-1 triangles of the same colour: the
 * scene with the opaque geometry included. Checked for the part file
 * (streamed, every packing: the counted, first-k and K-slot captures, and
 * the compute capture) and
 * for the same triangles as an in-core scene (DFB), in perspective and in
 * the same view orthographic:
 *   - at most 0.1% of the viewport's pixels off by more than 1/255;
 *   - over the occluder, the reference differs from the occluder alone on a
 *     real share of pixels (surfaces in front of it), and liboit WITHOUT
 *     the depth texture differs from the reference on a real share
 *     (surfaces behind it), while liboit with it matches there: a test
 *     that fails if depth_texture were ignored;
 *   - fewer fragments with the depth texture than without;
 *   - the border outside the viewport, the depth texture's unit
 *     (OIT_TEX_OPAQUE_DEPTH: liboit.h's unit 7) and the active unit come
 *     back; bad depth textures fail with OIT_ERR_ARGUMENT.
 *
 * usage: test_liboit_depth FILE.oitp (a part file, e.g. from test_streamer) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/glsl_bindings.h"
#include "view/render/image/view.h"
#include "partfile/triangles.h"
#include "tests/lib/test_check.h"
#include "tests/liboit/caller_fbo.h"
#include "tests/liboit/part_scene.h"

enum { W = 160, H = 120, PAD_X = 8, PAD_Y = 4, FW = W + 2 * PAD_X, FH = H + 2 * PAD_Y };
static const float kClear[4] = {0.2f, 0.4f, 0.6f, 1.0f};
static const uint8_t kOccluder[4] = {200, 60, 60, 255};

/* Colour cleared to kClear, depth (format depth_format, 0: none) to 1. */
static caller_fbo target_make(GLenum depth_format)
{
    caller_fbo t = caller_fbo_make(FW, FH, kClear);
    glDepthMask(GL_TRUE);
    if (depth_format) {
        glCreateTextures(GL_TEXTURE_2D, 1, &t.depth);
        glTextureStorage2D(t.depth, 1, depth_format, FW, FH);
        glNamedFramebufferTexture(t.fbo, depth_format == GL_DEPTH24_STENCIL8
                                             ? GL_DEPTH_STENCIL_ATTACHMENT
                                             : GL_DEPTH_ATTACHMENT,
                                  t.depth, 0);
        float one = 1.0f;
        glClearNamedFramebufferfv(t.fbo, GL_DEPTH, 0, &one);
    }
    return t;
}

/* The caller's opaque pass: the occluder with its own program, depth
 * tested and written, shaded as shade.h shades an alpha-1 surface (base *
 * (0.3 + 0.7 |n.v|)), so that its colour is the reference's. */
static const char occ_vs[] =
    "#version 450 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 0) uniform mat4 u_view;\n"
    "layout(location = 1) uniform mat4 u_proj;\n"
    "out vec3 v_pos;\n"
    "void main() {\n"
    "    vec4 vp = u_view * vec4(a_pos, 1.0);\n"
    "    v_pos = vp.xyz;\n"
    "    gl_Position = u_proj * vp;\n"
    "}\n";
static const char occ_fs[] =
    "#version 450 core\n"
    "layout(location = 2) uniform vec3 u_normal;\n" /* view space */
    "layout(location = 3) uniform vec3 u_base;\n"
    "in vec3 v_pos;\n"
    "out vec4 o_colour;\n"
    "layout(location = 4) uniform int u_ortho;\n"
    "void main() {\n"
    /* Orthographic rays all run along -z: the view vector is +z. */
    "    vec3 v = u_ortho != 0 ? vec3(0.0, 0.0, 1.0) : -v_pos / length(v_pos);\n"
    "    float light = 0.3 + 0.7 * abs(dot(normalize(u_normal), v));\n"
    "    o_colour = vec4(u_base * light, 1.0);\n"
    "}\n";

typedef struct occluder {
    float pos[6][3]; /* two triangles */
    GLuint prog, vao, vbo;
} occluder;

static void occluder_make(occluder *o, const oit_camera *cam, const oit_scene_info *info)
{
    float f[3], r[3], u[3], c[3], diag = 0.0f;
    for (int k = 0; k < 3; k++) {
        f[k] = cam->target[k] - cam->eye[k];
        c[k] = 0.5f * (info->bounds_min[k] + info->bounds_max[k]);
        diag += (info->bounds_max[k] - info->bounds_min[k]) *
                (info->bounds_max[k] - info->bounds_min[k]);
    }
    diag = sqrtf(diag);
    float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; k++)
        f[k] /= fl;
    r[0] = f[1] * cam->up[2] - f[2] * cam->up[1];
    r[1] = f[2] * cam->up[0] - f[0] * cam->up[2];
    r[2] = f[0] * cam->up[1] - f[1] * cam->up[0];
    float rl = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++)
        r[k] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    /* Left of a line a little right of the centre, through the centre's
     * depth; counter-clockwise seen from the eye. */
    const float a[4] = {-2.0f * diag, 0.08f * diag, 0.08f * diag, -2.0f * diag};
    const float b[4] = {-2.0f * diag, -2.0f * diag, 2.0f * diag, 2.0f * diag};
    const int tri[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 3; k++)
            o->pos[i][k] = c[k] + a[tri[i]] * r[k] + b[tri[i]] * u[k];
    oit_error err = {0};
    const char *vs[] = {occ_vs, NULL}, *fs[] = {occ_fs, NULL};
    oit_status s = oit_gl_program_graphics("test occluder", vs, fs, &o->prog, &err);
    CHECK(s == OIT_OK, "occluder program: %s", err.message);
    glCreateBuffers(1, &o->vbo);
    glNamedBufferStorage(o->vbo, sizeof o->pos, o->pos, 0);
    glCreateVertexArrays(1, &o->vao);
    glVertexArrayVertexBuffer(o->vao, 0, o->vbo, 0, 12);
    glEnableVertexArrayAttrib(o->vao, 0);
    glVertexArrayAttribFormat(o->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(o->vao, 0, 0);
}

static void occluder_free(occluder *o)
{
    glDeleteProgram(o->prog);
    glDeleteVertexArrays(1, &o->vao);
    glDeleteBuffers(1, &o->vbo);
}

/* The caller's opaque pass into t's viewport, depth tested. */
static void occluder_draw(const occluder *o, const oit_frame *f, const caller_fbo *t)
{
    float e1[3], e2[3], n[3], nv[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = o->pos[1][k] - o->pos[0][k];
        e2[k] = o->pos[2][k] - o->pos[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int row = 0; row < 3; row++)
        nv[row] = f->view[row] * n[0] + f->view[4 + row] * n[1] + f->view[8 + row] * n[2];
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(f->viewport_x, f->viewport_y, f->viewport_width, f->viewport_height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(o->prog);
    glProgramUniformMatrix4fv(o->prog, 0, 1, GL_FALSE, f->view);
    glProgramUniformMatrix4fv(o->prog, 1, 1, GL_FALSE, f->projection);
    glProgramUniform3fv(o->prog, 2, 1, nv);
    float base[3] = {kOccluder[0] / 255.0f, kOccluder[1] / 255.0f, kOccluder[2] / 255.0f};
    glProgramUniform3fv(o->prog, 3, 1, base);
    glProgramUniform1i(o->prog, 4, f->projection[11] == 0.0f); /* orthographic */
    glBindVertexArray(o->vao);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static double px_diff(const float *a, const float *b)
{
    double d = 0.0;
    for (int c = 0; c < 3; c++)
        d = fmax(d, fabs((double)a[c] - b[c]));
    return d;
}

/* One scene and packing: the caller's occluder, then liboit with and
 * without the depth texture, against ref (the scene with the occluder as
 * alpha-1 triangles) and occ (the occluder alone). */
static void check_depth(const char *name, oit_scene *scene, oit_render_pack pack,
                        oit_render_capture capture, GLenum depth_format, const occluder *o,
                        const oit_frame *f0, const float *ref, const float *occ,
                        uint64_t *first_fragments)
{
    oit_error err = {0};
    oit_renderer_desc rd = {.pack = pack, .capture = capture};
    oit_renderer *r = NULL;
    if (oit_renderer_create(&rd, &r, &err) != OIT_OK) {
        CHECK(0, "%s: oit_renderer_create: %s", name, err.message);
        return;
    }
    oit_frame f = *f0;
    caller_fbo with = target_make(depth_format), without = target_make(depth_format);
    occluder_draw(o, &f, &with);
    occluder_draw(o, &f, &without);

    /* A caller's texture on liboit's depth unit and another active unit, to be given back. */
    GLuint mark = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &mark);
    glTextureStorage2D(mark, 1, GL_RGBA8, 4, 4);
    glBindTextureUnit(OIT_TEX_OPAQUE_DEPTH, mark);
    glActiveTexture(GL_TEXTURE3);

    f.framebuffer = with.fbo;
    f.depth_texture = with.depth; /* also the target's depth attachment */
    oit_draw_stats sd = {0}, sn = {0};
    oit_status s = oit_renderer_draw(r, scene, &f, &sd, &err);
    CHECK(s == OIT_OK, "%s: draw with depth: %s", name, err.message);
    GLint active = 0, held = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_DEPTH);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &held);
    glActiveTexture(GL_TEXTURE0);
    CHECK(active == GL_TEXTURE3 && (GLuint)held == mark,
          "%s: texture state not restored: active 0x%x (want 0x%x), unit %d holds %d (want %u)",
          name, active, GL_TEXTURE3, OIT_TEX_OPAQUE_DEPTH, held, mark);
    glBindTextureUnit(OIT_TEX_OPAQUE_DEPTH, 0);
    glDeleteTextures(1, &mark);

    f.framebuffer = without.fbo;
    f.depth_texture = 0;
    if (s == OIT_OK) {
        s = oit_renderer_draw(r, scene, &f, &sn, &err);
        CHECK(s == OIT_OK, "%s: draw without depth: %s", name, err.message);
    }
    if (s == OIT_OK) {
        float *a = caller_fbo_read(&with), *n = caller_fbo_read(&without);
        uint64_t over = 0, region = 0, region_over = 0, behind = 0, front = 0, border = 0;
        double max_abs = 0.0;
        for (int y = 0; y < FH; y++)
            for (int x = 0; x < FW; x++) {
                size_t i = ((size_t)y * FW + x) * 4;
                int inside = x >= PAD_X && y >= PAD_Y && x < PAD_X + W && y < PAD_Y + H;
                if (!inside) {
                    border += memcmp(a + i, kClear, sizeof kClear) != 0;
                    continue;
                }
                double d = px_diff(a + i, ref + i);
                max_abs = fmax(max_abs, d);
                over += d > 1.0 / 255.0;
                if (px_diff(occ + i, kClear) > 1.0 / 255.0) {
                    region++;
                    region_over += d > 1.0 / 255.0;
                    behind += px_diff(n + i, ref + i) > 1.0 / 255.0;
                    front += px_diff(ref + i, occ + i) > 1.0 / 255.0;
                }
            }
        free(a);
        free(n);
        double pct = 100.0 * over / (W * H), rpct = region ? 100.0 * region_over / region : 0;
        double bpct = region ? 100.0 * behind / region : 0, fpct = region ? 100.0 * front / region : 0;
        printf("%s: max_abs %.5f, %.4f%% pixels over 1/255; occluder on %.1f%% of the view: "
               "%.4f%% over there, %.1f%% show surfaces in front, %.1f%% differ without the "
               "depth texture; fragments %llu with depth, %llu without; %u packs\n",
               name, max_abs, pct, 100.0 * region / (W * H), rpct, fpct, bpct,
               (unsigned long long)sd.fragments, (unsigned long long)sn.fragments, sd.packs);
        CHECK(pct <= 0.1, "%s: %.4f%% of pixels differ from the reference by more than 1/255",
              name, pct);
        CHECK(rpct <= 0.1, "%s: %.4f%% of the occluder's pixels differ from the reference",
              name, rpct);
        CHECK(region >= (uint64_t)(W * H) / 4 && region <= (uint64_t)(W * H) * 3 / 4,
              "%s: the occluder covers %llu of %d pixels", name, (unsigned long long)region,
              W * H);
        /* The scene must have surfaces on both sides of the occluder, and
         * ignoring the depth texture must show those behind it. */
        CHECK(fpct >= 5.0, "%s: only %.1f%% of the occluder's pixels have surfaces in front",
              name, fpct);
        CHECK(bpct >= 5.0, "%s: without the depth texture only %.1f%% of the occluder's "
              "pixels change: the test cannot see surfaces behind it", name, bpct);
        /* Every path keeps the same fragments: those in front of the
         * occluder (a skipped part that had some would lose them). The
         * compute capture's fill rule is not the rasterizer's: pixel
         * centres within a rounding of an edge may go to the other
         * triangle or to none, 1 fragment in 1000 at most. */
        if (!*first_fragments)
            *first_fragments = sd.fragments;
        uint64_t off = sd.fragments > *first_fragments ? sd.fragments - *first_fragments
                                                       : *first_fragments - sd.fragments;
        uint64_t edges = capture == OIT_RENDER_CAPTURE_COMPUTE ? *first_fragments / 1000 : 0;
        CHECK(off <= edges, "%s: %llu fragments with the depth texture, "
              "the first scene drawn %llu", name, (unsigned long long)sd.fragments,
              (unsigned long long)*first_fragments);
        CHECK(sd.fragments < sn.fragments, "%s: %llu fragments with the depth texture, %llu "
              "without", name, (unsigned long long)sd.fragments,
              (unsigned long long)sn.fragments);
        CHECK(border == 0, "%s: %llu pixels outside the viewport changed", name,
              (unsigned long long)border);
        /* Parts wholly behind the occluder are skipped (streamed scenes):
         * the image above is the check that none in front was. */
        oit_scene_info si;
        oit_scene_get_info(scene, &si, &err);
        printf("%s: %llu parts skipped with depth, %llu without; %llu drawn, %llu culled\n",
               name, (unsigned long long)sd.parts_skipped, (unsigned long long)sn.parts_skipped,
               (unsigned long long)sd.parts_drawn, (unsigned long long)sd.parts_culled);
        CHECK(sn.parts_skipped == 0 && (si.in_core || sd.parts_skipped > 0) &&
                  sd.parts_skipped + sd.parts_drawn == sn.parts_drawn,
              "%s: %llu parts skipped with the depth texture (%llu drawn), %llu without (%llu "
              "drawn)", name, (unsigned long long)sd.parts_skipped,
              (unsigned long long)sd.parts_drawn, (unsigned long long)sn.parts_skipped,
              (unsigned long long)sn.parts_drawn);
    }
    caller_fbo_free(&with);
    caller_fbo_free(&without);
    oit_renderer_destroy(r);
}

/* Depth textures liboit must refuse. */
static void check_bad_depth(oit_scene *scene, const oit_frame *f0)
{
    oit_error err = {0};
    oit_renderer *r = NULL;
    if (oit_renderer_create(NULL, &r, &err) != OIT_OK) {
        CHECK(0, "oit_renderer_create: %s", err.message);
        return;
    }
    caller_fbo t = target_make(GL_DEPTH_COMPONENT32F);
    GLuint small = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &small);
    glTextureStorage2D(small, 1, GL_DEPTH_COMPONENT32F, W, H); /* the viewport's size */
    struct { GLuint tex; const char *what; } bad[] = {
        {t.colour, "a colour texture"}, {small, "smaller than viewport + offset"},
        {987654u, "not a texture"}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        oit_frame f = *f0;
        f.framebuffer = t.fbo;
        f.depth_texture = bad[i].tex;
        oit_status s = oit_renderer_draw(r, scene, &f, NULL, &err);
        printf("depth texture %s: %s: %s\n", bad[i].what, oit_status_name(s), err.message);
        CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "depth_texture"),
              "depth texture %s gave %s", bad[i].what, oit_status_name(s));
    }
    glDeleteTextures(1, &small);
    caller_fbo_free(&t);
    oit_renderer_destroy(r);
}

/* One projection (perspective, or the same view orthographic): the
 * occluder, the reference and every path's checks. 0 when set-up failed. */
static int run_projection(oit_scene *scene, oit_partfile *pf, const oit_scene_info *info,
                          int ortho)
{
    oit_error err = {0};
    oit_camera cam;
    oit_camera_default(&cam, info->bounds_min, info->bounds_max, 35.0f, 25.0f);
    if (ortho) {
        /* The same view orthographic: the volume as high as the frustum at
         * the target, its near plane behind the eye. */
        double dist = 0.0, ty = tan(0.5 * cam.fovy_deg * 3.14159265358979323846 / 180.0);
        for (int k = 0; k < 3; k++)
            dist += pow((double)cam.target[k] - cam.eye[k], 2.0);
        dist = sqrt(dist);
        cam.projection = OIT_PROJ_ORTHOGRAPHIC;
        cam.ortho_height = (float)(2.0 * dist * ty);
        cam.znear = (float)(cam.znear - 0.5 * dist);
    }
    oit_frame f = {0};
    oit_camera_view_matrix(&cam, f.view);
    oit_camera_proj_matrix(&cam, (float)W / H, f.projection);
    f.viewport_x = PAD_X;
    f.viewport_y = PAD_Y;
    f.viewport_width = W;
    f.viewport_height = H;
    occluder o = {0};
    occluder_make(&o, &cam, info);

    /* The file's triangles as a soup with their colours, and the same with
     * the occluder's two alpha-1 triangles added: the reference scene. */
    oit_mesh mesh = {0};
    if (oit_partfile_load_mesh(pf, &mesh, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 0;
    }
    size_t nv = mesh.count * 3 + 6;
    float *pos = malloc(nv * 3 * sizeof *pos);
    uint8_t *rgba = malloc(nv * 4);
    for (size_t t = 0; t < mesh.count; t++)
        for (int c = 0; c < 3; c++) {
            memcpy(pos + (t * 3 + c) * 3, mesh.tris[t].v[c].pos, 12);
            memcpy(rgba + (t * 3 + c) * 4, mesh.tris[t].v[c].rgba, 4);
        }
    for (int i = 0; i < 6; i++) {
        memcpy(pos + (mesh.count * 3 + i) * 3, o.pos[i], 12);
        memcpy(rgba + (mesh.count * 3 + i) * 4, kOccluder, 4);
    }
    oit_scene_mesh_desc md = {.positions = pos, .vertex_count = mesh.count * 3,
                              .colours = rgba, .name = "grid arrays"};
    oit_scene *core = NULL, *with_occ = NULL;
    oit_status s = oit_scene_create_mesh(&md, &core, &err);
    md.vertex_count = nv;
    md.name = "grid arrays + occluder";
    if (s == OIT_OK)
        s = oit_scene_create_mesh(&md, &with_occ, &err);
    free(pos);
    free(rgba);
    oit_mesh_free(&mesh);
    if (s != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 0;
    }

    /* The reference (DFB, in core) and the occluder alone. */
    float *ref = NULL, *occ = NULL;
    {
        oit_renderer *r = NULL;
        caller_fbo t = target_make(0), t_occ = target_make(GL_DEPTH_COMPONENT32F);
        s = oit_renderer_create(NULL, &r, &err);
        oit_frame fr = f;
        fr.framebuffer = t.fbo;
        if (s == OIT_OK)
            s = oit_renderer_draw(r, with_occ, &fr, NULL, &err);
        CHECK(s == OIT_OK, "reference: %s", err.message);
        occluder_draw(&o, &f, &t_occ);
        ref = caller_fbo_read(&t);
        occ = caller_fbo_read(&t_occ);
        caller_fbo_free(&t);
        caller_fbo_free(&t_occ);
        oit_renderer_destroy(r);
    }
    uint64_t first = 0; /* every path keeps the first one's fragments */
    if (s == OIT_OK) {
        /* The part file through every packing (the K-slot array capture,
         * counted and first-k), in a depth-stencil texture; the in-core
         * scene (DFB) in a float depth texture. */
        static const struct {
            const char *name, *ortho_name;
            oit_render_pack pack;
            oit_render_capture capture;
        } packs[] = {
            {"stream auto", "ortho stream auto", OIT_RENDER_PACK_AUTO, 0},
            {"stream counted", "ortho stream counted", OIT_RENDER_PACK_COUNTED, 0},
            {"stream first-k", "ortho stream first-k", OIT_RENDER_PACK_FIRSTK, 0},
            {"stream budget", "ortho stream budget", OIT_RENDER_PACK_BUDGET, 0},
            {"stream disjoint", "ortho stream disjoint", OIT_RENDER_PACK_DISJOINT, 0},
            /* the compute capture tests the depth in its own sweep */
            {"stream compute", "ortho stream compute", OIT_RENDER_PACK_AUTO,
             OIT_RENDER_CAPTURE_COMPUTE}};
        for (size_t i = 0; i < sizeof packs / sizeof *packs; i++)
            check_depth(ortho ? packs[i].ortho_name : packs[i].name, scene, packs[i].pack,
                        packs[i].capture, GL_DEPTH24_STENCIL8, &o, &f, ref, occ, &first);
        check_depth(ortho ? "ortho in-core" : "in-core", core, OIT_RENDER_PACK_AUTO, 0,
                    GL_DEPTH_COMPONENT32F, &o, &f, ref, occ, &first);
        if (!ortho)
            check_bad_depth(scene, &f);
    }
    free(ref);
    free(occ);
    occluder_free(&o);
    oit_scene_close(core);
    oit_scene_close(with_occ);
    return s == OIT_OK;
}

int main(int argc, char **argv)
{
    part_scene ps = open_part_scene(argc, argv);
    CHECK(ps.info.triangles > 0 && (ps.info.attributes & OIT_ATTR_ALPHA),
          "the scene needs triangles with alpha (%llu triangles, attributes %u)",
          (unsigned long long)ps.info.triangles, ps.info.attributes);

    int ok = run_projection(ps.scene, ps.pf, &ps.info, 0) && run_projection(ps.scene, ps.pf, &ps.info, 1);
    oit_partfile_close(ps.pf);
    oit_scene_close(ps.scene);
    oit_gl_destroy(ps.gl);
    return !ok || test_failures != 0;
}
