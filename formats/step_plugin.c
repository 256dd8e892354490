/* oit_read_step and oit_read_iges for liboit: the Open CASCADE adapter is
 * the plugin liboit-occt.so, looked up beside the file that holds this code,
 * loaded on the first read, as the glTF plugin is (gltf_plugin.c,
 * step_internal.h). Unlike glTF's it stays loaded (RTLD_NODELETE): Open
 * CASCADE's libraries keep process-wide state (type registry, messenger,
 * the XCAF application) that is not made to be unloaded and loaded again. */
#define _GNU_SOURCE /* dladdr */
#include "formats/step_internal.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#ifndef OIT_OCCT_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_OCCT_PLUGIN_FILE (the STEP/IGES plugin's file name) is not defined"
#endif

/* An object of this library for dladdr to place (see gltf_plugin.c). */
static const char here;

static int plugin_path(char *buf, size_t cap)
{
    Dl_info at;
    const char *lib = dladdr(&here, &at) && at.dli_fname ? at.dli_fname : "";
    const char *slash = strrchr(lib, '/');
    int n = slash ? snprintf(buf, cap, "%.*s/%s", (int)(slash - lib), lib, OIT_OCCT_PLUGIN_FILE)
                  : snprintf(buf, cap, "%s", OIT_OCCT_PLUGIN_FILE);
    return n > 0 && (size_t)n < cap;
}

static oit_status read_through_plugin(const char *path, oit_occt_format format,
                                      const oit_read_desc *desc, oit_triangle_sink sink,
                                      void *user, oit_mesh_info *info, oit_error *err)
{
    const char *what = format == OIT_OCCT_STEP ? "STEP" : "IGES";
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_%s: no path given",
                             format == OIT_OCCT_STEP ? "step" : "iges");
    char plugin[4096];
    if (!plugin_path(plugin, sizeof plugin))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the path of the "
                             "plugin %s is too long", path, what, OIT_OCCT_PLUGIN_FILE);
    void *h = dlopen(plugin, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!h) {
        const char *why = dlerror();
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the Open CASCADE "
                             "plugin %s could not be loaded (%s)", path, what, plugin,
                             why ? why : "no reason given");
    }
    oit_occt_read_fn *entry = (oit_occt_read_fn *)dlsym(h, OIT_OCCT_PLUGIN_ENTRY);
    if (!entry) {
        dlclose(h);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the plugin %s "
                             "lacks its entry %s (not this liboit's plugin?)", path, what,
                             plugin, OIT_OCCT_PLUGIN_ENTRY);
    }
    oit_status s = entry(path, format, desc, sink, user, info, err);
    dlclose(h);
    return s;
}

oit_status oit_read_step(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return read_through_plugin(path, OIT_OCCT_STEP, desc, sink, user, info, err);
}

oit_status oit_read_iges(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return read_through_plugin(path, OIT_OCCT_IGES, desc, sink, user, info, err);
}
