/* Conversion statistics as JSON (stats_json.h). */
#include "prepare/convert/stats_json.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "base/json.h"

/* The seconds of the whole conversion and of each stage. */
static void put_seconds(oit_json *w, const oit_convert_stats *s)
{
    oit_json_begin_object(w, "seconds", OIT_JSON_INLINE);
    oit_json_fixed(w, "total", s->seconds_total, 3);
    oit_json_begin_object(w, "stages", OIT_JSON_INLINE);
    oit_json_fixed(w, "bounds", s->seconds_bounds, 3);
    oit_json_fixed(w, "bin", s->seconds_bin, 3);
    oit_json_fixed(w, "partition", s->seconds_partition, 3);
    oit_json_fixed(w, "write", s->seconds_write, 3);
    oit_json_end(w);
    oit_json_end(w);
}

oit_status oit_convert_stats_write_json(const char *path, const oit_convert_options *o,
                                        const oit_convert_stats *s, oit_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write stats: %s", path, strerror(errno));
    oit_json w;
    oit_json_init(&w, f, path);
    const oit_json_uint_member dropped[] = {
        {"triangles_in", s->triangles_in}, {"triangles_out", s->triangles_out},
        {"degenerate_dropped", s->degenerate_dropped}, {"nonfinite_dropped", s->nonfinite_dropped}};
    const oit_json_uint_member layout[] = {
        {"pieces", s->pieces}, {"pieces_clustered", s->pieces_clustered},
        {"wide_parts", s->wide_parts}, {"max_layer_bound", s->max_layer_bound},
        {"parts", s->parts}, {"slabs", s->slabs}, {"cut_slabs", s->cut_slabs},
        {"cells", s->cells}, {"subgrids", s->subgrids}, {"subgrid_depth", s->subgrid_depth}};
    const oit_json_uint_member run[] = {{"peak_rss_bytes", s->peak_rss_bytes},
                                        {"threads", s->threads}, {"K", s->K},
                                        {"memory", o->memory}};
    oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
    OIT_JSON_UINTS(&w, dropped);
    oit_json_int(&w, "split_added", s->split_added);
    OIT_JSON_UINTS(&w, layout);
    oit_json_begin_array(&w, "grid", OIT_JSON_INLINE);
    for (int k = 0; k < 3; k++)
        oit_json_uint(&w, NULL, s->grid_dims[k]);
    oit_json_end(&w);
    oit_json_uint(&w, "spilled_bytes", s->spilled_bytes);
    put_seconds(&w, s);
    OIT_JSON_UINTS(&w, run);
    oit_json_string(&w, "manage", oit_manage_name(o->manage));
    oit_json_string(&w, "scheme", oit_scheme_name(o->scheme));
    oit_json_uint(&w, "part_triangles",
                  o->scheme == OIT_SCHEME_FAST
                      ? (o->part_triangles ? o->part_triangles : OIT_FAST_PART_TRIANGLES)
                      : 0);
    oit_json_uint(&w, "clamped_parts", s->clamped_parts);
    oit_json_uint(&w, "max_measured_layers", s->max_measured);
    /* STEP/IGES: the tessellation's chordal deflection; 0 for meshes */
    oit_json_general(&w, "deflection", s->deflection, 9);
    oit_json_end(&w);
    return oit_json_close(&w, err);
}
