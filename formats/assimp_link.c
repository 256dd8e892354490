/* oit_read_assimp for the tools: the assimp adapter is linked in
 * (assimp_internal.h; liboit has assimp_plugin.c instead). */
#include "formats/assimp_internal.h"

oit_status oit_read_assimp(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                           void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_assimp_read_file(path, desc, sink, user, info, err);
}
