/* Shared GLSL (frag_glsl.h). Every line of shading and compositing here
 * mirrors shade.h / shade.c; keep them in step. */
#include "view/render/gl/frag_glsl.h"

#include "view/render/image/shade.h"

#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Every program's first lines: the version, the binding points and
 * locations (glsl_bindings.h, glsl_locations.h) and the C constants that
 * the shared GLSL (glsl/) names. The GLSL itself is embedded from the
 * files of glsl/ (CMakeLists.txt). */
const char oit_glsl_version[] =
    "#version 450 core\n" OIT_GLSL_BINDINGS OIT_GLSL_LOCATIONS
    "#define OIT_CLIP_MAX " OIT_GLSL_STR(OIT_CLIP_MAX) "\n"
    "#define OIT_DEPTH_GRAZING " OIT_GLSL_STR(OIT_DEPTH_GRAZING) "\n"
    "#define OIT_DEPTH_KEY_MASK " OIT_GLSL_STR(OIT_DEPTH_KEY_MASK) "\n"
    "#define OIT_SEGMENT_LOCAL " OIT_GLSL_STR(OIT_GLSL_SEGMENT_LOCAL) "u\n";

/* Uniforms are set by name: a location a program does not use is -1, which
 * GL ignores, whereas an unused explicit location is an error. */
/* src = oit_glsl_version, then 'lead' (when set), then parts up to their
 * first NULL, then NULL. */
static void stage_sources(const char *lead, const char *const *parts, const char **src)
{
    int n = 0;
    src[n++] = oit_glsl_version;
    if (lead)
        src[n++] = lead;
    for (int i = 0; i < OIT_GLSL_PARTS_MAX && parts[i]; i++)
        src[n++] = parts[i];
    src[n] = NULL;
}

int oit_glsl_program_stage(const oit_glsl_program *p, oit_glsl_stage stage, const char **src)
{
    static const char *const standard_vs[] = {oit_glsl_vertex, NULL};
    int raster = p->fs[0] != NULL, own_vs = p->vs[0] != NULL;
    if (stage == OIT_GLSL_COMPUTE && !raster)
        stage_sources(NULL, p->cs, src);
    else if (stage == OIT_GLSL_VERTEX && raster)
        stage_sources(NULL, own_vs ? p->vs : standard_vs, src);
    else if (stage == OIT_GLSL_FRAGMENT && raster)
        stage_sources(own_vs ? NULL : oit_glsl_fragment_gen, p->fs, src);
    else
        return 0;
    return 1;
}

static uint64_t fnv1a(uint64_t h, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        h = (h ^ (unsigned char)s[i]) * 0x100000001b3ull;
    return h;
}

uint64_t oit_glsl_program_hash(const oit_glsl_program *p)
{
    static const char tags[] = "vfc";
    uint64_t h = 0xcbf29ce484222325ull;
    for (int stage = OIT_GLSL_VERTEX; stage <= OIT_GLSL_COMPUTE; stage++) {
        const char *src[OIT_GLSL_SOURCES_MAX];
        if (!oit_glsl_program_stage(p, (oit_glsl_stage)stage, src))
            continue;
        h = fnv1a(h, &tags[stage], 1);
        for (int i = 0; src[i]; i++)
            h = fnv1a(h, src[i], strlen(src[i]));
    }
    return h;
}

/* The test suite's record of what it built (glsl_program.h). One write a
 * line with O_APPEND, so that tests running at once do not mix lines. */
static void log_built(const oit_glsl_program *p)
{
    const char *path = getenv("OIT_GLSL_LOG");
    if (!path || !*path)
        return;
    char line[256];
    int n = snprintf(line, sizeof line, "%016llx %.200s\n", (unsigned long long)oit_glsl_program_hash(p),
                     p->what ? p->what : "");
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        return;
    if (write(fd, line, (size_t)n) != n) {
        /* a lost line fails the completeness test, which names the log */
    }
    close(fd);
}

oit_status oit_glsl_programs_build(oit_program_cache *pc, const oit_glsl_program *table, int n, GLuint *out,
                                   oit_error *err)
{
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++) {
        const char *vs[OIT_GLSL_SOURCES_MAX], *fs[OIT_GLSL_SOURCES_MAX], *cs[OIT_GLSL_SOURCES_MAX];
        int raster = oit_glsl_program_stage(&table[i], OIT_GLSL_VERTEX, vs);
        oit_glsl_program_stage(&table[i], OIT_GLSL_FRAGMENT, fs);
        oit_glsl_program_stage(&table[i], OIT_GLSL_COMPUTE, cs);
        s = oit_program_cache_build(pc, table[i].what, raster ? vs : NULL, raster ? fs : NULL,
                                    raster ? NULL : cs, &out[i], err);
        if (s == OIT_OK)
            log_built(&table[i]);
    }
    return s;
}

void oit_glsl_programs_delete(GLuint *progs, int n)
{
    for (int i = 0; i < n; i++) {
        glDeleteProgram(progs[i]);
        progs[i] = 0;
    }
}

void *oit_glsl_module_create(size_t size, const oit_glsl_program *p, const char *what,
                             oit_status *st, oit_error *err)
{
    GLuint *prog = calloc(1, size);
    if (!prog) {
        *st = oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", what);
        return NULL;
    }
    *st = oit_glsl_programs_build(NULL, p, 1, prog, err);
    if (*st != OIT_OK) {
        free(prog);
        return NULL;
    }
    return prog;
}

static GLint loc(GLuint prog, const char *name)
{
    return glGetUniformLocation(prog, name);
}

void oit_glsl_set_view(GLuint prog, const oit_view *view)
{
    float m[16];
    const oit_shading *s = &view->shading;
    oit_camera_view_matrix(&view->camera, m);
    glProgramUniformMatrix4fv(prog, loc(prog, "u_view"), 1, GL_FALSE, m);
    oit_camera_proj_matrix(&view->camera, (float)view->width / (float)view->height, m);
    glProgramUniformMatrix4fv(prog, loc(prog, "u_proj"), 1, GL_FALSE, m);
    glProgramUniform1i(prog, loc(prog, "u_mode"), (GLint)s->mode);
    glProgramUniform1i(prog, loc(prog, "u_colour_space"), (GLint)s->colour_space);
    glProgramUniform1ui(prog, loc(prog, "u_attrs"), oit_shading_attrs(s));
    glProgramUniform1f(prog, loc(prog, "u_alpha"), s->alpha);
    float drgb[3];
    for (int c = 0; c < 3; c++)
        drgb[c] = s->colour_space == OIT_COLOUR_LINEAR ? (float)oit_srgb_decode(s->default_rgb[c])
                                                       : s->default_rgb[c];
    glProgramUniform3fv(prog, loc(prog, "u_default_rgb"), 1, drgb);
    glProgramUniform1i(prog, loc(prog, "u_width"), view->width);
    float sigma = s->scene_scale > 0.0f ? s->absorption / s->scene_scale : 0.0f;
    glProgramUniform1f(prog, loc(prog, "u_sigma"), sigma);
    float bg[3];
    for (int c = 0; c < 3; c++)
        bg[c] = fmaxf(s->background[c], 0.0f);
    glProgramUniform3fv(prog, loc(prog, "u_background"), 1, bg);
    glProgramUniform2i(prog, loc(prog, "u_size"), view->width, view->height);
    const float *e = view->camera.eye;
    glProgramUniform3d(prog, loc(prog, "u_eye"), e[0], e[1], e[2]);
    float ray[4];
    oit_view_ray_map(view, ray);
    glProgramUniform4fv(prog, loc(prog, "u_ray"), 1, ray);
    float org[4], org_z;
    oit_view_origin_map(view, org, &org_z);
    glProgramUniform4fv(prog, loc(prog, "u_org"), 1, org);
    double md[16];
    oit_view_model(view, md);
    for (int i = 0; i < 16; i++)
        m[i] = (float)md[i];
    glProgramUniformMatrix4fv(prog, loc(prog, "u_model"), 1, GL_FALSE, m);
    glProgramUniform1f(prog, loc(prog, "u_org_z"), org_z);
    float clip[OIT_CLIP_MAX][4];
    oit_camera_view_matrix(&view->camera, m);
    oit_clip_eye(&view->clip, m, clip);
    glProgramUniform1i(prog, loc(prog, "u_clip_count"), view->clip.count);
    glProgramUniform4fv(prog, loc(prog, "u_clip"), OIT_CLIP_MAX, &clip[0][0]);
}

void oit_glsl_set_opaque(GLuint prog, const oit_opaque_depth *o)
{
    int on = o && o->enabled;
    glProgramUniform1i(prog, loc(prog, "u_opaque"), on);
    glProgramUniform1i(prog, loc(prog, "u_opaque_keyed"), o && o->keyed);
    glProgramUniform2i(prog, loc(prog, "u_opaque_origin"), on ? o->origin[0] : 0,
                       on ? o->origin[1] : 0);
    if (on)
        glProgramUniformMatrix4fv(prog, loc(prog, "u_proj"), 1, GL_FALSE, o->proj);
}

void oit_glsl_set_opaque_all(const GLuint *progs, int n, const oit_opaque_depth *o)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            oit_glsl_set_opaque(progs[i], o);
}

void oit_glsl_set_view_all(const GLuint *progs, int n, const oit_view *view)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            oit_glsl_set_view(progs[i], view);
}

void oit_glsl_set_epsilon_all(const GLuint *progs, int n, float epsilon)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            glProgramUniform1f(progs[i], loc(progs[i], "u_epsilon"), epsilon);
}

void oit_glsl_raster_begin(GLuint fbo, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_MULTISAMPLE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
}

void oit_glsl_raster_begin_sized(GLuint fbo, int w, int h)
{
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, w);
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, h);
    oit_glsl_raster_begin(fbo, w, h);
}
