/* oitprep: converts models to part files (issue 4) and inspects part files.
 *
 *   oitprep info FILE [--json]   validate FILE and print its summary
 *   oitprep INPUT -o OUT         conversion: not built yet
 *
 * Exit codes follow DESIGN.md: 0 ok, 1 I/O, 2 usage, 3 bad input.
 */
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "oit/status.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fputs("usage: oitprep info FILE [--json]\n"
          "       oitprep INPUT -o OUT.oitp\n"
          "\n"
          "  info FILE     validate a part file completely (header, checksums, every record\n"
          "                and index) and print its counts; --json prints one JSON object\n"
          "                (triangles, parts, pieces, slabs, cells, subgrid_depth, bytes,\n"
          "                layer_bound, attributes, version, K, ...)\n"
          "  INPUT -o OUT  convert a mesh into a part file: NOT BUILT YET (issue 4); it\n"
          "                exits 1 without writing anything\n"
          "  -h, --help    this text\n"
          "\n"
          "exit: 0 ok, 1 runtime or I/O failure, 2 usage error, 3 bad input file\n",
          f);
}

/* Writes s as a JSON string body; control bytes become \u escapes. */
static void json_string(const char *s)
{
    putchar('"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\')
            printf("\\%c", *p);
        else if (*p < 0x20)
            printf("\\u%04x", *p);
        else
            putchar(*p);
    }
    putchar('"');
}

static void print_json(const oit_partfile *pf, const oit_partfile_summary *s)
{
    printf("{\"file\": ");
    json_string(oit_partfile_name(pf));
    printf(", \"version\": %u, \"K\": %u, \"triangles\": %llu, \"triangles_in\": %llu, "
           "\"triangles_dropped\": %llu, \"triangles_split\": %llu, \"parts\": %llu, "
           "\"pieces\": %llu, \"slabs\": %llu, \"cells\": %llu, \"subgrids\": %llu, "
           "\"subgrid_depth\": %u, \"layer_bound\": %u, \"parts_index16\": %llu, "
           "\"parts_index32\": %llu, \"bytes\": %llu, \"data_bytes\": %llu, "
           "\"part_align\": %u, \"attributes\": [",
           s->version, s->K, (unsigned long long)s->triangles,
           (unsigned long long)s->triangles_in, (unsigned long long)s->triangles_dropped,
           (unsigned long long)s->triangles_split, (unsigned long long)s->parts,
           (unsigned long long)s->pieces, (unsigned long long)s->slabs,
           (unsigned long long)s->cells, (unsigned long long)s->subgrids, s->subgrid_depth,
           s->layer_bound, (unsigned long long)s->parts_index16,
           (unsigned long long)s->parts_index32, (unsigned long long)s->bytes,
           (unsigned long long)s->data_bytes, s->part_align);
    const char *sep = "";
    if (s->attributes & OIT_ATTR_COLOR) {
        printf("\"color\"");
        sep = ", ";
    }
    if (s->attributes & OIT_ATTR_ALPHA)
        printf("%s\"alpha\"", sep);
    printf("], \"bounds_min\": [%.9g, %.9g, %.9g], \"bounds_max\": [%.9g, %.9g, %.9g], "
           "\"source\": ",
           s->bounds_min[0], s->bounds_min[1], s->bounds_min[2], s->bounds_max[0],
           s->bounds_max[1], s->bounds_max[2]);
    json_string(oit_partfile_source_name(pf));
    printf("}\n");
}

static void print_human(const oit_partfile *pf, const oit_partfile_summary *s)
{
    const char *attr = s->attributes == (OIT_ATTR_COLOR | OIT_ATTR_ALPHA) ? "colour, alpha"
                       : s->attributes & OIT_ATTR_COLOR                  ? "colour"
                       : s->attributes & OIT_ATTR_ALPHA                  ? "alpha"
                                                                         : "positions only";
    printf("%s: part file version %u, K %u, source \"%s\"\n", oit_partfile_name(pf), s->version,
           s->K, oit_partfile_source_name(pf));
    printf("  triangles  %llu (read %llu, dropped %llu, added by splitting %llu)\n",
           (unsigned long long)s->triangles, (unsigned long long)s->triangles_in,
           (unsigned long long)s->triangles_dropped, (unsigned long long)s->triangles_split);
    printf("  parts      %llu (16-bit indices %llu, 32-bit %llu), layer bound %u\n",
           (unsigned long long)s->parts, (unsigned long long)s->parts_index16,
           (unsigned long long)s->parts_index32, s->layer_bound);
    printf("  pieces     %llu\n", (unsigned long long)s->pieces);
    printf("  cells      %llu (subgrids %llu, subgrid depth %u), slabs %llu\n",
           (unsigned long long)s->cells, (unsigned long long)s->subgrids, s->subgrid_depth,
           (unsigned long long)s->slabs);
    printf("  attributes %s\n", attr);
    printf("  bytes      %llu (part data %llu, parts aligned to %u)\n",
           (unsigned long long)s->bytes, (unsigned long long)s->data_bytes, s->part_align);
    printf("  bounds     (%g %g %g) .. (%g %g %g)\n", s->bounds_min[0], s->bounds_min[1],
           s->bounds_min[2], s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]);
}

static int cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (argv[i][0] == '-' || path) {
            fprintf(stderr, "oitprep info: unexpected argument '%s'\n", argv[i]);
            return 2;
        } else
            path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "oitprep info: no FILE given (see oitprep --help)\n");
        return 2;
    }
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_status st = oit_partfile_open(path, NULL, &pf, &err);
    if (st) {
        fprintf(stderr, "oitprep: %s\n", err.message);
        return oit_status_exit_code(st);
    }
    oit_partfile_summary s;
    oit_partfile_get_summary(pf, &s);
    if (json)
        print_json(pf, &s);
    else
        print_human(pf, &s);
    oit_partfile_close(pf);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "info") == 0)
        return cmd_info(argc, argv);
    fprintf(stderr, "oitprep: conversion is not built yet (issue 4)\n");
    return 1;
}
