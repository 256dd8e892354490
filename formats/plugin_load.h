/* The C++ readers' plugins as liboit and the tools load them (gltf_plugin.c,
 * assimp_plugin.c, step_plugin.c): a plugin is looked up beside the file
 * that holds this code (liboit.so), else in ../lib from it (a tool in bin/),
 * in the build tree and installed alike, so one liboit or tool always loads
 * its own plugins whatever the library path. */
#ifndef OIT_FORMATS_PLUGIN_LOAD_H
#define OIT_FORMATS_PLUGIN_LOAD_H

#include "oit/mesh.h"
#include "oit/status.h"

typedef struct oit_plugin {
    void *handle;
    void *entry; /* the entry's address: POSIX lets it convert to a function pointer */
} oit_plugin;

/* Which plugin and what its errors say. */
typedef struct oit_plugin_desc {
    const char *file;  /* the plugin's file name (e.g. liboit-gltf.so) */
    const char *entry; /* its one exported symbol */
    const char *name;  /* for messages: "glTF", "assimp", "Open CASCADE" */
    int keep;          /* 1: never unloaded (RTLD_NODELETE), for libraries with
                          process-wide state that is not made to be unloaded */
} oit_plugin_desc;

/* Loads d->file for reading path (what: what the read is, for the message,
 * e.g. "glTF" or "STEP"); on failure the error names path, the plugin's
 * path and dlerror's reason, and nothing is left loaded. */
oit_status oit_plugin_open(const oit_plugin_desc *d, const char *path, const char *what,
                           oit_plugin *out, oit_error *err);
void oit_plugin_close(oit_plugin *p);

/* The entry of a plugin that reads a mesh file as oit_read_gltf does
 * (mesh.h): the glTF and assimp adapters'. */
typedef oit_status oit_plugin_read_fn(const char *path, const oit_read_desc *desc,
                                      oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                      oit_error *err);

/* One read through d's plugin, whose entry is an oit_plugin_read_fn: loaded
 * for the read and closed after it (what: as for oit_plugin_open). */
oit_status oit_plugin_read(const oit_plugin_desc *d, const char *what, const char *path,
                           const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                           oit_mesh_info *info, oit_error *err);

#endif
