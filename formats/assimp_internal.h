/* The assimp reader's C entries (assimp_adapter.cpp, C++ over Debian's
 * libassimp): every mesh format assimp imports that our own readers do not
 * take (FBX, Collada, 3DS, 3MF, IFC, Blender, X, LightWave, ...).
 *
 * Built as the glTF reader is (gltf_internal.h): oit_read_assimp is
 * implemented over oit_assimp_read_file by
 * - assimp_link.c (tests and fuzzers, oit_formats_linked): the adapter is linked in;
 * - assimp_plugin.c (liboit, oit_formats_loaded): the adapter is the plugin
 *   liboit-assimp.so beside liboit.so, loaded with dlopen for the read and
 *   closed after it, so that liboit links neither C++ nor assimp. The plugin
 *   exports oit_assimp_read_file alone (assimp_plugin.map).
 *
 * oit_mesh_read (read_mesh.c) hands it every extension no reader of ours
 * takes; the adapter asks assimp whether it imports that extension and
 * refuses the file (OIT_ERR_UNSUPPORTED, naming the extensions of both)
 * when it does not.
 *
 * assimp holds the whole scene: the file's size is charged against
 * desc->memory_budget before the import, the scene's vertex and index
 * arrays after it (the parser's own peak is not seen). Triangles are
 * emitted per node instance with the node's composed transform; points and
 * lines are skipped and counted in a note on stderr.
 *
 * assimp 5.2 dies (SIGSEGV) on some malformed files, so the import runs in
 * a child process (fork) that sends the triangles back through a pipe: a
 * child that dies makes the read fail with OIT_ERR_FORMAT naming its signal,
 * and the caller lives on. The caller's sink runs in the caller's process.
 *
 * oit_read_assimp_memory reads from memory (a gzip stream is inflated
 * first), for the fuzz target and for .gz files: `hint` is the format's
 * extension without its dot ("fbx"). Nothing else is opened, so a format
 * whose data lie in other files reads without them.
 */
#ifndef OIT_ASSIMP_INTERNAL_H
#define OIT_ASSIMP_INTERNAL_H

#include <stddef.h>

#include "oit/export.h"
#include "oit/mesh.h"
#include "formats/plugin_load.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A file in a format assimp imports: in the tools the adapter, in liboit
 * its plugin (assimp_link.c, assimp_plugin.c). */
oit_status oit_read_assimp(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                           void *user, oit_mesh_info *info, oit_error *err);

#define OIT_ASSIMP_PLUGIN_ENTRY "oit_assimp_read_file"
/* Visible although the build hides symbols by default: the plugin's one
 * export (assimp_plugin.map), which liboit finds with dlsym. */
OIT_API oit_plugin_read_fn oit_assimp_read_file;

oit_status oit_read_assimp_memory(const unsigned char *bytes, size_t size, const char *name,
                                  const char *hint, const oit_read_desc *desc,
                                  oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                  oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
