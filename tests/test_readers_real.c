/* Reads the real meshes data_scripts/fetch_meshes.sh puts in $OIT_MESH_CACHE
 * and prints their figures. Asserts the known triangle count of bunny00.off
 * and finite, non-empty bounds for every file present; skips (77) when none
 * is there. */
#include "oit/mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

static const struct {
    const char *name;
    long long triangles; /* -1: not pinned */
} files[] = {
    {"bunny00.off", 75408},  {"armadillo.off", -1},      {"refined_elephant.off", -1},
    {"ChineseDragon-10kv.off", -1}, {"fandisk.off", -1}, {"turbine.off", -1},
    {"Wuson.ply", -1},       {"spider.obj", -1},         {"Spider_binary.stl", -1},
    {"head.stl", -1},        {"propeller.stl", -1},
};

static oit_status discard(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return OIT_OK;
}

static int bounds_ok(const oit_mesh_info *info)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(info->bounds_min[k]) || !isfinite(info->bounds_max[k]) ||
            info->bounds_min[k] > info->bounds_max[k])
            return 0;
    return info->triangles > 0;
}

int main(void)
{
    const char *cache = getenv("OIT_MESH_CACHE");
    int present = 0, failures = 0;
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", cache ? cache : ".", files[i].name);
        if (access(path, R_OK) != 0) {
            printf("%-24s absent\n", files[i].name);
            continue;
        }
        present++;
        oit_mesh_info info;
        oit_error err = {0};
        clock_t t0 = clock();
        oit_status s = oit_mesh_read(path, NULL, discard, NULL, &info, &err);
        double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
        if (s != OIT_OK) {
            printf("FAIL %-19s %s\n", files[i].name, err.message);
            failures++;
            continue;
        }
        printf("%-24s %8llu triangles %7llu faces %7llu vertices %llu non-finite attr=%u "
               "[%g %g %g]..[%g %g %g] %.2f s\n",
               files[i].name, (unsigned long long)info.triangles,
               (unsigned long long)info.faces_in, (unsigned long long)info.vertices_in,
               (unsigned long long)info.nonfinite_dropped, info.attributes, info.bounds_min[0],
               info.bounds_min[1], info.bounds_min[2], info.bounds_max[0], info.bounds_max[1],
               info.bounds_max[2], secs);
        if (!bounds_ok(&info)) {
            printf("FAIL %s: empty or non-finite bounds\n", files[i].name);
            failures++;
        }
        if (files[i].triangles >= 0 && (long long)info.triangles != files[i].triangles) {
            printf("FAIL %s: %llu triangles, expected %lld\n", files[i].name,
                   (unsigned long long)info.triangles, files[i].triangles);
            failures++;
        }
    }
    if (!present) {
        printf("skip: no real meshes under OIT_MESH_CACHE=%s (run data_scripts/fetch_meshes.sh)\n",
               cache ? cache : "(unset)");
        return 77;
    }
    printf("%d file(s) read, %d failure(s)\n", present, failures);
    return failures ? 1 : 0;
}
