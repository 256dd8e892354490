/* Tiles of the caller's opaque depth (opaque_tiles.h). */
#include "view/render/capture/opaque_tiles.h"
#include "base/minmax.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

struct oit_opaque_tiles {
    GLuint prog, buf;
    uint64_t cap;      /* bytes of buf */
    float *tiles;      /* largest depth a tile, GL rows (bottom first) */
    int tx, ty, w, h;  /* tiles across and down; the view's size */
    int on;
    double view[16], proj[16];
};
_Static_assert(offsetof(struct oit_opaque_tiles, prog) == 0,
               "oit_glsl_module_create builds the first member");

extern const char oit_opaque_tiles_cs[]; /* glsl/opaque_tiles.glsl */
static const oit_glsl_program program = {
    "opaque depth tiles",
    .cs = {"#define OIT_OPAQUE_TILE " OIT_GLSL_STR(OIT_OPAQUE_TILE) "\n", oit_opaque_tiles_cs}};

void oit_opaque_tiles_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &program);
}

oit_status oit_opaque_tiles_create(oit_opaque_tiles **out, oit_error *err)
{
    oit_status st;
    *out = oit_glsl_module_create(sizeof **out, &program, "opaque tiles", &st, err);
    return st;
}

void oit_opaque_tiles_destroy(oit_opaque_tiles *t)
{
    if (!t)
        return;
    glDeleteProgram(t->prog);
    glDeleteBuffers(1, &t->buf);
    free(t->tiles);
    free(t);
}

oit_status oit_opaque_tiles_begin(oit_opaque_tiles *t, const oit_view *view,
                                  const oit_opaque_depth *o, oit_host_waits *waits,
                                  oit_error *err)
{
    t->on = 0;
    if (!o || !o->enabled)
        return OIT_OK;
    /* Only projections whose depth and w depend on eye z alone (symmetric
     * and off-centre perspectives, orthographic): the box's nearest depth
     * is then at one of its eye-z extremes. */
    const float *P = o->proj;
    if (P[2] != 0.0f || P[6] != 0.0f || P[3] != 0.0f || P[7] != 0.0f)
        return OIT_OK;
    int tx = (view->width + OIT_OPAQUE_TILE - 1) / OIT_OPAQUE_TILE;
    int ty = (view->height + OIT_OPAQUE_TILE - 1) / OIT_OPAQUE_TILE;
    uint64_t bytes = (uint64_t)tx * ty * sizeof(float);
    if (bytes > t->cap) {
        float *m = realloc(t->tiles, bytes);
        if (!m)
            return oit_error_set(err, OIT_ERR_NOMEM, "opaque tiles: %dx%d tiles", tx, ty);
        t->tiles = m;
        glDeleteBuffers(1, &t->buf);
        glCreateBuffers(1, &t->buf);
        glNamedBufferStorage(t->buf, (GLsizeiptr)bytes, NULL, GL_MAP_READ_BIT);
        oit_gl_poison_buffer(t->buf);
        t->cap = bytes;
    }
    glProgramUniform2i(t->prog, glGetUniformLocation(t->prog, "u_size"), view->width,
                       view->height);
    glProgramUniform2i(t->prog, glGetUniformLocation(t->prog, "u_origin"), o->origin[0],
                       o->origin[1]);
    glProgramUniform2i(t->prog, glGetUniformLocation(t->prog, "u_tiles"), tx, ty);
    glUseProgram(t->prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OPAQUE_TILES, t->buf);
    glDispatchCompute((GLuint)(tx + 7) / 8, (GLuint)(ty + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    oit_host_read(waits, t->buf, 0, bytes, t->tiles);
    oit_status st = oit_gl_check("opaque tiles", err);
    if (st != OIT_OK)
        return st;
    float vm[16];
    oit_camera_view_matrix(&view->camera, vm);
    for (int i = 0; i < 16; i++) {
        t->view[i] = vm[i];
        t->proj[i] = P[i];
    }
    t->tx = tx;
    t->ty = ty;
    t->w = view->width;
    t->h = view->height;
    t->on = 1;
    return OIT_OK;
}

/* Window depth of eye z (glDepthRange(0, 1)); NAN when w <= 0. */
static double window_depth(const double *P, double z)
{
    double cz = P[10] * z + P[14], cw = P[11] * z + P[15];
    return cw > 0.0 ? 0.5 * cz / cw + 0.5 : NAN;
}

int oit_opaque_tiles_behind(const oit_opaque_tiles *t, const float bmin[3], const float bmax[3],
                            const int rect[4])
{
    if (!t || !t->on || rect[0] >= rect[2] || rect[1] >= rect[3])
        return 0;
    /* The box's eye-z range: its corners under the view matrix. */
    double zlo = INFINITY, zhi = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? bmax[0] : bmin[0], c & 2 ? bmax[1] : bmin[1],
                       c & 4 ? bmax[2] : bmin[2]};
        double z = t->view[2] * p[0] + t->view[6] * p[1] + t->view[10] * p[2] + t->view[14];
        zlo = oit_min_d(zlo, z);
        zhi = oit_max_d(zhi, z);
    }
    double d0 = window_depth(t->proj, zlo), d1 = window_depth(t->proj, zhi);
    if (!(d0 == d0) || !(d1 == d1)) /* reaches behind the eye */
        return 0;
    double nearest = fmin(d0, d1) - OIT_OPAQUE_MARGIN;
    /* Top-row rectangle to GL tile rows. */
    int x0 = rect[0] < 0 ? 0 : rect[0], x1 = rect[2] > t->w ? t->w : rect[2];
    int gy0 = t->h - rect[3], gy1 = t->h - rect[1];
    gy0 = gy0 < 0 ? 0 : gy0;
    gy1 = gy1 > t->h ? t->h : gy1;
    if (x0 >= x1 || gy0 >= gy1)
        return 0;
    for (int y = gy0 / OIT_OPAQUE_TILE; y <= (gy1 - 1) / OIT_OPAQUE_TILE; y++)
        for (int x = x0 / OIT_OPAQUE_TILE; x <= (x1 - 1) / OIT_OPAQUE_TILE; x++)
            if (!(nearest > (double)t->tiles[y * t->tx + x]))
                return 0;
    return 1;
}

uint64_t oit_opaque_tiles_gpu_bytes(const oit_opaque_tiles *t)
{
    return t ? t->cap : 0;
}
