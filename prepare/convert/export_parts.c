/* A part file's parts as a coloured PLY (export_parts.h). */
#include "prepare/convert/export_parts.h"

#include <stdlib.h>
#include <string.h>

#include "formats/ply_writer.h"
#include "oit/partfile.h"

enum { KIND_AXIS, KIND_SEPARATING, KIND_CUTTING, KIND_WIDE };

static const uint8_t kind_rgb[4][3] = {
    {170, 170, 170}, {40, 110, 230}, {245, 140, 20}, {220, 30, 30}};

/* Per part: which slab kind it belongs to (the last one naming it). */
/* Wide parts are the guaranteed scheme's: in a file of measured bounds
 * (the fast scheme) a part above K is only deep, and is painted as what it
 * is, an axis split. */
static uint8_t *part_kinds(const oit_partfile *pf, uint32_t K, bool measured)
{
    uint32_t n = oit_partfile_part_count(pf);
    uint8_t *kind = calloc(n ? n : 1, 1);
    if (!kind)
        return NULL;
    for (uint32_t s = 0; s < oit_partfile_slab_count(pf); s++) {
        const oit_partfile_slab *sl = oit_partfile_slab_at(pf, s);
        uint8_t k = sl->d0 == sl->d1 ? KIND_CUTTING : KIND_SEPARATING;
        kind[sl->part_below] = kind[sl->part_above] = k;
        uint32_t m = 0;
        const uint32_t *in = oit_partfile_slab_inside(pf, s, &m);
        for (uint32_t i = 0; i < m; i++)
            kind[in[i]] = k;
    }
    for (uint32_t p = 0; p < n && !measured; p++)
        if (oit_partfile_parts(pf)[p].layer_bound > K)
            kind[p] = KIND_WIDE;
    return kind;
}

/* A hue per part, golden-ratio spaced so consecutive parts (neighbours in
 * the tree) differ; saturated, not dark. */
static void part_rgb(uint32_t p, uint8_t rgb[3])
{
    double h = (double)p * 0.6180339887498949;
    h = (h - (double)(uint64_t)h) * 6;
    int sector = (int)h;
    double f = h - sector, hi = 235, lo = 60, up = lo + f * (hi - lo), down = hi - f * (hi - lo);
    double c[6][3] = {{hi, up, lo},   {down, hi, lo}, {lo, hi, up},
                      {lo, down, hi}, {up, lo, hi},   {hi, lo, down}};
    for (int k = 0; k < 3; k++)
        rgb[k] = (uint8_t)c[sector % 6][k];
}

static oit_status write_part(oit_ply_writer *w, const oit_partfile *pf, uint32_t p,
                             const uint8_t rgb[3], uint8_t alpha, oit_error *err)
{
    oit_partfile_part_view v;
    oit_partfile_buffer buf = {0};
    oit_status s = oit_partfile_part_data(pf, p, &buf, &v, err);
    uint32_t nv = oit_partfile_parts(pf)[p].vertex_count;
    float *xyz = s ? NULL : malloc((nv ? nv : 1) * 12u);
    uint8_t *rgba = s ? NULL : malloc((nv ? nv : 1) * 4u);
    uint32_t *idx = s ? NULL : malloc((v.index_count ? v.index_count : 1) * sizeof *idx);
    if (!s && (!xyz || !rgba || !idx))
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: part %u: out of memory",
                          oit_partfile_name(pf), p);
    uint32_t first = 0;
    if (!s) {
        for (uint32_t i = 0; i < nv; i++) {
            const char *q = (const char *)v.positions + (size_t)i * v.stride;
            memcpy(xyz + 3 * i, q, 12);
            memcpy(rgba + 4 * i, rgb, 3);
            rgba[4 * i + 3] = alpha ? alpha : v.rgba ? ((const uint8_t *)q)[15] : 255;
        }
        s = oit_ply_writer_add_vertices(w, xyz, rgba, nv, &first, err);
    }
    if (!s) {
        for (uint64_t i = 0; i < v.index_count; i++)
            idx[i] = first + oit_partfile_index(&v, i);
        s = oit_ply_writer_add_faces(w, idx, NULL, v.index_count / 3, err);
    }
    oit_partfile_drop_part_data(pf, p, 1);
    oit_partfile_buffer_free(&buf);
    free(xyz);
    free(rgba);
    free(idx);
    return s;
}

oit_status oit_export_parts(const char *path, const char *out, oit_export_colour colour,
                            uint8_t alpha, oit_export_counts *counts, oit_error *err)
{
    oit_export_counts c = {0};
    oit_partfile *pf = NULL;
    oit_status s = oit_partfile_open(path, NULL, &pf, err);
    if (s)
        return s;
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    uint8_t *kind = part_kinds(pf, sum.K, sum.measured_bounds);
    oit_ply_writer *w = NULL;
    oit_ply_writer_desc d = {.path = out, .vertex_rgba = 1, .vertex_double = 1,
                             .comment = colour == OIT_EXPORT_BY_KIND
                                            ? "oitprep parts: grey axis, blue separating slab, "
                                              "orange cutting plane, red wide"
                                            : "oitprep parts: a colour per part"};
    memcpy(d.offset, sum.origin, sizeof d.offset);
    if (!kind)
        s = oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", path);
    else
        s = oit_ply_writer_open(&d, &w, err);
    for (uint32_t p = 0; !s && p < sum.parts; p++) {
        uint8_t rgb[3];
        if (colour == OIT_EXPORT_BY_KIND)
            memcpy(rgb, kind_rgb[kind[p]], 3);
        else
            part_rgb(p, rgb);
        s = write_part(w, pf, p, rgb, alpha, err);
        c.parts++;
        c.separating_parts += kind[p] == KIND_SEPARATING;
        c.cutting_parts += kind[p] == KIND_CUTTING;
        c.wide_parts += kind[p] == KIND_WIDE;
    }
    if (w) {
        oit_ply_writer_stats st = {0};
        oit_status cs = oit_ply_writer_close(w, &st, s ? NULL : err);
        s = s ? s : cs;
        c.triangles = st.faces;
    }
    free(kind);
    oit_partfile_close(pf);
    if (counts)
        *counts = c;
    return s;
}
