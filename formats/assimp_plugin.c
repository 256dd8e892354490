/* oit_read_assimp for liboit: the assimp adapter (C++, libassimp) is the
 * plugin liboit-assimp.so, looked up beside the file that holds this code
 * (liboit.so, in the build tree and installed alike), loaded for the read
 * and closed after it, as the glTF plugin is (gltf_plugin.c). */
#define _GNU_SOURCE /* dladdr */
#include "formats/assimp_internal.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#ifndef OIT_ASSIMP_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_ASSIMP_PLUGIN_FILE (the assimp plugin's file name) is not defined"
#endif

/* An object of this library for dladdr to place (a static one: see
 * gltf_plugin.c). */
static const char here;

/* The plugin's path beside this library, or its bare name; 0 when it does
 * not fit in cap bytes. */
static int plugin_path(char *buf, size_t cap)
{
    Dl_info at;
    const char *lib = dladdr(&here, &at) && at.dli_fname ? at.dli_fname : "";
    const char *slash = strrchr(lib, '/');
    int n = slash ? snprintf(buf, cap, "%.*s/%s", (int)(slash - lib), lib, OIT_ASSIMP_PLUGIN_FILE)
                  : snprintf(buf, cap, "%s", OIT_ASSIMP_PLUGIN_FILE);
    return n > 0 && (size_t)n < cap;
}

oit_status oit_read_assimp(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                           void *user, oit_mesh_info *info, oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_assimp: no path given");
    char plugin[4096];
    if (!plugin_path(plugin, sizeof plugin))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read it through assimp: the "
                             "path of the plugin %s is too long", path, OIT_ASSIMP_PLUGIN_FILE);
    void *h = dlopen(plugin, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *why = dlerror();
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read it through assimp: the "
                             "assimp plugin %s could not be loaded (%s)", path, plugin,
                             why ? why : "no reason given");
    }
    /* POSIX guarantees dlsym's object pointer converts to a function pointer */
    oit_assimp_read_fn *entry = (oit_assimp_read_fn *)dlsym(h, OIT_ASSIMP_PLUGIN_ENTRY);
    if (!entry) {
        dlclose(h);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read it through assimp: the "
                             "plugin %s lacks its entry %s (not this liboit's plugin?)", path,
                             plugin, OIT_ASSIMP_PLUGIN_ENTRY);
    }
    oit_status s = entry(path, desc, sink, user, info, err);
    dlclose(h);
    return s;
}
