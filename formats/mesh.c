#include "oit/mesh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void oit_mesh_info_init(oit_mesh_info *info)
{
    memset(info, 0, sizeof *info);
    for (int k = 0; k < 3; k++) {
        info->bounds_min[k] = INFINITY;
        info->bounds_max[k] = -INFINITY;
    }
}

void oit_mesh_origin_pick(const double first[3], double origin[3])
{
    for (int k = 0; k < 3; k++)
        origin[k] = fabs(first[k]) < 65536.0 || !isfinite(first[k]) ? 0.0
                                                                     : nearbyint(first[k]);
}

void oit_mesh_position(const double origin[3], const double in[3], float out[3])
{
    for (int k = 0; k < 3; k++) {
        double d = in[k] - origin[k];
        out[k] = d > FLT_MAX ? INFINITY : d < -FLT_MAX ? -INFINITY : (float)d;
    }
}

/* Zero cross product of two float edges: no plane, no fragment. */
static int zero_area(const oit_triangle *t)
{
    const float *a = t->v[0].pos, *b = t->v[1].pos, *c = t->v[2].pos;
    float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return u[1] * w[2] - u[2] * w[1] == 0.0f && u[2] * w[0] - u[0] * w[2] == 0.0f &&
           u[0] * w[1] - u[1] * w[0] == 0.0f;
}

void oit_mesh_info_add(oit_mesh_info *info, const oit_triangle *tris, size_t count)
{
    for (size_t i = 0; i < count; i++)
        info->zero_area += (uint64_t)zero_area(&tris[i]);
    for (size_t i = 0; i < count; i++)
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                float x = tris[i].v[v].pos[k];
                if (x < info->bounds_min[k]) info->bounds_min[k] = x;
                if (x > info->bounds_max[k]) info->bounds_max[k] = x;
            }
    info->triangles += count;
}

void oit_mesh_info_opaque(oit_mesh_info *info, const oit_triangle *tris, size_t count)
{
    for (size_t i = 0; i < count && !(info->attributes & OIT_ATTR_OPAQUE); i++)
        if (tris[i].v[0].rgba[3] == 255 && tris[i].v[1].rgba[3] == 255 &&
            tris[i].v[2].rgba[3] == 255)
            info->attributes |= OIT_ATTR_OPAQUE;
    if (!(info->attributes & OIT_ATTR_ALPHA))
        info->attributes &= ~(uint32_t)OIT_ATTR_OPAQUE;
}

int oit_triangle_is_finite(const oit_triangle *t)
{
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(t->v[v].pos[k]))
                return 0;
    return 1;
}

oit_status oit_mesh_append(oit_mesh *m, const oit_triangle *tris, size_t count,
                           oit_error *err)
{
    if (count > SIZE_MAX / sizeof(oit_triangle) / 2 - m->count)
        return oit_error_set(err, OIT_ERR_NOMEM, "mesh of %zu + %zu triangles is too large",
                             m->count, count);
    size_t need = m->count + count;
    if (need > m->capacity) {
        size_t ncap = m->capacity ? m->capacity : 1024;
        while (ncap < need)
            ncap *= 2;
        oit_triangle *p = realloc(m->tris, ncap * sizeof *p);
        if (!p)
            return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate %zu triangles (%zu bytes)",
                                 ncap, ncap * sizeof *p);
        m->tris = p;
        m->capacity = ncap;
    }
    if (count)
        memcpy(m->tris + m->count, tris, count * sizeof *tris);
    m->count = need;
    return OIT_OK;
}

void oit_mesh_free(oit_mesh *m)
{
    if (!m) return;
    free(m->tris);
    m->tris = NULL;
    m->count = 0;
    m->capacity = 0;
}
