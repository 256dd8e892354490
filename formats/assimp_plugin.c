/* oit_read_assimp for liboit: the assimp adapter (C++, libassimp) is the
 * plugin liboit-assimp.so (plugin_load.h), loaded for the read and closed
 * after it, as the glTF plugin is (gltf_plugin.c). */
#include "formats/assimp_internal.h"
#include "formats/plugin_load.h"

#ifndef OIT_ASSIMP_PLUGIN_FILE /* the plugin's file name, from formats/CMakeLists.txt */
#error "OIT_ASSIMP_PLUGIN_FILE (the assimp plugin's file name) is not defined"
#endif

oit_status oit_read_assimp(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                           void *user, oit_mesh_info *info, oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_assimp: no path given");
    static const oit_plugin_desc d = {OIT_ASSIMP_PLUGIN_FILE, OIT_ASSIMP_PLUGIN_ENTRY, "assimp",
                                      0};
    return oit_plugin_read(&d, "it through assimp", path, desc, sink, user, info, err);
}
