/* The caller's framebuffer that liboit's tests (test_liboit, _depth,
 * _sizes) draw into: an RGBA32F colour texture cleared to a known colour
 * (a depth texture where the test adds one), its viewport at an offset,
 * and that viewport against DFB's image with the border untouched. */
#ifndef OIT_TESTS_LIBOIT_CALLER_FBO_H
#define OIT_TESTS_LIBOIT_CALLER_FBO_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_util.h"
#include "view/render/image/view.h"

typedef struct caller_fbo {
    GLuint fbo, colour, depth; /* depth: 0 unless the test makes one */
    int fw, fh;
} caller_fbo;

/* fw x fh, cleared to clear. */
static inline caller_fbo caller_fbo_make(int fw, int fh, const float clear[4])
{
    caller_fbo t = {.fw = fw, .fh = fh};
    glCreateTextures(GL_TEXTURE_2D, 1, &t.colour);
    glTextureStorage2D(t.colour, 1, GL_RGBA32F, fw, fh);
    glCreateFramebuffers(1, &t.fbo);
    glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.colour, 0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE); /* DFB leaves it off */
    glClearNamedFramebufferfv(t.fbo, GL_COLOR, 0, clear);
    return t;
}

static inline void caller_fbo_free(caller_fbo *t)
{
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteTextures(1, &t->colour);
    glDeleteTextures(1, &t->depth);
}

/* The colour texture's RGBA floats, bottom row first (free them). */
static inline float *caller_fbo_read(const caller_fbo *t)
{
    size_t bytes = (size_t)t->fw * t->fh * 4 * sizeof(float);
    float *px = malloc(bytes);
    glGetTextureImage(t->colour, 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, px);
    return px;
}

/* The reference's channels that tell a covered pixel (caller_fbo_compare). */
enum { COVER_R = 1, COVER_G = 2, COVER_B = 4 };

typedef struct viewport_diff {
    double max_abs; /* largest channel difference */
    double pct;     /* % of viewport pixels over 1/255 */
    double cov;     /* % of viewport pixels the reference covers */
    uint64_t border_bad; /* pixels outside the viewport that lost the clear colour */
} viewport_diff;

/* The viewport of t (ref's size, at pad_x, pad_y) against ref, its rows
 * below `occluded` against the clear colour instead. A pixel is covered
 * where the reference's channels named by covered_channels (COVER_*)
 * differ from the clear colour's by over 1/255 in sum.
 * Prints the figures after name. */
static inline viewport_diff caller_fbo_compare(const char *name, const caller_fbo *t, int pad_x,
                                               int pad_y, const oit_image *ref,
                                               const float clear[4], int occluded,
                                               unsigned covered_channels)
{
    const int w = ref->width, h = ref->height;
    float *px = caller_fbo_read(t);
    uint64_t over = 0, covered = 0;
    viewport_diff d = {0};
    for (int y = 0; y < t->fh; y++)
        for (int x = 0; x < t->fw; x++) {
            const float *p = px + ((size_t)y * t->fw + x) * 4;
            int vx = x - pad_x, vy = y - pad_y;
            if (vx < 0 || vy < 0 || vx >= w || vy >= h) {
                d.border_bad += memcmp(p, clear, 4 * sizeof *clear) != 0;
                continue;
            }
            const float *r = vy < occluded ? clear : ref->rgba + ((size_t)(h - 1 - vy) * w + vx) * 4;
            double m = 0.0;
            float away = 0.0f;
            for (int c = 0; c < 3; c++) {
                m = fmax(m, fabs((double)p[c] - r[c]));
                away += (covered_channels >> c & 1u) ? fabsf(r[c] - clear[c]) : 0.0f;
            }
            d.max_abs = fmax(d.max_abs, m);
            over += m > 1.0 / 255.0;
            covered += away > 1.0f / 255.0f;
        }
    free(px);
    d.pct = 100.0 * (double)over / ((double)w * h);
    d.cov = 100.0 * (double)covered / ((double)w * h);
    printf("%s: max_abs %.5f, %.4f%% pixels over 1/255, %.1f%% covered, border pixels "
           "changed %llu\n",
           name, d.max_abs, d.pct, d.cov, (unsigned long long)d.border_bad);
    return d;
}

#endif
