/* Voxel occupancy (occupancy.h). */
#include "prepare/scenes/occupancy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static size_t word_count(const oit_occupancy *o)
{
    return ((size_t)o->dims[0] * (size_t)o->dims[1] * (size_t)o->dims[2] + 63) / 64;
}

oit_status oit_occupancy_init(oit_occupancy *o, oit_v3 lo, oit_v3 hi, float voxel)
{
    memset(o, 0, sizeof *o);
    o->origin = lo;
    o->voxel = voxel;
    const float ext[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
    for (int k = 0; k < 3; k++)
        o->dims[k] = (int)ceilf(ext[k] / voxel) + 1;
    o->bits = calloc(word_count(o), sizeof *o->bits);
    return o->bits ? OIT_OK : OIT_ERR_NOMEM;
}

void oit_occupancy_free(oit_occupancy *o)
{
    free(o->bits);
    memset(o, 0, sizeof *o);
}

void oit_occupancy_reset(oit_occupancy *o, oit_v3 origin)
{
    o->origin = origin;
    memset(o->bits, 0, word_count(o) * sizeof *o->bits);
}

/* The voxel range a box touches on each axis, clipped to the grid; 0 when
 * the box misses the grid. */
static int voxel_range(const oit_occupancy *o, oit_v3 lo, oit_v3 hi, float grow, int a[3],
                       int b[3])
{
    const float l[3] = {lo.x - o->origin.x, lo.y - o->origin.y, lo.z - o->origin.z};
    const float h[3] = {hi.x - o->origin.x, hi.y - o->origin.y, hi.z - o->origin.z};
    for (int k = 0; k < 3; k++) {
        float x0 = floorf((l[k] - grow) / o->voxel), x1 = floorf((h[k] + grow) / o->voxel);
        if (x1 < 0 || x0 >= (float)o->dims[k])
            return 0;
        a[k] = x0 < 0 ? 0 : (int)x0;
        b[k] = x1 >= (float)o->dims[k] ? o->dims[k] - 1 : (int)x1;
    }
    return 1;
}

static size_t voxel_index(const oit_occupancy *o, int x, int y, int z)
{
    return ((size_t)z * (size_t)o->dims[1] + (size_t)y) * (size_t)o->dims[0] + (size_t)x;
}

int oit_occupancy_clear(const oit_occupancy *o, oit_v3 lo, oit_v3 hi, float clearance)
{
    int a[3], b[3];
    if (!voxel_range(o, lo, hi, clearance, a, b))
        return 1;
    for (int z = a[2]; z <= b[2]; z++)
        for (int y = a[1]; y <= b[1]; y++)
            for (int x = a[0]; x <= b[0]; x++) {
                size_t i = voxel_index(o, x, y, z);
                if (o->bits[i / 64] >> (i % 64) & 1)
                    return 0;
            }
    return 1;
}

void oit_occupancy_mark(oit_occupancy *o, oit_v3 lo, oit_v3 hi)
{
    int a[3], b[3];
    if (!voxel_range(o, lo, hi, 0, a, b))
        return;
    for (int z = a[2]; z <= b[2]; z++)
        for (int y = a[1]; y <= b[1]; y++)
            for (int x = a[0]; x <= b[0]; x++) {
                size_t i = voxel_index(o, x, y, z);
                o->bits[i / 64] |= 1ull << (i % 64);
            }
}
