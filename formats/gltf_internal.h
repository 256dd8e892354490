/* From-memory entry of the glTF reader, for the fuzz target and for callers
 * that already hold the bytes.
 *
 * The bytes are a .glb when they start with the magic "glTF", otherwise JSON
 * text. `name` is used in messages only. External buffers ("uri" that is not
 * a data: URI) are looked up under `dir`; with dir == NULL no file is ever
 * opened and such a buffer is a format error, so untrusted bytes cannot make
 * the reader touch the file system.
 */
#ifndef OIT_GLTF_INTERNAL_H
#define OIT_GLTF_INTERNAL_H

#include <stddef.h>

#include "oit/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* read_common.c's check that a read delivered a triangle (readers_internal.h). */
oit_status oit_rd_require_triangles(const char *name, const oit_mesh_info *info,
                                    oit_error *err);

oit_status oit_read_gltf_memory(const unsigned char *bytes, size_t size, const char *name,
                                const char *dir, const oit_read_desc *desc,
                                oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
