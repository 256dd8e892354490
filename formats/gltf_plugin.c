/* oit_read_gltf for liboit: the glTF adapter (C++: tinygltf, Draco) is the
 * plugin liboit-gltf.so (plugin_load.h), loaded for the read and closed
 * after it: a glTF read is a one-shot, so no handle outlives it and nothing
 * is cached (gltf_internal.h). */
#include "formats/gltf_internal.h"
#include "formats/plugin_load.h"

#ifndef OIT_GLTF_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_GLTF_PLUGIN_FILE (the glTF plugin's file name) is not defined"
#endif

oit_status oit_read_gltf(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_gltf: no path given");
    static const oit_plugin_desc d = {OIT_GLTF_PLUGIN_FILE, OIT_GLTF_PLUGIN_ENTRY, "glTF", 0};
    return oit_plugin_read(&d, "glTF", path, desc, sink, user, info, err);
}
