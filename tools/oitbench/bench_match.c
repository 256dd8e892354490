/* Does a part file come from a mesh (bench_match.h). */
#include "tools/oitbench/bench_match.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec.h"
#include "partfile/triangles.h"

/* m[0] += area, m[1..3] += area * centroid, over n triangles. */
static void add_moments(const oit_triangle *t, size_t n, double m[4])
{
    for (size_t i = 0; i < n; i++) {
        const float *a = t[i].v[0].pos, *b = t[i].v[1].pos, *c = t[i].v[2].pos;
        double area = oit_area3fd(a, b, c);
        m[0] += area;
        for (int k = 0; k < 3; k++)
            m[1 + k] += area * ((double)a[k] + b[k] + c[k]) / 3.0;
    }
}

/* The same over every part of pf, one part in memory at a time. */
static oit_status part_moments(oit_partfile *pf, double m[4], oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    uint32_t n = oit_partfile_part_count(pf);
    uint64_t most = 0;
    for (uint32_t p = 0; p < n; p++)
        most = parts[p].index_count / 3 > most ? parts[p].index_count / 3 : most;
    oit_triangle *buf = malloc((size_t)(most ? most : 1) * sizeof *buf);
    if (!buf)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold a part of %llu triangles",
                             oit_partfile_name(pf), (unsigned long long)most);
    oit_status s = OIT_OK;
    oit_partfile_buffer decoded = {0};
    for (uint32_t p = 0; p < n && s == OIT_OK; p++) {
        s = oit_part_expand(pf, p, &decoded, buf, err);
        if (s == OIT_OK)
            add_moments(buf, (size_t)(parts[p].index_count / 3), m);
    }
    oit_partfile_buffer_free(&decoded);
    free(buf);
    return s;
}

static double diagonal(const oit_mesh_info *i)
{
    double d = 0.0;
    for (int k = 0; k < 3; k++) {
        double e = (double)i->bounds_max[k] - i->bounds_min[k];
        d += e * e;
    }
    return sqrt(d);
}

/* The counts, origin and bounds: what META says without reading parts. */
static void header_mismatch(const oit_mesh_info *i, const oit_partfile_summary *s, char *why,
                            size_t cap)
{
    uint64_t read = i->triangles + i->nonfinite_dropped;
    double worst = 0.0, diag = diagonal(i);
    for (int k = 0; k < 3; k++) {
        worst = fmax(worst, fabs((double)s->bounds_min[k] - i->bounds_min[k]));
        worst = fmax(worst, fabs((double)s->bounds_max[k] - i->bounds_max[k]));
    }
    if (s->triangles_in != read)
        snprintf(why, cap, "it was made from %llu triangles, the mesh has %llu",
                 (unsigned long long)s->triangles_in, (unsigned long long)read);
    else if (memcmp(s->origin, i->origin, sizeof s->origin))
        snprintf(why, cap, "its origin (%.17g %.17g %.17g) is not the mesh's (%.17g %.17g %.17g)",
                 s->origin[0], s->origin[1], s->origin[2], i->origin[0], i->origin[1],
                 i->origin[2]);
    else if (s->parts && !(worst <= 1e-3 * diag))
        snprintf(why, cap, "its bounds differ from the mesh's by %g (more than 1/1000 of the "
                 "diagonal %g)", worst, diag);
}

oit_status oit_bench_match(const oit_mesh *mesh, oit_partfile *pf, char *why, size_t cap,
                           oit_error *err)
{
    oit_partfile_summary s;
    oit_partfile_get_summary(pf, &s);
    why[0] = 0;
    header_mismatch(&mesh->info, &s, why, cap);
    if (why[0])
        return OIT_OK;
    double a[4] = {0}, b[4] = {0}, diag = diagonal(&mesh->info), off = 0.0;
    add_moments(mesh->tris, mesh->count, a);
    oit_status st = part_moments(pf, b, err);
    if (st != OIT_OK)
        return st;
    for (int k = 0; k < 3 && a[0] > 0.0 && b[0] > 0.0; k++)
        off = fmax(off, fabs(a[1 + k] / a[0] - b[1 + k] / b[0]));
    if (!(fabs(a[0] - b[0]) <= 1e-4 * a[0]))
        snprintf(why, cap, "its surface area %.9g is not the mesh's %.9g (as many triangles "
                 "in the same box, but another model)", b[0], a[0]);
    else if (!(off <= 1e-4 * diag))
        snprintf(why, cap, "its area-weighted centroid lies %g from the mesh's (as many "
                 "triangles, the same box and area, but another model)", off);
    return OIT_OK;
}
