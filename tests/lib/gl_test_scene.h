/* Test scenes for the GL methods: camera at the origin looking down -z with
 * a 90-degree field of view, and stacks of screen-aligned quads whose exact
 * per-pixel result the tests compute by hand from shade.h (without
 * view/render/image/shade.c, so that a mistake there and in the GLSL cannot cancel). */
#ifndef OIT_TESTS_GL_TEST_SCENE_H
#define OIT_TESTS_GL_TEST_SCENE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/view.h"

typedef struct quad_spec {
    float z;          /* plane z (< 0) */
    float half;       /* half extent in x and y */
    uint8_t rgba[4];
    int front;        /* 1: counter-clockwise seen from the eye */
} quad_spec;

static inline void scene_view(oit_view *v, int w, int h, oit_shading_mode mode)
{
    memset(v, 0, sizeof *v);
    v->camera.target[2] = -1.0f;
    v->camera.up[1] = 1.0f;
    v->camera.fovy_deg = 90.0f;
    v->camera.znear = 0.5f;
    v->camera.zfar = 1000.0f;
    v->width = w;
    v->height = h;
    v->shading.mode = mode;
    v->shading.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    v->shading.background[0] = 0.2f;
    v->shading.background[1] = 0.4f;
    v->shading.background[2] = 0.9f;
    v->shading.absorption = 3.0f;
    v->shading.scene_scale = 10.0f;
}

/* Two triangles (prims 2i, 2i+1 when written at tris[2i]). */
static inline void quad_tris(const quad_spec *q, oit_triangle out[2])
{
    const float h = q->half;
    const float c[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; t++)
        for (int k = 0; k < 3; k++) {
            int corner = idx[t][q->front ? k : 2 - k];
            oit_vertex *v = &out[t].v[k];
            v->pos[0] = c[corner][0];
            v->pos[1] = c[corner][1];
            v->pos[2] = q->z;
            memcpy(v->rgba, q->rgba, 4);
        }
}

static inline oit_triangle *scene_tris(const quad_spec *q, int n)
{
    oit_triangle *t = malloc(sizeof *t * 2 * (size_t)n);
    for (int i = 0; t && i < n; i++)
        quad_tris(&q[i], &t[2 * i]);
    return t;
}

/* Bounding box (top rows first, exclusive) of the pixels quad q covers. */
static inline void footprint(const oit_view *v, const quad_spec *q, int rect[4])
{
    rect[0] = v->width, rect[1] = v->height, rect[2] = 0, rect[3] = 0;
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * v->width / v->height;
            double dy = 1 - (y + 0.5) / v->height * 2;
            if (fabs(dx * q->z) < q->half && fabs(dy * q->z) < q->half) {
                rect[0] = x < rect[0] ? x : rect[0];
                rect[1] = y < rect[1] ? y : rect[1];
                rect[2] = x + 1 > rect[2] ? x + 1 : rect[2];
                rect[3] = y + 1 > rect[3] ? y + 1 : rect[3];
            }
        }
}

/* The union of the footprints of quads q[first..last): a batch's tight rect. */
static inline void batch_rect(const oit_view *v, const quad_spec *q, int first, int last,
                              int r[4])
{
    r[0] = v->width, r[1] = v->height, r[2] = 0, r[3] = 0;
    for (int i = first; i < last; i++) {
        int f[4];
        footprint(v, &q[i], f);
        r[0] = f[0] < r[0] ? f[0] : r[0];
        r[1] = f[1] < r[1] ? f[1] : r[1];
        r[2] = f[2] > r[2] ? f[2] : r[2];
        r[3] = f[3] > r[3] ? f[3] : r[3];
    }
}

typedef struct hand_frag {
    double t;
    int order; /* quad index: prim order */
    const quad_spec *q;
} hand_frag;

static inline int hand_frag_cmp(const void *a, const void *b)
{
    const hand_frag *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return x->order - y->order;
}

/* State of shade.h, in double, after compositing quads[first..first+n)
 * that the pixel's centre ray meets; used with a carried state to check
 * batches. */
typedef struct hand_state {
    double C[3], T[3], t_prev, medium[3];
    int nest;
} hand_state;

static inline void hand_begin(hand_state *s)
{
    memset(s, 0, sizeof *s);
    s->T[0] = s->T[1] = s->T[2] = 1.0;
}

static inline void hand_add(hand_state *s, const oit_view *v, const quad_spec *q, int n,
                     int px, int py)
{
    double tanh = tan(0.5 * v->camera.fovy_deg * 3.14159265358979323846 / 180.0);
    double aspect = (double)v->width / v->height;
    double dx = ((px + 0.5) / v->width * 2 - 1) * tanh * aspect;
    double dy = (1 - (py + 0.5) / v->height * 2) * tanh;
    double len = sqrt(dx * dx + dy * dy + 1.0);
    hand_frag *f = malloc(sizeof *f * (size_t)(n > 0 ? n : 1));
    int m = 0;
    for (int i = 0; i < n; i++) {
        double d = -q[i].z;
        if (fabs(dx * d) < q[i].half && fabs(dy * d) < q[i].half)
            f[m++] = (hand_frag){d * len, i, &q[i]};
    }
    qsort(f, (size_t)m, sizeof *f, hand_frag_cmp);
    const oit_shading *sh = &v->shading;
    int translucent = sh->mode == OIT_SHADING_TRANSLUCENT;
    double ndv = 1.0 / len, light = 0.3 + 0.7 * ndv;
    for (int i = 0; i < m; i++) {
        const quad_spec *qq = f[i].q;
        double colour[3], a, base[3];
        for (int c = 0; c < 3; c++)
            base[c] = qq->rgba[c] / 255.0;
        if (translucent) {
            colour[0] = colour[1] = colour[2] = light;
            a = 0.04 + 0.96 * pow(1.0 - ndv, 5.0);
            if (s->nest > 0)
                for (int c = 0; c < 3; c++)
                    s->T[c] *= exp(-sh->absorption / sh->scene_scale * (1 - s->medium[c]) *
                                   (f[i].t - s->t_prev));
        } else {
            for (int c = 0; c < 3; c++)
                colour[c] = base[c] * light;
            a = qq->rgba[3] / 255.0;
        }
        for (int c = 0; c < 3; c++) {
            s->C[c] += s->T[c] * a * colour[c];
            s->T[c] *= 1.0 - a;
        }
        if (translucent) {
            if (qq->front) {
                s->nest++;
                memcpy(s->medium, base, sizeof base);
            } else if (s->nest > 0) {
                s->nest--;
            }
            s->t_prev = f[i].t;
        }
    }
    free(f);
}

static inline void hand_end(const hand_state *s, const oit_view *v, double rgb[3])
{
    for (int c = 0; c < 3; c++)
        rgb[c] = s->C[c] + s->T[c] * fmax(v->shading.background[c], 0.0);
}

/* The hand result at pixel (x, y): quads q[0..n) composited over v's
 * background. */
static inline void hand_pixel(const oit_view *v, const quad_spec *q, int n, int x, int y,
                              double rgb[3])
{
    hand_state s;
    hand_begin(&s);
    hand_add(&s, v, q, n, x, y);
    hand_end(&s, v, rgb);
}

/* Largest channel difference over the image between it and the hand result. */
static inline double hand_max_diff(const oit_image *img, const oit_view *v, const quad_spec *q,
                            int n)
{
    double worst = 0.0;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++) {
            double rgb[3];
            hand_pixel(v, q, n, x, y, rgb);
            const float *p = &img->rgba[4 * ((size_t)y * img->width + x)];
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(p[c] - rgb[c]));
        }
    return worst;
}

/* Deterministic shuffle (xorshift), so failures reproduce. */
static inline void shuffle_quads(quad_spec *q, int n, uint32_t seed)
{
    for (int i = n - 1; i > 0; i--) {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        int j = (int)(seed % (uint32_t)(i + 1));
        quad_spec tmp = q[i];
        q[i] = q[j];
        q[j] = tmp;
    }
}

#endif
