/* Part blobs as triangle soups (triangles.h). */
#include "partfile/triangles.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Triangle t of a part view. */
static void expand_triangle(const oit_partfile_part_view *v, uint64_t t, oit_triangle *out)
{
    const char *base = (const char *)v->positions;
    for (int c = 0; c < 3; c++) {
        uint32_t k = oit_partfile_index(v, 3 * t + (uint64_t)c);
        oit_vertex *o = &out->v[c];
        memcpy(o->pos, base + (size_t)k * v->stride, sizeof o->pos);
        if (v->rgba)
            memcpy(o->rgba, v->rgba + (size_t)k * v->stride, 4);
        else
            memset(o->rgba, 255, 4);
    }
}

/* The part's triangles into dst; the view, for what else the caller needs. */
static oit_status expand_part(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                              oit_triangle *dst, oit_partfile_part_view *v, oit_error *err)
{
    oit_status s = oit_partfile_part_load(pf, part, buf, v, err);
    if (s != OIT_OK)
        return s;
    for (uint64_t t = 0; t < v->index_count / 3; t++)
        expand_triangle(v, t, &dst[t]);
    return OIT_OK;
}

oit_status oit_part_expand(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                           oit_triangle *dst, oit_error *err)
{
    oit_partfile_part_view v;
    return expand_part(pf, part, buf, dst, &v, err);
}

oit_status oit_part_expand_sourced(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                                   void *dst, oit_error *err)
{
    oit_partfile_part_view v;
    oit_status s = expand_part(pf, part, buf, dst, &v, err);
    if (s != OIT_OK)
        return s;
    uint64_t n = v.index_count / 3;
    memcpy((char *)dst + n * sizeof(oit_triangle), v.sources, n * sizeof(uint32_t));
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

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The rare path of oit_partfile_load_mesh: triangles_in out of proportion
 * to the triangles stored (a source mostly dropped, or a crafted file), so
 * that a bucket per source index would cost more than the mesh. Every part
 * expanded in file order, the keys source << 32 | position sorted (the
 * position makes it stable), then the mesh permuted in place, cycle by
 * cycle. */
static oit_status load_sorted_by_keys(oit_partfile *pf, oit_mesh *out, oit_error *err)
{
    uint32_t n = oit_partfile_part_count(pf);
    oit_partfile_part_view v;
    oit_partfile_buffer buf = {0};
    oit_status s = OIT_OK;
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_part_expand(pf, p, &buf, out->tris + out->count, err);
        out->count += (size_t)(oit_partfile_parts(pf)[p].index_count / 3);
    }
    if (s != OIT_OK) {
        oit_partfile_buffer_free(&buf);
        return s;
    }
    size_t count = out->count;
    uint64_t *key = count <= UINT32_MAX ? malloc((count ? count : 1) * sizeof *key) : NULL;
    uint8_t *done = key ? calloc(count / 8 + 1, 1) : NULL;
    if (!done) {
        free(key);
        oit_partfile_buffer_free(&buf);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot sort %zu triangles by their "
                             "source indices", oit_partfile_name(pf), count);
    }
    size_t at = 0;
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_partfile_part_data(pf, p, &buf, &v, err);
        for (uint64_t t = 0; s == OIT_OK && t < v.index_count / 3; t++, at++)
            key[at] = (uint64_t)oit_partfile_source(&v, t) << 32 | at;
    }
    if (s == OIT_OK)
        qsort(key, count, sizeof *key, cmp_u64);
    /* Position i takes the triangle at key[i]'s position. */
    for (size_t i = 0; s == OIT_OK && i < count; i++) {
        if (done[i / 8] >> (i % 8) & 1)
            continue;
        oit_triangle first = out->tris[i];
        for (size_t j = i;;) {
            done[j / 8] |= (uint8_t)(1u << (j % 8));
            size_t k = (size_t)(key[j] & 0xffffffffu);
            if (k == i) {
                out->tris[j] = first;
                break;
            }
            out->tris[j] = out->tris[k];
            j = k;
        }
    }
    free(key);
    free(done);
    oit_partfile_buffer_free(&buf);
    return s;
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
    if (sum.triangles_in > 2 * sum.triangles + 65536) {
        s = load_sorted_by_keys(pf, out, err);
        if (s != OIT_OK) {
            oit_mesh_free(out);
            return s;
        }
        oit_partfile_mesh_info(pf, &out->info);
        return OIT_OK;
    }
    /* A counting sort by source index (every index < triangles_in, checked
     * by validation): count, prefix sums, then each part's triangles go
     * straight to their places, parts and triangles in file order, which
     * keeps it stable. */
    size_t *next = calloc((size_t)sum.triangles_in + 1, sizeof *next);
    if (!next) {
        oit_mesh_free(out);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot sort %llu triangles by their %llu "
                             "source indices", oit_partfile_name(pf),
                             (unsigned long long)sum.triangles,
                             (unsigned long long)sum.triangles_in);
    }
    oit_partfile_part_view v;
    oit_partfile_buffer buf = {0};
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_partfile_part_load(pf, p, &buf, &v, err);
        for (uint64_t t = 0; s == OIT_OK && t < v.index_count / 3; t++)
            next[oit_partfile_source(&v, t) + 1]++;
    }
    for (uint64_t i = 1; s == OIT_OK && i <= sum.triangles_in; i++)
        next[i] += next[i - 1];
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_partfile_part_data(pf, p, &buf, &v, err);
        for (uint64_t t = 0; s == OIT_OK && t < v.index_count / 3; t++)
            expand_triangle(&v, t, &out->tris[next[oit_partfile_source(&v, t)]++]);
        out->count += (size_t)(parts[p].index_count / 3);
    }
    free(next);
    oit_partfile_buffer_free(&buf);
    if (s != OIT_OK) {
        oit_mesh_free(out);
        return s;
    }
    oit_partfile_mesh_info(pf, &out->info);
    return OIT_OK;
}
