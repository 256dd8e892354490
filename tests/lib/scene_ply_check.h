/* Test helper: loads a binary little-endian PLY as the streaming writer
 * lays it out (float xyz [+ uchar rgba] vertices, uchar-count int-index
 * triangle faces [+ uchar rgba]) and checks it independently of the
 * project's readers: header counts against the file size, list counts,
 * index ranges. Test sizes are small, so the file is read whole. */
#ifndef OIT_TESTS_SCENE_PLY_CHECK_H
#define OIT_TESTS_SCENE_PLY_CHECK_H

#include "tests/lib/test_files.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct test_ply {
    size_t vertices, faces, header_bytes, file_bytes;
    int vertex_rgba, face_rgba;
    float *xyz;       /* 3 per vertex */
    uint8_t *vrgba;   /* 4 per vertex when vertex_rgba */
    uint32_t *idx;    /* 3 per face */
    uint8_t *frgba;   /* 4 per face when face_rgba */
    char why[1024];   /* what failed */
} test_ply;

static inline uint32_t test_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline void test_ply_free(test_ply *p)
{
    free(p->xyz);
    free(p->vrgba);
    free(p->idx);
    free(p->frgba);
}

/* Parses the header lines; 0 on success. */
static inline int test_ply_header(test_ply *p, const char *h)
{
    if (strncmp(h, "ply\nformat binary_little_endian 1.0\n", 36))
        return snprintf(p->why, sizeof p->why, "bad magic/format line"), 1;
    int in_face = -1, props = 0;
    for (const char *l = h; *l; l = strchr(l, '\n') + 1) {
        unsigned long long n;
        if (sscanf(l, "element vertex %llu", &n) == 1)
            p->vertices = (size_t)n, in_face = 0, props = 0;
        else if (sscanf(l, "element face %llu", &n) == 1)
            p->faces = (size_t)n, in_face = 1, props = 0;
        else if (!strncmp(l, "property uchar red", 18))
            *(in_face ? &p->face_rgba : &p->vertex_rgba) = 1;
        else if (!strncmp(l, "property list uchar int vertex_indices", 38) && in_face != 1)
            return snprintf(p->why, sizeof p->why, "face list outside face element"), 1;
        if (!strncmp(l, "property", 8))
            props++;
        if (!strncmp(l, "end_header\n", 11))
            break;
    }
    return 0;
}

/* Loads path into p; 0 on success, else p->why says what is wrong. */
static inline int test_ply_load(test_ply *p, const char *path)
{
    memset(p, 0, sizeof *p);
    size_t size;
    uint8_t *b = test_read_file(path, &size);
    if (!b)
        return snprintf(p->why, sizeof p->why, "%s: cannot read", path), 1;
    p->file_bytes = size;
    const char *end = NULL;
    for (size_t i = 0; i + 11 <= size && i < 4096 && !end; i++)
        if (!memcmp(b + i, "end_header\n", 11))
            end = (const char *)b + i + 11;
    int bad = !end;
    if (bad)
        snprintf(p->why, sizeof p->why, "%s: no end_header", path);
    char *h = NULL;
    if (!bad) {
        p->header_bytes = (size_t)(end - (const char *)b);
        h = malloc(p->header_bytes + 1);
        memcpy(h, b, p->header_bytes);
        h[p->header_bytes] = 0;
        bad = test_ply_header(p, h);
    }
    size_t vs = p->vertex_rgba ? 16 : 12, fs = p->face_rgba ? 17 : 13;
    if (!bad && p->header_bytes + p->vertices * vs + p->faces * fs != size)
        bad = snprintf(p->why, sizeof p->why, "%s: size %zu, header declares %zu", path, size,
                       p->header_bytes + p->vertices * vs + p->faces * fs) > 0;
    if (!bad) {
        p->xyz = malloc(3 * sizeof(float) * (p->vertices + 1));
        p->vrgba = malloc(4 * (p->vertices + 1));
        p->idx = malloc(3 * sizeof(uint32_t) * (p->faces + 1));
        p->frgba = malloc(4 * (p->faces + 1));
        const uint8_t *q = (const uint8_t *)end;
        for (size_t i = 0; i < p->vertices; i++, q += vs) {
            for (int k = 0; k < 3; k++) {
                uint32_t u = test_u32(q + 4 * k);
                memcpy(p->xyz + 3 * i + k, &u, 4);
            }
            if (p->vertex_rgba)
                memcpy(p->vrgba + 4 * i, q + 12, 4);
        }
        for (size_t i = 0; i < p->faces && !bad; i++, q += fs) {
            if (q[0] != 3)
                bad = snprintf(p->why, sizeof p->why, "%s: face %zu has %u corners", path, i, q[0]) > 0;
            for (int k = 0; k < 3 && !bad; k++) {
                p->idx[3 * i + k] = test_u32(q + 1 + 4 * k);
                if (p->idx[3 * i + k] >= p->vertices)
                    bad = snprintf(p->why, sizeof p->why, "%s: face %zu index %u >= %zu", path, i,
                                   p->idx[3 * i + k], p->vertices) > 0;
            }
            if (p->face_rgba)
                memcpy(p->frgba + 4 * i, q + 13, 4);
        }
    }
    free(h);
    free(b);
    return bad;
}

/* Signed volume (divergence theorem) of faces [f0, f1): positive for a
 * closed surface wound counter-clockwise seen from outside. */
static inline double test_ply_volume(const test_ply *p, size_t f0, size_t f1)
{
    double v = 0;
    for (size_t f = f0; f < f1; f++) {
        const float *a = p->xyz + 3 * p->idx[3 * f], *b = p->xyz + 3 * p->idx[3 * f + 1],
                    *c = p->xyz + 3 * p->idx[3 * f + 2];
        v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
             (double)a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
             (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    return v / 6.0;
}

static inline int test_cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Directed edges that break closed, consistently oriented surfaces: each
 * edge a->b must occur exactly once and b->a exactly once. Returns the
 * number of offending edges. */
static inline size_t test_ply_open_edges(const test_ply *p)
{
    size_t n = 3 * p->faces, bad = 0;
    uint64_t *e = malloc(sizeof *e * (n + 1));
    for (size_t f = 0; f < p->faces; f++)
        for (int k = 0; k < 3; k++)
            e[3 * f + k] = (uint64_t)p->idx[3 * f + k] << 32 | p->idx[3 * f + (k + 1) % 3];
    qsort(e, n, sizeof *e, test_cmp_u64);
    for (size_t i = 0; i < n; i++) {
        uint64_t r = e[i] << 32 | e[i] >> 32;
        int dup = (i + 1 < n && e[i + 1] == e[i]) || (i > 0 && e[i - 1] == e[i]);
        if (dup || !bsearch(&r, e, n, sizeof *e, test_cmp_u64))
            bad++;
    }
    free(e);
    return bad;
}

static inline uint32_t test_find(uint32_t *parent, uint32_t v)
{
    while (parent[v] != v)
        v = parent[v] = parent[parent[v]];
    return v;
}

/* Splits the mesh into vertex-connected components (one per solid) and
 * counts those whose signed volume is not positive (inside out) and those
 * whose triangles do not all share the first corner's colour. */
static inline void test_ply_components(const test_ply *p, size_t *components, size_t *inverted,
                                size_t *multicolour)
{
    uint32_t *parent = malloc(sizeof *parent * (p->vertices + 1));
    double *vol = calloc(p->vertices + 1, sizeof *vol);
    uint32_t *colour = malloc(sizeof *colour * (p->vertices + 1));
    for (size_t v = 0; v < p->vertices; v++)
        parent[v] = (uint32_t)v;
    for (size_t f = 0; f < p->faces; f++)
        for (int k = 1; k < 3; k++)
            parent[test_find(parent, p->idx[3 * f + k])] = test_find(parent, p->idx[3 * f]);
    for (size_t f = 0; f < p->faces; f++)
        vol[test_find(parent, p->idx[3 * f])] += test_ply_volume(p, f, f + 1);
    *components = *inverted = *multicolour = 0;
    for (size_t v = 0; v < p->vertices; v++) {
        uint32_t r = test_find(parent, (uint32_t)v), c;
        memcpy(&c, p->vrgba + 4 * v, 4);
        if (r == v) {
            colour[r] = c;
            ++*components;
            *inverted += !(vol[r] > 0);
        }
    }
    for (size_t v = 0; v < p->vertices; v++) {
        uint32_t c;
        memcpy(&c, p->vrgba + 4 * v, 4);
        if (p->vertex_rgba && c != colour[test_find(parent, (uint32_t)v)])
            ++*multicolour;
    }
    free(parent);
    free(vol);
    free(colour);
}

#endif
