/* Triangles as every reader produces them and every renderer consumes them.
 *
 * Readers stream: they call a sink with chunks of triangles, so a converter's
 * memory is bounded by its chunk and vertex tables, not by the file. A
 * triangle carries its three vertices by value (a "soup"): attribute lookups
 * are resolved by the reader, and a chunk can be handed to any consumer
 * without the file's index space.
 *
 * Colours are 8-bit sRGB-encoded values with straight (not premultiplied)
 * alpha. By default (oit_render_shading.colour_space OIT_RENDER_COLOUR_SRGB,
 * oit/liboit.h) all methods blend them in that encoding, as the OIT papers
 * and most viewers do: 50% red over white is 255,127,127.
 * OIT_RENDER_COLOUR_LINEAR decodes them with the exact sRGB EOTF,
 * composites in linear light and encodes the result: 255,187,187. Alpha is coverage in both and never converted.
 * When the input has no colour (or no alpha) the reader writes 255 and clears
 * the bit in oit_mesh_info.attributes; the renderer then substitutes its
 * default colour or alpha (oit_render_shading).
 */
#ifndef OIT_MESH_H
#define OIT_MESH_H

#include "oit/export.h"

#include <stddef.h>
#include <stdint.h>

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_vertex {
    float pos[3];
    uint8_t rgba[4];
} oit_vertex; /* 16 bytes */

typedef struct oit_triangle {
    oit_vertex v[3];
} oit_triangle; /* 48 bytes */

enum {
    OIT_ATTR_COLOUR = 1u << 0, /* the input defines rgb  */
    OIT_ATTR_ALPHA = 1u << 1, /* the input defines alpha */
    /* with OIT_ATTR_ALPHA: some triangle has alpha 255 at its three
     * vertices, so it is opaque (it hides what lies behind it; a triangle
     * with some corners below 255 is not) and the renderers run their
     * opaque pre-pass; readers set it (never without OIT_ATTR_ALPHA),
     * oit_mesh_info_opaque computes it */
    OIT_ATTR_OPAQUE = 1u << 2
};

typedef struct oit_mesh_info {
    uint64_t triangles;          /* triangles delivered to the sink            */
    uint64_t faces_in;           /* polygons read before triangulation         */
    uint64_t vertices_in;        /* vertices declared/read                     */
    uint64_t nonfinite_dropped;  /* triangles dropped: NaN/inf coordinate      */
    uint32_t attributes;         /* OIT_ATTR_* bits                            */
    float bounds_min[3];         /* of delivered triangles; +inf when empty    */
    float bounds_max[3];
    double origin[3];            /* positions are relative to it: a vertex's
                                    place in the file is origin + pos       */
    uint64_t zero_area;          /* delivered triangles of zero area (kept:
                                    they draw nothing; all of them is bad
                                    input for the path readers)             */
    double deflection;           /* STEP and IGES: the chordal deflection
                                    they were tessellated with, in the
                                    file's units; 0 for mesh formats        */
} oit_mesh_info;

/* The origin every reader picks from the first vertex it reads (then
 * subtracts, in double, from every position before rounding to float): 0 on
 * an axis where that vertex lies within 2^16 of zero, where a float still
 * resolves 1/128; else its coordinate rounded to an integer. So a model near
 * the origin is read as it is, and a georeferenced one (UTM or ECEF
 * coordinates, 1e5 to 1e7) keeps its sub-millimetre detail instead of
 * collapsing onto the float grid of 1 that 1e7 has. */
OIT_API void oit_mesh_origin_pick(const double first[3], double origin[3]);
/* in - origin rounded to float; beyond the float range it becomes +-inf
 * (the readers then drop the triangle as non-finite). */
OIT_API void oit_mesh_position(const double origin[3], const double in[3], float out[3]);

/* Descriptor for a read; zero means default for every field. */
typedef struct oit_read_desc {
    size_t chunk_triangles; /* triangles per sink call; default 65536        */
    size_t memory_budget;   /* bytes a reader may hold for vertex tables and
                               buffers; default 2 GiB. A file that needs more
                               fails with OIT_ERR_NOMEM naming the need.     */
    double deflection;      /* STEP and IGES only: the largest distance, in
                               the file's units, between a surface and the
                               triangles that stand for it (Open CASCADE's
                               linear deflection). 0: OIT_DEFAULT_DEFLECTION
                               of the diagonal of the model's bounding box.
                               Negative, NaN or infinite: OIT_ERR_ARGUMENT. */
} oit_read_desc;

/* The default deflection, relative to the bounding box's diagonal: 0.1%,
 * fine enough that curved glass reads as smooth at a full-model view. */
#define OIT_DEFAULT_DEFLECTION 0.001

/* Called with each chunk; return OIT_OK to continue. Any other status stops
 * the read and is returned by the reader (err is passed through). */
typedef oit_status (*oit_triangle_sink)(void *user, const oit_triangle *tris,
                                        size_t count, oit_error *err);

/* Reads any supported file; the format is chosen by extension
 * (case-insensitive): .ply .obj .off .stl .gltf .glb .vtk .vtp by liboit's own
 * readers, .step .stp .iges .igs through Open CASCADE, every other extension
 * that assimp imports (.fbx .dae .3ds .3mf .ifc ...) through assimp; each
 * C++ reader is a plugin liboit loads for the read. info may be NULL. On
 * failure the message names the file and, where the reader knows it, the
 * line or byte offset where it went wrong. */
OIT_API oit_status oit_mesh_read(const char *path, const oit_read_desc *desc,
                                 oit_triangle_sink sink, void *user,
                                 oit_mesh_info *info, oit_error *err);

/* The individual readers, for callers that know the format. */
OIT_API oit_status oit_read_ply(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
OIT_API oit_status oit_read_obj(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
OIT_API oit_status oit_read_off(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
OIT_API oit_status oit_read_stl(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
OIT_API oit_status oit_read_gltf(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
/* STEP (AP203/AP214/AP242) and IGES: the B-rep tessellated at
 * desc->deflection, every instance of the assembly placed, each face with
 * the colour and transparency of its presentation data (the face's own,
 * else its shape's, else the nearest assembly's). Faces without any colour
 * are white; OIT_ATTR_ALPHA is set only when some colour is transparent. */
OIT_API oit_status oit_read_step(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);
OIT_API oit_status oit_read_iges(const char *path, const oit_read_desc *desc, oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err);

/* An in-core triangle array, for renderers that need the whole scene. */
typedef struct oit_mesh {
    oit_triangle *tris;
    size_t count;
    size_t capacity;
    oit_mesh_info info;
} oit_mesh;

OIT_API oit_status oit_mesh_load(const char *path, const oit_read_desc *desc,
                                 oit_mesh *out, oit_error *err);
/* Appends triangles, growing geometrically; for generators and tests. */
OIT_API oit_status oit_mesh_append(oit_mesh *m, const oit_triangle *tris, size_t count,
                                   oit_error *err);
OIT_API void oit_mesh_free(oit_mesh *m);

/* Bounds helpers used by readers so that every reader counts the same way. */
OIT_API void oit_mesh_info_init(oit_mesh_info *info);
OIT_API void oit_mesh_info_add(oit_mesh_info *info, const oit_triangle *tris, size_t count);
/* Sets OIT_ATTR_OPAQUE in info->attributes when it has OIT_ATTR_ALPHA and
 * one of tris[0..count) has alpha 255 at its three vertices; clears it
 * without OIT_ATTR_ALPHA. Readers call it on every chunk and at the end. */
OIT_API void oit_mesh_info_opaque(oit_mesh_info *info, const oit_triangle *tris, size_t count);
/* 1 when all nine coordinates are finite. */
OIT_API int oit_triangle_is_finite(const oit_triangle *t);

#ifdef __cplusplus
}
#endif
#endif
