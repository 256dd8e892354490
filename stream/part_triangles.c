/* Part blobs as triangle soups (part_triangles.h). */
#include "stream/part_triangles.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

oit_status oit_part_expand(const oit_partfile *pf, uint32_t part, oit_triangle *dst,
                           oit_error *err)
{
    oit_partfile_part_view v;
    oit_status s = oit_partfile_part_data(pf, part, &v, err);
    if (s != OIT_OK)
        return s;
    const char *base = (const char *)v.positions;
    for (uint64_t i = 0; i < v.index_count; i++) {
        uint32_t k = oit_partfile_index(&v, i);
        oit_vertex *out = &dst[i / 3].v[i % 3];
        memcpy(out->pos, base + (size_t)k * v.stride, sizeof out->pos);
        if (v.rgba)
            memcpy(out->rgba, v.rgba + (size_t)k * v.stride, 4);
        else
            memset(out->rgba, 255, 4);
    }
    return OIT_OK;
}

void oit_partfile_mesh_info(const oit_partfile *pf, oit_mesh_info *info)
{
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    oit_mesh_info_init(info);
    info->triangles = sum.triangles;
    info->faces_in = sum.triangles_in;
    info->attributes = sum.attributes;
    memcpy(info->origin, sum.origin, sizeof info->origin);
    if (sum.parts) {
        memcpy(info->bounds_min, sum.bounds_min, sizeof info->bounds_min);
        memcpy(info->bounds_max, sum.bounds_max, sizeof info->bounds_max);
    }
}

oit_status oit_partfile_load_mesh(oit_partfile *pf, oit_mesh *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    uint32_t n = oit_partfile_part_count(pf);
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    if (sum.triangles > SIZE_MAX / sizeof(oit_triangle) ||
        !(out->tris = malloc((size_t)(sum.triangles ? sum.triangles : 1) * sizeof(oit_triangle))))
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold %llu triangles in core",
                             oit_partfile_name(pf), (unsigned long long)sum.triangles);
    out->capacity = (size_t)sum.triangles;
    oit_status s = OIT_OK;
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_partfile_validate_part(pf, p, err);
        if (s == OIT_OK)
            s = oit_part_expand(pf, p, out->tris + out->count, err);
        out->count += (size_t)(parts[p].index_count / 3);
    }
    if (s != OIT_OK) {
        oit_mesh_free(out);
        return s;
    }
    oit_partfile_mesh_info(pf, &out->info);
    return OIT_OK;
}
