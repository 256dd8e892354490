/* Streaming writer for binary little-endian PLY triangle meshes.
 *
 * Memory stays bounded whatever the size: vertices go straight to
 * "<path>.tmp" behind a header of reserved size, faces go to
 * "<path>.faces.tmp" next to it; close appends the faces, writes the real
 * counts into the reserved header (a padding comment keeps its size fixed)
 * and renames "<path>.tmp" to path, so a crash or an abort never leaves a
 * half-written file under the final name.
 *
 * Layout written:
 *   element vertex N: float x y z [uchar red green blue alpha]
 *                     (double x y z when the descriptor asks for doubles)
 *   element face   M: list uchar int vertex_indices (always 3)
 *                     [uchar red green blue alpha]
 * Colour properties appear only when the descriptor asks for them. Indices are
 * absolute (0 = first vertex ever added); oit_ply_writer_add_vertices returns
 * the index of the first vertex it wrote, so a caller can emit one object's
 * vertices and then its faces relative to that base.
 *
 * Usage:
 *   oit_ply_writer *w;
 *   oit_ply_writer_desc d = { .path = "out.ply", .vertex_rgba = 1 };
 *   if (oit_ply_writer_open(&d, &w, &err)) return err.status;
 *   ... oit_ply_writer_add_vertices / oit_ply_writer_add_faces ...
 *   if (oit_ply_writer_close(w, &stats, &err)) return err.status;
 * After any failed call the writer is still valid and must be closed (which
 * then fails and cleans up) or aborted.
 */
#ifndef OIT_FORMATS_PLY_WRITER_H
#define OIT_FORMATS_PLY_WRITER_H

#include <stddef.h>
#include <stdint.h>

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_ply_writer oit_ply_writer;

typedef struct oit_ply_writer_desc {
    const char *path;    /* final file name                                */
    int vertex_rgba;     /* vertices carry red green blue alpha (uchar)    */
    int face_rgba;       /* faces carry red green blue alpha (uchar)       */
    const char *comment; /* optional one-line header comment (no newline)  */
    /* Georeferenced output: positions are written as doubles equal to
     * offset + the float given, so a scene can sit far from the origin with
     * features finer than a float could keep there. */
    int vertex_double;
    double offset[3];
} oit_ply_writer_desc;

typedef struct oit_ply_writer_stats {
    uint64_t vertices;
    uint64_t faces;
    uint64_t bytes; /* size of the final file */
} oit_ply_writer_stats;

/* PLY "int" indices limit the vertex count. */
#define OIT_PLY_WRITER_MAX_VERTICES ((uint64_t)INT32_MAX)

oit_status oit_ply_writer_open(const oit_ply_writer_desc *desc,
                               oit_ply_writer **out, oit_error *err);

/* xyz: 3 floats per vertex; rgba: 4 bytes per vertex, required when the
 * descriptor set vertex_rgba, ignored otherwise. *first (may be NULL) gets
 * the absolute index of the first vertex written. */
oit_status oit_ply_writer_add_vertices(oit_ply_writer *w, const float *xyz,
                                       const uint8_t *rgba, size_t count,
                                       uint32_t *first, oit_error *err);

/* Triangles: idx holds 3 absolute vertex indices per face, each below the
 * number of vertices added so far (checked). rgba: 4 bytes per face, required
 * when the descriptor set face_rgba, ignored otherwise. */
oit_status oit_ply_writer_add_faces(oit_ply_writer *w, const uint32_t *idx,
                                    const uint8_t *rgba, size_t count,
                                    oit_error *err);

/* Counts so far (for progress). */
oit_ply_writer_stats oit_ply_writer_counts(const oit_ply_writer *w);

/* Finishes the file and frees w, successful or not; stats may be NULL. On
 * failure no file appears under the final name and the temporaries are
 * removed. */
oit_status oit_ply_writer_close(oit_ply_writer *w, oit_ply_writer_stats *stats,
                                oit_error *err);

/* Drops everything written, removes the temporaries and frees w. NULL is
 * accepted. */
void oit_ply_writer_abort(oit_ply_writer *w);

#ifdef __cplusplus
}
#endif
#endif
