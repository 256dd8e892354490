/* Every real mesh data_scripts/fetch_meshes.sh provides, read through
 * oit_mesh_read: prints triangles, bounds and read time. Asserts that each
 * file yields its known triangle count (bunny00.off: 75408; the others as
 * the packages ship them) with finite, ordered bounds, and that the Draco-compressed glTF of 2CylinderEngine
 * decodes to the same bounds (1e-3 of the extent) as the plain GLB, and to
 * as many triangles as the GLB has triangles with three distinct corners:
 * Draco's encoder dropped the GLB's 11160 degenerate ones (quantization
 * then collapses a few more, so the Draco side counts all it delivers).
 * Skips (77) when the cache is incomplete. */
#include "oit/mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

static const char *const files[] = {
    "bunny00.off", "armadillo.off", "refined_elephant.off", "ChineseDragon-10kv.off",
    "fandisk.off", "turbine.off", "2CylinderEngine.glb", "2CylinderEngine-draco.gltf",
    "Wuson.ply", "spider.obj", "Spider_binary.stl", "head.stl", "propeller.stl",
};
/* Triangles each file must give (faces fan-triangulated). */
static const unsigned long long expected[] = {
    75408, 52000, 88928, 19994, 12946, 18460, 121496, 110336, 3732, 1368, 1368, 117694, 7375,
};
enum { NFILES = sizeof files / sizeof files[0], GLB = 6, DRACO = 7 };
_Static_assert(sizeof expected / sizeof expected[0] == NFILES, "one expected count per file");

static int same_pos(const oit_vertex *a, const oit_vertex *b)
{
    return a->pos[0] == b->pos[0] && a->pos[1] == b->pos[1] && a->pos[2] == b->pos[2];
}

/* Counts triangles whose three corners are distinct points: Draco's encoder
 * drops degenerate faces, so only these can be compared across encodings. */
static oit_status count_proper(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    unsigned long long *proper = user;
    for (size_t i = 0; i < n; i++)
        *proper += !same_pos(&t[i].v[0], &t[i].v[1]) && !same_pos(&t[i].v[1], &t[i].v[2]) &&
                   !same_pos(&t[i].v[0], &t[i].v[2]);
    return OIT_OK;
}

static int bounds_ok(const oit_mesh_info *m)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(m->bounds_min[k]) || !isfinite(m->bounds_max[k]) ||
            m->bounds_min[k] > m->bounds_max[k])
            return 0;
    return 1;
}

static int same_bounds(const oit_mesh_info *a, const oit_mesh_info *b)
{
    double extent = 0;
    for (int k = 0; k < 3; k++)
        extent = fmax(extent, a->bounds_max[k] - a->bounds_min[k]);
    for (int k = 0; k < 3; k++) {
        double d = fmax(fabs(a->bounds_min[k] - b->bounds_min[k]), fabs(a->bounds_max[k] - b->bounds_max[k]));
        printf("  axis %d: glb %.4f..%.4f draco %.4f..%.4f (|diff| %.2e of extent %.1f)\n", k,
               a->bounds_min[k], a->bounds_max[k], b->bounds_min[k], b->bounds_max[k], d / extent, extent);
        if (!(d <= 1e-3 * extent))
            return 0;
    }
    return 1;
}

int main(void)
{
    const char *cache = getenv("OIT_MESH_CACHE");
    char path[4096];
    for (int i = 0; cache && i < NFILES; i++) {
        snprintf(path, sizeof path, "%s/%s", cache, files[i]);
        if (access(path, R_OK) != 0) {
            printf("skip: %s missing (run data_scripts/fetch_meshes.sh %s)\n", path, cache);
            return 77;
        }
    }
    if (!cache) {
        printf("skip: OIT_MESH_CACHE is not set\n");
        return 77;
    }
    oit_mesh_info info[NFILES];
    unsigned long long proper[NFILES] = {0};
    int failures = 0;
    printf("%-28s %10s %10s %10s %8s  bounds\n", "file", "triangles", "distinct", "nonfinite", "ms");
    for (int i = 0; i < NFILES; i++) {
        snprintf(path, sizeof path, "%s/%s", cache, files[i]);
        oit_error err = {0};
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        oit_status s = oit_mesh_read(path, NULL, count_proper, &proper[i], &info[i], &err);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double ms = (t1.tv_sec - t0.tv_sec) * 1e3 + (t1.tv_nsec - t0.tv_nsec) / 1e6;
        if (s != OIT_OK) {
            printf("FAIL %s: %s\n", files[i], err.message);
            failures++;
            info[i].triangles = 0;
            continue;
        }
        const oit_mesh_info *m = &info[i];
        printf("%-28s %10llu %10llu %10llu %8.1f  %g %g %g  %g %g %g\n", files[i],
               (unsigned long long)m->triangles, proper[i], (unsigned long long)m->nonfinite_dropped, ms, m->bounds_min[0], m->bounds_min[1],
               m->bounds_min[2], m->bounds_max[0], m->bounds_max[1], m->bounds_max[2]);
        if (m->triangles != expected[i] || !bounds_ok(m)) {
            printf("FAIL %s: %llu triangles (want %llu) or bad bounds\n", files[i],
                   (unsigned long long)m->triangles, expected[i]);
            failures++;
        }
    }
    printf("2CylinderEngine: glb %llu triangles (%llu with distinct corners), draco %llu (%llu)\n",
           (unsigned long long)info[GLB].triangles, proper[GLB], (unsigned long long)info[DRACO].triangles,
           proper[DRACO]);
    if (info[DRACO].triangles != proper[GLB] || proper[GLB] == 0 ||
        !same_bounds(&info[GLB], &info[DRACO])) {
        printf("FAIL 2CylinderEngine: the Draco glTF does not match the GLB\n");
        failures++;
    }
    printf("%s (%d failures)\n", failures ? "FAILED" : "ok", failures);
    return failures ? 1 : 0;
}
