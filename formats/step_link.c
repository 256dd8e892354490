/* oit_occt_read for the tools: the Open CASCADE adapter is linked in
 * (step_internal.h; liboit has step_plugin.c instead). */
#include "formats/step_internal.h"

oit_status oit_occt_read(const char *path, oit_occt_format format, const oit_read_desc *desc,
                         oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_occt_read_file(path, format, desc, sink, user, info, err);
}
