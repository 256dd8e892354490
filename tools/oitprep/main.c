/* oitprep: converts models to part files and inspects and verifies them.
 *
 *   oitprep info FILE [--json]          validate FILE and print its summary
 *   oitprep verify FILE [options]       check layer bounds and visibility order
 *   oitprep parts FILE -o OUT.ply       the parts as a coloured PLY to look at
 *   oitprep INPUT -o OUT [options]      convert a mesh (prepare/convert/convert.h)
 *
 * Exit codes follow DESIGN.md: 0 ok, 1 I/O, 2 usage, 3 bad input.
 */
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "oit/status.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/args.h"
#include "base/json.h"
#include "tools/common/exit_code.h"
#include "tools/common/flag_spelling.h"
#include "tools/common/mesh_formats.h"
#include "tools/common/paths.h"
#include "tools/common/progress_mode.h"
#include "tools/common/signals.h"
#include "prepare/convert/convert.h"
#include "prepare/convert/progress.h"
#include "prepare/convert/decode_rate.h"
#include "prepare/convert/stats_json.h"
#include "prepare/convert/export_parts.h"
#include "prepare/convert/verify.h"

/* The conversion's errors name its options' fields; oitprep's user gave
 * flags (flag_spelling.h). */
static void print_error(oit_error *err)
{
    oit_flags_spell_error(err);
    fprintf(stderr, "oitprep: %s\n", err->message);
}

static void usage(FILE *f)
{
    fputs("usage: oitprep info FILE [--json] [--decode]\n"
          "       oitprep verify FILE [--directions M] [--viewpoints V] [--chunk-triangles T]\n"
          "       oitprep parts FILE -o OUT.ply [--colour part|kind] [--alpha A]\n"
          "       oitprep INPUT -o OUT.oitp [--max-layers K] [--memory BYTES] [--threads N]\n"
          "               [--stats FILE.json] [--grid N] [--max-piece-triangles T]\n"
          "               [--manage grid|kd-parts|kd-facets] [--slabs all|separating|none]\n"
          "               [--scheme fast|guaranteed] [--part-triangles T] [--deflection D]\n"
          "\n"
          "  info FILE     validate a part file completely (header, checksums, every record\n"
          "                and index) and print its counts; --json prints one JSON object\n"
          "                (triangles, parts, pieces, slabs, cut_slabs, cells,\n"
          "                subgrid_depth, bytes, layer_bound, attributes, version, K, ...);\n"
          "                --decode also times decoding every part on one thread (best of\n"
          "                3 passes), alone and with the first use's checks, in MB/s of\n"
          "                decoded output\n"
          "  verify FILE   cast rays through every part (Embree): parallel bundles from\n"
          "                --directions M (0..100000, default 64) and rays from\n"
          "                --viewpoints V (0..100000, default 16, the centre among them;\n"
          "                M or V above 0);\n"
          "                fails (exit 1) when a part yields more\n"
          "                hits than its layer bound, parts are met out of the order\n"
          "                partfile/order.h computes for the ray's origin, or a slab's\n"
          "                parts have a vertex on the wrong side of its planes (exact),\n"
          "                or a source triangle the converter kept (not degenerate, finite)\n"
          "                is the source index of no part triangle (a triangle lost).\n"
          "                A file of measured bounds (--scheme fast) guarantees none: its\n"
          "                hits over a part's bound are reported, not failed; order and\n"
          "                slab violations and lost triangles fail it as for any file.\n"
          "                The parts go into Embree scenes of at most --chunk-triangles T\n"
          "                triangles\n"
          "                (1..4G, default 4M, suffix K/M/G), built and cast one at a time:\n"
          "                memory holds one scene (about 100 bytes a triangle)\n"
          "  parts FILE    write FILE's parts as a PLY to look at (render it with oitstream):\n"
          "                --colour part (default) gives each part a hue of its own; kind\n"
          "                paints parts of axis splits grey, of separating slabs blue, of\n"
          "                cutting planes orange, wide parts (guaranteed scheme) red.\n"
          "                --alpha A (1..255) for every triangle, else the file's alpha\n"
          "  INPUT -o OUT  convert a mesh (formats below) into a part file,\n"
          "                out of core: the model is binned into a grid of top cells (--grid\n"
          "                N along the longest axis, 1..1024; default: cells of at least\n"
          "                256K triangles or 8 parts' worth, doubled where that makes\n"
          "                fewer cells, for the fast scheme, ~64K triangles a cell for\n"
          "                the guaranteed one; cells are rounded to a power-of-two size)\n"
          "                and each cell is subdivided into parts by a kd-tree, so that\n"
          "                the parts are exactly ordered per view. Two schemes (--scheme):\n"
          "                fast (default), built for streaming speed: a kd node stops\n"
          "                splitting when it holds at most --part-triangles T triangles\n"
          "                (1..16M, default 131072); triangles are clipped only where a\n"
          "                tree plane crosses them and keep their source order within a\n"
          "                part (depth ties resolve as in the source mesh). A part's layer\n"
          "                bound is MEASURED, not guaranteed: the most triangles one line\n"
          "                crosses among 64x64 parallel lines in each of 13 fixed\n"
          "                directions (prepare/partition/layers_measured.h); a part measured above\n"
          "                64 is split further (up to 12 levels), else stored as 64 and\n"
          "                counted (clamped_parts in --stats). oitstream's default\n"
          "                captures (first-k and counted packs) need no bound; --pack\n"
          "                disjoint|budget count any excess as overflow. The file is\n"
          "                flagged as of measured bounds.\n"
          "                guaranteed: Wang & Xie's scheme, for its comparisons: convex\n"
          "                pieces (--max-piece-triangles T stops one at T triangles,\n"
          "                1..1073741824, default 4096) grouped into parts of at most K\n"
          "                layers (1 per planar piece, 2 per other); a node of at most 2K\n"
          "                layers that no axis plane splits without cutting may instead\n"
          "                become two parts on either side of a slab: a separating one (a\n"
          "                gap, any normal, nothing clipped), else a cutting plane (one of\n"
          "                49 integer normals; it clips, seams exactly on the plane) when\n"
          "                it crosses fewer triangles than the axis split or spares that\n"
          "                split's further splits. --slabs all (default), separating (no\n"
          "                cutting planes) or none (axis splits only): cut_slabs in\n"
          "                --stats. Where more than K layers meet at one vertex no box\n"
          "                separates them: that node becomes a wide part (bound up to 64,\n"
          "                streamed alone over smaller tiles; wide_parts in --stats); a\n"
          "                node of more than 64 layers is refused (exit 3). --manage\n"
          "                (Wang & Xie, Table 1): grid (default: the above); kd-parts:\n"
          "                one kd-tree over the whole model's convex pieces, one part a\n"
          "                leaf (--grid 1: one top cell an axis, or two where the bounds\n"
          "                straddle a power of two; in memory); kd-facets: one kd-tree\n"
          "                over single facets, leaves of at most K facets (no convex\n"
          "                pieces). --max-piece-triangles, --slabs and --manage other\n"
          "                than grid select this scheme when --scheme is not given, and\n"
          "                are usage errors with --scheme fast.\n"
          "                Both: --max-layers K (even, 2..64, default 8: the capture's\n"
          "                slots a pixel; above 16 the streamer captures parts over tiles),\n"
          "                --memory BYTES for the binning (>= 64K, suffix K/M/G, default\n"
          "                2G; beyond it bins spill to OUT.spill), --threads N (1..1024,\n"
          "                default: all cores), --stats FILE.json figures. Clipping at kd\n"
          "                planes adds triangles (split_added in --stats). The output is\n"
          "                byte-identical for any --threads and --memory. Progress\n"
          "                goes to stderr: a bar per stage on a terminal, else a line\n"
          "                every 5 s (OIT_PROGRESS_PERIOD=SECONDS sets the period).\n"
          "                STEP/IGES: --deflection D (> 0, in the file's units) bounds\n"
          "                the distance of the triangles from the surfaces; unset it is\n"
          "                a thousandth of the bounding box's diagonal (deflection in\n"
          "                --stats gives the one used).\n"
          "  -h, --help    this text\n"
          "\n"
          OIT_TOOL_MESH_FORMATS_HELP
          "\n"
          "exit: 0 ok, 1 runtime or I/O failure, 2 usage error, 3 bad input file\n",
          f);
}

static void put_triple(oit_json *w, const char *key, const double v[3], int digits)
{
    oit_json_begin_array(w, key, OIT_JSON_INLINE);
    for (int k = 0; k < 3; k++)
        oit_json_general(w, NULL, v[k], digits);
    oit_json_end(w);
}

/* --json: the summary as one JSON object on stdout. */
static oit_status print_json(const oit_partfile *pf, const oit_partfile_summary *s,
                             oit_error *err)
{
    oit_json w;
    oit_json_init(&w, stdout, "standard output");
    const oit_json_uint_member counts[] = {
        {"version", s->version}, {"K", s->K}, {"triangles", s->triangles},
        {"triangles_in", s->triangles_in}, {"triangles_dropped", s->triangles_dropped},
        {"triangles_split", s->triangles_split}, {"parts", s->parts}, {"pieces", s->pieces},
        {"slabs", s->slabs}, {"cut_slabs", s->cut_slabs}, {"cells", s->cells},
        {"subgrids", s->subgrids}, {"subgrid_depth", s->subgrid_depth},
        {"layer_bound", s->layer_bound}, {"parts_index16", s->parts_index16},
        {"parts_index32", s->parts_index32}, {"bytes", s->bytes}, {"data_bytes", s->data_bytes},
        {"part_align", s->part_align}};
    oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
    oit_json_string(&w, "file", oit_partfile_name(pf));
    OIT_JSON_UINTS(&w, counts);
    oit_json_bool(&w, "measured_bounds", s->measured_bounds);
    oit_json_begin_array(&w, "attributes", OIT_JSON_INLINE);
    if (s->attributes & OIT_ATTR_COLOUR)
        oit_json_string(&w, NULL, "color");
    if (s->attributes & OIT_ATTR_ALPHA)
        oit_json_string(&w, NULL, "alpha");
    if (s->attributes & OIT_ATTR_OPAQUE)
        oit_json_string(&w, NULL, "opaque");
    oit_json_end(&w);
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = s->bounds_min[k];
        hi[k] = s->bounds_max[k];
    }
    /* the bounds as the floats they are (%.9g), the origin as the double */
    put_triple(&w, "bounds_min", lo, 9);
    put_triple(&w, "bounds_max", hi, 9);
    put_triple(&w, "origin", s->origin, 17);
    oit_json_string(&w, "source", oit_partfile_source_name(pf));
    oit_json_end(&w);
    return oit_json_flush(&w, err);
}

static void print_human(const oit_partfile *pf, const oit_partfile_summary *s)
{
    const char *attr = s->attributes & OIT_ATTR_OPAQUE ? "colour, alpha, opaque triangles"
                       : s->attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA) ? "colour, alpha"
                       : s->attributes & OIT_ATTR_COLOUR                  ? "colour"
                       : s->attributes & OIT_ATTR_ALPHA                  ? "alpha"
                                                                         : "positions only";
    printf("%s: part file version %u, K %u, source \"%s\"\n", oit_partfile_name(pf), s->version,
           s->K, oit_partfile_source_name(pf));
    printf("  triangles  %llu (read %llu, dropped %llu, added by splitting %llu)\n",
           (unsigned long long)s->triangles, (unsigned long long)s->triangles_in,
           (unsigned long long)s->triangles_dropped, (unsigned long long)s->triangles_split);
    printf("  parts      %llu (16-bit indices %llu, 32-bit %llu), layer bound %u%s\n",
           (unsigned long long)s->parts, (unsigned long long)s->parts_index16,
           (unsigned long long)s->parts_index32, s->layer_bound,
           s->measured_bounds ? " (measured, not guaranteed)" : "");
    printf("  pieces     %llu\n", (unsigned long long)s->pieces);
    printf("  cells      %llu (subgrids %llu, subgrid depth %u), slabs %llu (%llu cutting)\n",
           (unsigned long long)s->cells, (unsigned long long)s->subgrids, s->subgrid_depth,
           (unsigned long long)s->slabs, (unsigned long long)s->cut_slabs);
    printf("  attributes %s\n", attr);
    printf("  bytes      %llu (part data %llu, parts aligned to %u)\n",
           (unsigned long long)s->bytes, (unsigned long long)s->data_bytes, s->part_align);
    printf("  bounds     (%g %g %g) .. (%g %g %g)", s->bounds_min[0], s->bounds_min[1],
           s->bounds_min[2], s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]);
    if (s->origin[0] || s->origin[1] || s->origin[2])
        printf(" relative to origin (%.17g %.17g %.17g)", s->origin[0], s->origin[1], s->origin[2]);
    printf("\n");
}

static int print_decode_rate(const char *path)
{
    oit_decode_rate r;
    oit_error err = {0};
    oit_status st = oit_measure_decode(path, 3, &r, &err);
    if (st) {
        print_error(&err);
        return oit_tool_exit_code(st);
    }
    double mb = (double)r.decoded_bytes / 1e6;
    printf("  decode     %llu parts, %llu stored bytes -> %llu decoded, one thread: %.1f ms "
           "(%.0f MB/s), with the checks %.1f ms (%.0f MB/s)\n",
           (unsigned long long)r.parts, (unsigned long long)r.stored_bytes,
           (unsigned long long)r.decoded_bytes, 1e3 * r.decode_s,
           r.decode_s > 0 ? mb / r.decode_s : 0.0, 1e3 * r.checked_s,
           r.checked_s > 0 ? mb / r.checked_s : 0.0);
    return 0;
}

/* A subcommand's FILE: arg, unless it is an option or a FILE came before
 * (then 2, said on stderr). */
static int file_arg(const char *cmd, const char *arg, const char **path)
{
    if (arg[0] == '-' || *path) {
        fprintf(stderr, "oitprep %s: unexpected argument '%s'\n", cmd, arg);
        return 2;
    }
    *path = arg;
    return 0;
}

/* 2, said on stderr, when the subcommand got no FILE; else 0. */
static int file_given(const char *cmd, const char *path)
{
    if (path)
        return 0;
    fprintf(stderr, "oitprep %s: no FILE given (see oitprep --help)\n", cmd);
    return 2;
}

static int cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0, decode = 0;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (strcmp(argv[i], "--decode") == 0)
            decode = 1;
        else if (file_arg("info", argv[i], &path))
            return 2;
    }
    if (file_given("info", path))
        return 2;
    if (json && decode) {
        fprintf(stderr, "oitprep info: --decode prints a line of text, not JSON: give it "
                "without --json\n");
        return 2;
    }
    oit_partfile *pf = NULL;
    oit_error err = {0};
    oit_status st = oit_partfile_open(path, NULL, &pf, &err);
    if (st) {
        print_error(&err);
        return oit_tool_exit_code(st);
    }
    oit_partfile_summary s;
    oit_partfile_get_summary(pf, &s);
    if (json)
        st = print_json(pf, &s, &err);
    else
        print_human(pf, &s);
    oit_partfile_close(pf);
    if (st) {
        print_error(&err);
        return oit_tool_exit_code(st);
    }
    return decode ? print_decode_rate(path) : 0;
}

/* The number after argv[*i], in lo..hi; with suffixes, a byte count with
 * an optional K/M/G (powers of 1024). -1 with the message otherwise. */
static int option_value(int argc, char **argv, int *i, const char *name, int suffixes,
                        uint64_t lo, uint64_t hi, uint64_t *out)
{
    const char *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!v || (suffixes ? oit_parse_bytes(v, lo, hi, out) : oit_parse_u64(v, lo, hi, out))) {
        fprintf(stderr, "oitprep: %s needs a number in %llu..%llu\n", name,
                (unsigned long long)lo, (unsigned long long)hi);
        return -1;
    }
    (*i)++;
    return 0;
}

/* The index of the word after argv[*i] among names (NULL-terminated), or
 * -1 with a message listing `want`. */
static int option_choice(int argc, char **argv, int *i, const char *name,
                         const char *const *names, const char *want)
{
    const char *m = *i + 1 < argc ? argv[++*i] : "";
    for (int k = 0; names[k]; k++)
        if (strcmp(m, names[k]) == 0)
            return k;
    fprintf(stderr, "oitprep: %s '%s': want %s\n", name, m, want);
    return -1;
}

/* Before any work: neither output may be the input (or each other), and
 * both must be creatable, so a typo never costs the model or the run. */
static oit_status check_outputs(const char *input, const char *out, const char *stats,
                                oit_error *err)
{
    const char *ins[2] = {input, out};
    oit_status s = oit_output_check(out, "-o", ins, 1, err);
    if (!s && stats && strcmp(stats, out) == 0)
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "%s: --stats and -o name the same file", stats);
    if (!s && stats)
        s = oit_output_check(stats, "--stats", ins, 2, err);
    return s;
}

static int cmd_convert(int argc, char **argv)
{
    oit_convert_options o;
    oit_convert_options_init(&o);
    oit_tool_progress tp = oit_tool_progress_get("oitprep");
    o.progress = tp.bar ? OIT_PROGRESS_BAR : OIT_PROGRESS_LINES;
    o.progress_period_s = tp.period_s;
    const char *stats = NULL;
    /* Options only Wang & Xie's scheme has: without --scheme they select it,
     * so its comparisons keep their command lines. */
    const char *guaranteed_only = NULL;
    int scheme_given = 0;
    for (int i = 1; i < argc; i++) {
        uint64_t v;
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 && i + 1 < argc)
            o.output = argv[++i];
        else if (strcmp(a, "--stats") == 0 && i + 1 < argc)
            stats = argv[++i];
        else if (strcmp(a, "--max-layers") == 0) {
            /* 64: the widest part the streamer captures (over tiles) */
            if (i + 1 >= argc || oit_parse_u64(argv[i + 1], 2, 64, &v) || v % 2) {
                fprintf(stderr, "oitprep: --max-layers '%s': must be even, 2..64\n",
                        i + 1 < argc ? argv[i + 1] : "");
                return 2;
            }
            i++;
            o.K = (uint32_t)v;
        } else if (strcmp(a, "--memory") == 0) {
            if (option_value(argc, argv, &i, a, 1, 1 << 16, SIZE_MAX, &v))
                return 2;
            o.memory = (size_t)v;
        } else if (strcmp(a, "--threads") == 0) {
            if (option_value(argc, argv, &i, a, 0, 1, 1024, &v))
                return 2;
            o.threads = (uint32_t)v;
        } else if (strcmp(a, "--grid") == 0) {
            if (option_value(argc, argv, &i, a, 0, 1, 1024, &v))
                return 2;
            o.grid = (uint32_t)v;
        } else if (strcmp(a, "--manage") == 0) {
            static const char *const names[] = {"grid", "kd-parts", "kd-facets", NULL};
            int k = option_choice(argc, argv, &i, a, names, "grid, kd-parts or kd-facets");
            if (k < 0)
                return 2;
            o.manage = (oit_manage)k; /* in oit_manage's order */
            if (o.manage != OIT_MANAGE_GRID)
                guaranteed_only = a;
        } else if (strcmp(a, "--slabs") == 0) {
            static const char *const names[] = {"all", "separating", "none", NULL};
            int k = option_choice(argc, argv, &i, a, names, "all, separating or none");
            if (k < 0)
                return 2;
            o.slabs = (oit_kd_slabs)k; /* in oit_kd_slabs' order */
            guaranteed_only = a;
        } else if (strcmp(a, "--scheme") == 0) {
            static const char *const names[] = {"fast", "guaranteed", NULL};
            int k = option_choice(argc, argv, &i, a, names, "fast or guaranteed");
            if (k < 0)
                return 2;
            o.scheme = (oit_scheme)k; /* in oit_scheme's order */
            scheme_given = 1;
        } else if (strcmp(a, "--part-triangles") == 0) {
            if (option_value(argc, argv, &i, a, 1, 1, 1u << 24, &v))
                return 2;
            o.part_triangles = (uint32_t)v;
        } else if (strcmp(a, "--deflection") == 0) {
            /* checked here for the usage error; oit_read_desc owns its meaning */
            if (i + 1 >= argc || oit_parse_double(argv[i + 1], 0.0, DBL_MAX, &o.deflection) ||
                !(o.deflection > 0.0)) {
                fprintf(stderr, "oitprep: --deflection '%s': want a number > 0 (the file's "
                        "units)\n", i + 1 < argc ? argv[i + 1] : "");
                return 2;
            }
            i++;
        } else if (strcmp(a, "--max-piece-triangles") == 0) {
            if (option_value(argc, argv, &i, a, 0, 1, 1u << 30, &v))
                return 2;
            o.max_piece_triangles = (uint32_t)v;
            guaranteed_only = a;
        } else if (a[0] == '-' || o.input) {
            fprintf(stderr, "oitprep: unexpected argument '%s' (see oitprep --help)\n", a);
            return 2;
        } else
            o.input = a;
    }
    if (!o.input || !o.output) {
        fprintf(stderr, "oitprep: conversion needs INPUT and -o OUT (see oitprep --help)\n");
        return 2;
    }
    if (guaranteed_only && !scheme_given)
        o.scheme = OIT_SCHEME_GUARANTEED;
    else if (guaranteed_only && o.scheme == OIT_SCHEME_FAST) {
        fprintf(stderr, "oitprep: %s applies to --scheme guaranteed only (the fast scheme has "
                "no convex pieces and no slabs)\n", guaranteed_only);
        return 2;
    }
    oit_error err = {0};
    oit_status s = check_outputs(o.input, o.output, stats, &err);
    if (s) {
        print_error(&err);
        return oit_tool_exit_code(s);
    }
    static const char *const tmp[] = {".tmp", NULL}; /* partfile_write.c */
    oit_tool_signals_install("oitprep", o.output, tmp);
    oit_convert_stats st;
    s = oit_convert(&o, &st, &err);
    if (s) {
        print_error(&err);
        return oit_tool_exit_code(s);
    }
    if (o.scheme == OIT_SCHEME_FAST && st.clamped_parts)
        fprintf(stderr, "oitprep: %s: %llu parts measured more than %u layers (most %u) after "
                "every extra split; stored as %u\n", o.output,
                (unsigned long long)st.clamped_parts, OIT_PARTFILE_MAX_LAYERS, st.max_measured,
                OIT_PARTFILE_MAX_LAYERS);
    fprintf(stderr,
            "oitprep: %s: %llu triangles in, %llu out (dropped %llu degenerate, %llu non-finite; "
            "split %+lld), %llu pieces, %llu parts, %llu cells, %.2f s\n",
            o.output, (unsigned long long)st.triangles_in, (unsigned long long)st.triangles_out,
            (unsigned long long)st.degenerate_dropped, (unsigned long long)st.nonfinite_dropped,
            (long long)st.split_added, (unsigned long long)st.pieces,
            (unsigned long long)st.parts, (unsigned long long)st.cells, st.seconds_total);
    if (stats && (s = oit_convert_stats_write_json(stats, &o, &st, &err))) {
        print_error(&err);
        return oit_tool_exit_code(s);
    }
    return 0;
}

static int cmd_verify(int argc, char **argv)
{
    oit_verify_options o = {.directions = 64, .viewpoints = 16};
    const char *path = NULL;
    for (int i = 2; i < argc; i++) {
        uint64_t v;
        if (strcmp(argv[i], "--directions") == 0) {
            if (option_value(argc, argv, &i, argv[i], 0, 0, 100000, &v))
                return 2;
            o.directions = (uint32_t)v;
        } else if (strcmp(argv[i], "--viewpoints") == 0) {
            if (option_value(argc, argv, &i, argv[i], 0, 0, 100000, &v))
                return 2;
            o.viewpoints = (uint32_t)v;
        } else if (strcmp(argv[i], "--chunk-triangles") == 0) {
            if (option_value(argc, argv, &i, argv[i], 1, 1, 1ull << 32, &v))
                return 2;
            o.chunk_triangles = v;
        } else if (file_arg("verify", argv[i], &path))
            return 2;
    }
    if (file_given("verify", path))
        return 2;
    if (o.directions == 0 && o.viewpoints == 0) { /* no ray: nothing verified */
        fprintf(stderr, "oitprep verify: --directions 0 and --viewpoints 0 cast no ray; "
                "give one of them above 0\n");
        return 2;
    }
    oit_verify_report rep;
    oit_error err = {0};
    oit_status s = oit_verify(path, &o, &rep, &err);
    if (s) {
        print_error(&err);
        return oit_tool_exit_code(s);
    }
    oit_verify_print(stdout, path, &rep);
    return rep.layer_violations || rep.order_violations || rep.slab_violations ||
                   rep.sources_lost
               ? 1
               : 0;
}

static int cmd_parts(int argc, char **argv)
{
    const char *path = NULL, *out = NULL;
    oit_export_colour colour = OIT_EXPORT_BY_PART;
    uint8_t alpha = 0;
    for (int i = 2; i < argc; i++) {
        uint64_t v;
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--colour") == 0 || strcmp(argv[i], "--color") == 0) {
            static const char *const names[] = {"part", "kind", NULL};
            int k = option_choice(argc, argv, &i, argv[i], names, "part or kind");
            if (k < 0)
                return 2;
            colour = (oit_export_colour)k; /* in oit_export_colour's order */
        } else if (strcmp(argv[i], "--alpha") == 0) {
            if (option_value(argc, argv, &i, argv[i], 0, 1, 255, &v))
                return 2;
            alpha = (uint8_t)v;
        } else if (file_arg("parts", argv[i], &path))
            return 2;
    }
    if (!path || !out) {
        fprintf(stderr, "oitprep parts: needs FILE and -o OUT.ply (see oitprep --help)\n");
        return 2;
    }
    oit_export_counts c;
    oit_error err = {0};
    oit_status s = oit_output_check(out, "-o", &path, 1, &err);
    static const char *const tmp[] = {".tmp", ".faces.tmp", NULL}; /* write_ply.c */
    if (!s)
        oit_tool_signals_install("oitprep", out, tmp);
    if (!s)
        s = oit_export_parts(path, out, colour, alpha, &c, &err);
    if (s) {
        print_error(&err);
        return oit_tool_exit_code(s);
    }
    printf("%s: %llu parts, %llu triangles (%llu parts of separating slabs, %llu of cutting "
           "planes, %llu wide)\n", out, (unsigned long long)c.parts,
           (unsigned long long)c.triangles, (unsigned long long)c.separating_parts,
           (unsigned long long)c.cutting_parts, (unsigned long long)c.wide_parts);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    /* --help anywhere, after a subcommand too, prints the usage. */
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            usage(stdout);
            return 0;
        }
    if (strcmp(argv[1], "info") == 0)
        return cmd_info(argc, argv);
    if (strcmp(argv[1], "verify") == 0)
        return cmd_verify(argc, argv);
    if (strcmp(argv[1], "parts") == 0)
        return cmd_parts(argc, argv);
    return cmd_convert(argc, argv);
}
