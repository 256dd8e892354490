/* oit_read_gltf for the tools: the glTF adapter is linked in
 * (gltf_internal.h; liboit has gltf_plugin.c instead). */
#include "formats/gltf_internal.h"

oit_status oit_read_gltf(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_gltf_read_file(path, desc, sink, user, info, err);
}
