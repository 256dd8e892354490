/* A part's indexed blob (docs/part-file.md) as the triangle soup that
 * render/gpu_mesh draws, and a whole part file as an in-core oit_mesh, so
 * that every method renders the same triangles in the same order: part by
 * part, each part's triangles in its index order. A triangle's primitive id
 * is therefore the part's first triangle across the file plus its index in
 * the part, for the streamer and for DFB alike. */
#ifndef OIT_STREAM_PART_TRIANGLES_H
#define OIT_STREAM_PART_TRIANGLES_H

#include "oit/mesh.h"
#include "oit/partfile.h"

/* Writes the part's index_count / 3 triangles to dst; the part must pass
 * oit_partfile_part_data (validated). Parts without colour get rgba 255,
 * which the shading replaces with its defaults (oit_shading.attributes). */
oit_status oit_part_expand(const oit_partfile *pf, uint32_t part, oit_triangle *dst,
                           oit_error *err);

/* Validates and expands every part into out (info: the file's bounds,
 * attributes and triangle count). */
oit_status oit_partfile_load_mesh(oit_partfile *pf, oit_mesh *out, oit_error *err);

/* Mesh info of the file (bounds, attributes, triangles) without loading it. */
void oit_partfile_mesh_info(const oit_partfile *pf, oit_mesh_info *info);

#endif
