/* Conversion statistics as JSON (stats_json.h). */
#include "preprocess/stats_json.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

oit_status oit_convert_stats_write_json(const char *path, const oit_convert_options *o,
                                        const oit_convert_stats *s, oit_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write stats: %s", path, strerror(errno));
    fprintf(f,
            "{\"triangles_in\": %llu, \"triangles_out\": %llu, \"degenerate_dropped\": %llu, "
            "\"nonfinite_dropped\": %llu, \"split_added\": %lld, \"pieces\": %llu, "
            "\"pieces_clustered\": %llu, \"wide_parts\": %llu, \"max_layer_bound\": %u, "
            "\"parts\": %llu, \"slabs\": %llu, \"cut_slabs\": %llu, \"cells\": %llu, \"subgrids\": %llu, "
            "\"subgrid_depth\": %u, \"grid\": [%u, %u, %u], \"spilled_bytes\": %llu, "
            "\"seconds\": {\"total\": %.3f, \"stages\": {\"bounds\": %.3f, \"bin\": %.3f, "
            "\"partition\": %.3f, \"write\": %.3f}}, \"peak_rss_bytes\": %llu, "
            "\"threads\": %u, \"K\": %u, \"memory\": %zu, \"manage\": \"%s\", "
            "\"scheme\": \"%s\", \"part_triangles\": %u, \"clamped_parts\": %llu, "
            "\"max_measured_layers\": %u}\n",
            (unsigned long long)s->triangles_in, (unsigned long long)s->triangles_out,
            (unsigned long long)s->degenerate_dropped, (unsigned long long)s->nonfinite_dropped,
            (long long)s->split_added, (unsigned long long)s->pieces,
            (unsigned long long)s->pieces_clustered, (unsigned long long)s->wide_parts,
            s->max_layer_bound,
            (unsigned long long)s->parts, (unsigned long long)s->slabs,
            (unsigned long long)s->cut_slabs, (unsigned long long)s->cells,
            (unsigned long long)s->subgrids, s->subgrid_depth, s->grid_dims[0], s->grid_dims[1],
            s->grid_dims[2], (unsigned long long)s->spilled_bytes, s->seconds_total,
            s->seconds_bounds, s->seconds_bin, s->seconds_partition, s->seconds_write,
            (unsigned long long)s->peak_rss_bytes, s->threads, s->K, o->memory,
            oit_manage_name(o->manage), oit_scheme_name(o->scheme),
            o->scheme == OIT_SCHEME_FAST ? (o->part_triangles ? o->part_triangles
                                                              : OIT_FAST_PART_TRIANGLES)
                                         : 0,
            (unsigned long long)s->clamped_parts, s->max_measured);
    if (fclose(f))
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write stats: %s", path, strerror(errno));
    return OIT_OK;
}
