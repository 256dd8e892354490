/* instances: N copies of an input mesh in a near-square grid on the XZ
 * plane (Y up), spaced 1.1 times the mesh's extent, each in its own colour
 * with alpha. The input is read once through oit_mesh_read and re-indexed
 * (bit-identical positions merged) so that copies share vertices the way the
 * input's surface does; memory is that of one copy. Input colours are
 * replaced by the instance colour. */
#include "prepare/scenes/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit/mesh.h"
#include "prepare/scenes/rng.h"

typedef struct indexed_mesh {
    float *pos; /* 3 per vertex */
    uint32_t nv, cap_v;
    uint32_t *tri; /* 3 per triangle */
    uint64_t nt, cap_t;
    uint32_t *slots; /* open-addressing hash: vertex index + 1, 0 = empty */
    uint64_t nslots;
    const char *path;
} indexed_mesh;

static uint64_t hash_pos(const float *p)
{
    uint32_t b[3];
    memcpy(b, p, sizeof b);
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int k = 0; k < 3; k++)
        h = (h ^ b[k]) * 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 31);
}

static int grow(void **p, uint64_t *cap, uint64_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    uint64_t c = *cap ? *cap : 1024;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

static oit_status rehash(indexed_mesh *m, oit_error *err)
{
    uint64_t n = m->nslots ? m->nslots * 2 : 4096;
    uint32_t *s = calloc(n, sizeof *s);
    if (!s)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate vertex table", m->path);
    for (uint32_t v = 0; v < m->nv; v++) {
        uint64_t h = hash_pos(m->pos + 3 * v) & (n - 1);
        while (s[h])
            h = (h + 1) & (n - 1);
        s[h] = v + 1;
    }
    free(m->slots);
    m->slots = s;
    m->nslots = n;
    return OIT_OK;
}

/* Index of position p, added when new; UINT32_MAX on failure (err set). */
static uint32_t vertex_index(indexed_mesh *m, const float *p, oit_error *err)
{
    if ((uint64_t)(m->nv + 1) * 2 > m->nslots && rehash(m, err))
        return UINT32_MAX;
    uint64_t h = hash_pos(p) & (m->nslots - 1);
    for (; m->slots[h]; h = (h + 1) & (m->nslots - 1))
        if (!memcmp(m->pos + 3 * (m->slots[h] - 1), p, 3 * sizeof(float)))
            return m->slots[h] - 1;
    uint64_t cap = m->cap_v;
    if (m->nv == UINT32_MAX - 1 || !grow((void **)&m->pos, &cap, m->nv + 1u, 3 * sizeof(float))) {
        oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot grow vertex array (%u vertices)",
                      m->path, m->nv);
        return UINT32_MAX;
    }
    m->cap_v = (uint32_t)(cap > UINT32_MAX ? UINT32_MAX : cap);
    memcpy(m->pos + 3 * m->nv, p, 3 * sizeof(float));
    m->slots[h] = ++m->nv;
    return m->nv - 1;
}

static oit_status sink(void *user, const oit_triangle *tris, size_t count, oit_error *err)
{
    indexed_mesh *m = user;
    if (!grow((void **)&m->tri, &m->cap_t, m->nt + count, 3 * sizeof(uint32_t)))
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot grow triangle array", m->path);
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = vertex_index(m, tris[i].v[k].pos, err);
            if (v == UINT32_MAX)
                return err ? err->status : OIT_ERR_NOMEM;
            m->tri[3 * (m->nt + i) + k] = v;
        }
    m->nt += count;
    return OIT_OK;
}

static void free_mesh(indexed_mesh *m)
{
    free(m->pos);
    free(m->tri);
    free(m->slots);
}

static void emit_copy(oit_emit *e, const indexed_mesh *m, oit_v3 offset)
{
    uint32_t base = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        const float *p = m->pos + 3 * v;
        uint32_t id = oit_emit_vertex(e, oit_v3_make(p[0] + offset.x, p[1] + offset.y, p[2] + offset.z));
        if (v == 0)
            base = id;
    }
    for (uint64_t t = 0; t < m->nt; t++)
        oit_emit_tri(e, base + m->tri[3 * t], base + m->tri[3 * t + 1], base + m->tri[3 * t + 2]);
}

oit_status oit_scene_instances(oit_emit *e, const oit_scene_args *a, oit_error *err)
{
    indexed_mesh m = {.path = a->input};
    oit_mesh_info info;
    oit_status s = oit_mesh_read(a->input, NULL, sink, &m, &info, err);
    if (!s && m.nt == 0)
        s = oit_error_set(err, OIT_ERR_FORMAT, "%s: no triangles to replicate", a->input);
    if (!s && (uint64_t)m.nv * a->count > OIT_PLY_WRITER_MAX_VERTICES)
        s = oit_error_set(err, OIT_ERR_UNSUPPORTED,
                          "%s: %llu copies of %u vertices exceed the PLY index range",
                          a->input, (unsigned long long)a->count, m.nv);
    if (s) {
        free_mesh(&m);
        return s;
    }
    float ext[3], emax = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = info.bounds_max[k] - info.bounds_min[k];
        emax = fmaxf(emax, ext[k]);
    }
    /* A flat mesh still needs a gap between its copies. */
    float sx = 1.1f * fmaxf(ext[0], 0.05f * emax), sz = 1.1f * fmaxf(ext[2], 0.05f * emax);
    uint64_t cols = (uint64_t)ceil(sqrt((double)a->count));
    oit_rng rng = oit_rng_make(a->seed, 2);
    for (uint64_t i = 0; i < a->count && !e->status; i++) {
        uint8_t rgb[3];
        oit_scene_hsv((float)oit_rng_unit(&rng), 0.7f, 0.95f, rgb);
        oit_emit_color(e, rgb[0], rgb[1], rgb[2], (uint8_t)oit_rng_range(&rng, 77, 179));
        emit_copy(e, &m, oit_v3_make(sx * (float)(i % cols), 0, sz * (float)(i / cols)));
    }
    free_mesh(&m);
    return oit_emit_flush(e);
}
