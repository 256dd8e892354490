/* Which triangles each oitbench method draws. The user's choice is between
 * rendering the source mesh in core and streaming its part file, so:
 *
 *   MESH         in-core methods draw the mesh; the stream draws a part file
 *                given with --parts (checked against the mesh), else one
 *                converted now into a temporary file (removed once open) or
 *                into --save-parts FILE;
 *   FILE.oitp    the stream draws the file; in-core methods draw the source
 *                mesh from --mesh, else the one named in the file's META
 *                when it lies beside the file and matches, else the file's
 *                own (clipped) triangles, which the outputs then say.
 *
 * Whether a part file matches a mesh is bench_match.h's test; a different
 * recorded source name alone is a note, not a mismatch (files get renamed).
 * The reference, the error measure of every method, draws the source mesh
 * whenever there is one. */
#ifndef OIT_OITBENCH_BENCH_MODELS_H
#define OIT_OITBENCH_BENCH_MODELS_H

#include <stdint.h>
#include <stdio.h>

#include "oit/mesh.h"
#include "oit/partfile.h"
#include "prepare/convert/convert.h"
#include "tools/oitbench/bench_run.h"

#define OIT_BENCH_NOTES_MAX 4
#define OIT_BENCH_PATH_MAX 4096

typedef struct oit_bench_models_desc {
    const char *model;       /* the command line's MODEL: a mesh or a .oitp */
    const char *parts;       /* --parts (MODEL a mesh), or NULL */
    const char *mesh;        /* --mesh (MODEL a part file), or NULL */
    int need_parts;          /* an entry streams: a part file is needed */
    /* the conversion when MODEL is a mesh, no --parts and need_parts:
     * input is set here; output must be set (--save-parts, or a file of
     * oit_bench_temp_part_file) */
    oit_convert_options convert;
    int output_is_temp;      /* remove convert.output at close (or failure) */
    FILE *progress;          /* "oitbench: ..." lines; NULL: silent */
} oit_bench_models_desc;

typedef struct oit_bench_conversion {
    int done;                /* converted in this run */
    int kept;                /* into --save-parts (else temporary, removed) */
    const char *scheme;      /* oit_scheme_name */
    uint32_t part_triangles; /* fast scheme's cap, 0 otherwise */
    double seconds;
    uint64_t triangles_in, triangles_out, parts;
} oit_bench_conversion;

typedef struct oit_bench_models {
    int have_source;             /* source holds the source mesh */
    oit_mesh source;
    int have_clipped;            /* clipped holds the part file's triangles */
    oit_mesh clipped;
    oit_partfile *pf;            /* when a part file was opened */
    char source_path[OIT_BENCH_PATH_MAX];   /* "" without a source mesh */
    char parts_path[OIT_BENCH_PATH_MAX];    /* "" without a part file */
    uint64_t source_triangles;   /* the mesh's; META triangles_in without it */
    uint64_t part_triangles;     /* stored in the part file (after clipping) */
    oit_bench_conversion conv;
    /* The temporary part file (output_is_temp), kept until close: the
     * stream method opens it again by name (tools/common/method_run.h). */
    char temp_path[OIT_BENCH_PATH_MAX];
    /* what a reader must know: a source not found, a different name */
    char notes[OIT_BENCH_NOTES_MAX][600];
    int note_count;
} oit_bench_models;

/* Opens everything the run draws. Errors name the file: OIT_ERR_FORMAT
 * (exit 3) for a part file that does not match a mesh it was given with,
 * the reader's or converter's status otherwise. On failure *m holds
 * nothing (and no temporary file is left). */
oit_status oit_bench_models_open(const oit_bench_models_desc *d, oit_bench_models *m,
                                 oit_error *err);
void oit_bench_models_close(oit_bench_models *m);

/* 1 when path names a part file (.oitp, any case); else it is a mesh. */
int oit_bench_is_part_file(const char *path);

/* The mesh the in-core methods draw, its geometry, and the reference's. */
const oit_mesh *oit_bench_models_in_core(const oit_bench_models *m);
oit_bench_geometry oit_bench_models_in_core_geometry(const oit_bench_models *m);

/* Creates an empty temporary file for the conversion in $TMPDIR (else /tmp),
 * never beside the model, and writes its name to path; made before the
 * conversion so that the caller's signal handler knows what to remove. */
oit_status oit_bench_temp_part_file(char *path, size_t cap, oit_error *err);

#endif
