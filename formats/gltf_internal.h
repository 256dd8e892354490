/* The glTF reader's C entries (gltf_adapter.cpp, the only C++ of formats/).
 *
 * oit_gltf_read_file is oit_read_gltf's work. Two files implement the public
 * oit_read_gltf (mesh.h) over it, and formats/CMakeLists.txt builds the
 * readers with one or the other:
 * - gltf_link.c (tests and fuzzers, oit_formats_linked): the adapter is linked in;
 * - gltf_plugin.c (liboit, oit_formats_loaded): the adapter is the plugin
 *   liboit-gltf.so beside liboit.so, loaded with dlopen for each glTF read
 *   and closed after it, so that liboit links neither C++, tinygltf nor
 *   Draco. The plugin exports oit_gltf_read_file alone, found by the name
 *   OIT_GLTF_PLUGIN_ENTRY; liboit and its plugin come from one build, so
 *   the types they pass (mesh.h) agree.
 *
 * oit_read_gltf_memory reads from memory, for the fuzz target and for
 * callers that already hold the bytes (the tools only).
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

#include "oit/export.h"
#include "oit/mesh.h"
#include "formats/plugin_load.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_GLTF_PLUGIN_ENTRY "oit_gltf_read_file"
/* Visible although the build hides symbols by default: the plugin's one
 * export (gltf_plugin.map), which liboit finds with dlsym. */
OIT_API oit_plugin_read_fn oit_gltf_read_file;

oit_status oit_read_gltf_memory(const unsigned char *bytes, size_t size, const char *name,
                                const char *dir, const oit_read_desc *desc,
                                oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
