/* oit_meshinfo FILE...: reads each file through oit_mesh_read and prints
 * its figures, one "key value" per line, for data_scripts/fetch_meshes.sh
 * and for people checking a model before converting it. */
#include "oit/mesh.h"

#include <stdio.h>
#include <string.h>

#include "tools/common/exit_code.h"

static oit_status discard(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return OIT_OK;
}

static int usage(FILE *out, int code)
{
    fprintf(out, "usage: oit_meshinfo FILE...\n"
                 "Reads each mesh (as oitprep reads) and prints triangles,\n"
                 "faces, vertices, dropped non-finite triangles, attributes and bounds.\n");
    return code;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return usage(stderr, 2);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))
        return usage(stdout, 0);
    int code = 0;
    for (int i = 1; i < argc; i++) {
        oit_mesh_info m;
        oit_error err = {0};
        oit_status s = oit_mesh_read(argv[i], NULL, discard, NULL, &m, &err);
        if (s != OIT_OK) {
            fprintf(stderr, "oit_meshinfo: %s\n", err.message);
            code = oit_tool_exit_code(s);
            continue;
        }
        printf("file %s\ntriangles %llu\nfaces %llu\nvertices %llu\nnonfinite_dropped %llu\n"
               "attributes%s%s\nbounds %g %g %g  %g %g %g\n",
               argv[i], (unsigned long long)m.triangles, (unsigned long long)m.faces_in,
               (unsigned long long)m.vertices_in, (unsigned long long)m.nonfinite_dropped,
               m.attributes & OIT_ATTR_COLOUR ? " color" : "", m.attributes & OIT_ATTR_ALPHA ? " alpha" : "",
               m.bounds_min[0], m.bounds_min[1], m.bounds_min[2], m.bounds_max[0], m.bounds_max[1],
               m.bounds_max[2]);
    }
    return code;
}
