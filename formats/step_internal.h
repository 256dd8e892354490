/* The STEP and IGES reader's C entries (step_adapter.cpp, C++ over Open
 * CASCADE's XDE).
 *
 * The public oit_read_step and oit_read_iges (mesh.h) are one call of
 * oit_occt_read (step_read.c), which, as for glTF (gltf_internal.h), two
 * files implement over oit_occt_read_file:
 * - step_link.c (tests and fuzzers, oit_formats_linked): the adapter is linked in;
 * - step_plugin.c (liboit, oit_formats_loaded): the adapter is the plugin
 *   liboit-occt.so beside liboit.so, loaded with dlopen for each read and
 *   closed after it, so that liboit links neither C++ nor Open CASCADE. The
 *   plugin exports oit_occt_read_file alone (step_plugin.map).
 *
 * oit_read_step_memory reads STEP text from memory (Open CASCADE reads STEP
 * from a stream, IGES only from a file), for the fuzz target; `name` is used
 * in messages only and no file is opened.
 */
#ifndef OIT_STEP_INTERNAL_H
#define OIT_STEP_INTERNAL_H

#include <stddef.h>

#include "oit/export.h"
#include "oit/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum oit_occt_format { OIT_OCCT_STEP, OIT_OCCT_IGES } oit_occt_format;

#define OIT_OCCT_PLUGIN_ENTRY "oit_occt_read_file"
typedef oit_status oit_occt_read_fn(const char *path, oit_occt_format format,
                                    const oit_read_desc *desc, oit_triangle_sink sink,
                                    void *user, oit_mesh_info *info, oit_error *err);
/* The plugin's one export, which liboit finds with dlsym. */
OIT_API oit_occt_read_fn oit_occt_read_file;
/* A read of the adapter, linked in or through its plugin. */
oit_occt_read_fn oit_occt_read;

oit_status oit_read_step_memory(const unsigned char *bytes, size_t size, const char *name,
                                const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                                oit_mesh_info *info, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
