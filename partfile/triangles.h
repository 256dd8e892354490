/* A part's indexed blob (docs/part-file.md) as the triangle soup that
 * view/render/gl/gpu_mesh draws, and a whole part file as an in-core oit_mesh, so
 * that every method renders the same triangles with the same primitive ids
 * (the tie-break key): each triangle's source index (its position among
 * the triangles the reader delivered for the source file). The streamer
 * uploads the source indices with the triangles and draws them as the
 * prims (oit_part_expand_sourced); the in-core mesh is sorted by source
 * index, so that there a triangle's position, which DFB and the baselines
 * take as its prim, orders like its source index, and ties break as on the
 * source mesh. */
#ifndef OIT_PARTFILE_TRIANGLES_H
#define OIT_PARTFILE_TRIANGLES_H

#include "oit/mesh.h"
#include "oit/partfile.h"

/* Writes the part's index_count / 3 triangles to dst, decoding the part
 * once into buf (oit_partfile_part_load: validated on its first use, so no
 * separate oit_partfile_validate_part is needed). Parts without colour get
 * rgba 255, which the shading replaces with its defaults
 * (oit_shading.attributes). */
oit_status oit_part_expand(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                           oit_triangle *dst, oit_error *err);

/* Bytes oit_part_expand_sourced writes for a part of `triangles`: 48 a
 * triangle, then 4 a source index. */
static inline uint64_t oit_part_sourced_bytes(uint64_t triangles)
{
    return triangles * (sizeof(oit_triangle) + sizeof(uint32_t));
}

/* The part as the GPU draws it from the streamer's ring and cache: its
 * triangles as oit_part_expand writes them at dst (16-byte aligned), then
 * their source indices (u32) at dst + 48 x triangles. */
oit_status oit_part_expand_sourced(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                                   void *dst, oit_error *err);

/* Validates and expands every part into out (info: the file's bounds,
 * attributes and triangle count), ordered by source index, stably: the
 * pieces of one source triangle in file order (part by part, each part's
 * triangles in its index order). Then a triangle's position in out orders
 * like its source index, so DFB on out breaks depth ties as the stream
 * does, and as DFB on the source mesh. */
oit_status oit_partfile_load_mesh(oit_partfile *pf, oit_mesh *out, oit_error *err);

/* Mesh info of the file (bounds, attributes, triangles) without loading it. */
void oit_partfile_mesh_info(const oit_partfile *pf, oit_mesh_info *info);

#endif
