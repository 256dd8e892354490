/* oit_occt_read for liboit: the Open CASCADE adapter is
 * the plugin liboit-occt.so (plugin_load.h), loaded on the first read, as
 * the glTF plugin is (gltf_plugin.c, step_internal.h). Unlike glTF's it
 * stays loaded (RTLD_NODELETE): Open CASCADE's libraries keep process-wide
 * state (type registry, messenger, the XCAF application) that is not made
 * to be unloaded and loaded again. */
#include "formats/plugin_load.h"
#include "formats/step_internal.h"

#ifndef OIT_OCCT_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_OCCT_PLUGIN_FILE (the STEP/IGES plugin's file name) is not defined"
#endif

oit_status oit_occt_read(const char *path, oit_occt_format format, const oit_read_desc *desc,
                         oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err)
{
    const char *what = format == OIT_OCCT_STEP ? "STEP" : "IGES";
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_%s: no path given",
                             format == OIT_OCCT_STEP ? "step" : "iges");
    static const oit_plugin_desc d = {OIT_OCCT_PLUGIN_FILE, OIT_OCCT_PLUGIN_ENTRY,
                                      "Open CASCADE", 1};
    oit_plugin p;
    oit_status s = oit_plugin_open(&d, path, what, &p, err);
    if (s != OIT_OK)
        return s;
    s = ((oit_occt_read_fn *)p.entry)(path, format, desc, sink, user, info, err);
    oit_plugin_close(&p);
    return s;
}
