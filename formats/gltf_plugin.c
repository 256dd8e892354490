/* oit_read_gltf for liboit: the glTF adapter (C++: tinygltf, Draco) is the
 * plugin liboit-gltf.so, looked up beside the file that holds this code
 * (liboit.so, in the build tree and installed alike), loaded for the read
 * and closed after it: a glTF read is a one-shot, so no handle outlives it
 * and nothing is cached (gltf_internal.h). */
#define _GNU_SOURCE /* dladdr */
#include "formats/gltf_internal.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#ifndef OIT_GLTF_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_GLTF_PLUGIN_FILE (the glTF plugin's file name) is not defined"
#endif

/* An object of this library for dladdr to place. A static one: an exported
 * function's address could be an executable's definition of it (a program
 * that links both liboit and the readers). */
static const char here;

/* The plugin's path: the folder of the file that holds this code, or the
 * bare name (dlopen then searches the library path) when that file's name
 * has no folder. 0 when the path does not fit in cap bytes. */
static int plugin_path(char *buf, size_t cap)
{
    Dl_info at;
    const char *lib = dladdr(&here, &at) && at.dli_fname ? at.dli_fname : "";
    const char *slash = strrchr(lib, '/');
    int n = slash ? snprintf(buf, cap, "%.*s/%s", (int)(slash - lib), lib, OIT_GLTF_PLUGIN_FILE)
                  : snprintf(buf, cap, "%s", OIT_GLTF_PLUGIN_FILE);
    return n > 0 && (size_t)n < cap;
}

oit_status oit_read_gltf(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_gltf: no path given");
    char plugin[4096];
    if (!plugin_path(plugin, sizeof plugin))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read glTF: the path of the "
                             "glTF plugin %s is too long", path, OIT_GLTF_PLUGIN_FILE);
    void *h = dlopen(plugin, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *why = dlerror();
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read glTF: the glTF plugin "
                             "%s could not be loaded (%s)", path, plugin,
                             why ? why : "no reason given");
    }
    /* dlsym hands out an object pointer; POSIX guarantees it converts to a
     * function pointer. */
    oit_gltf_read_fn *entry = (oit_gltf_read_fn *)dlsym(h, OIT_GLTF_PLUGIN_ENTRY);
    if (!entry) {
        dlclose(h);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read glTF: the glTF plugin "
                             "%s lacks its entry %s (not this liboit's plugin?)", path, plugin,
                             OIT_GLTF_PLUGIN_ENTRY);
    }
    oit_status s = entry(path, desc, sink, user, info, err);
    dlclose(h);
    return s;
}
