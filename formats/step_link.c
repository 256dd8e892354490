/* oit_read_step and oit_read_iges for the tools: the Open CASCADE adapter
 * is linked in (step_internal.h; liboit has step_plugin.c instead). */
#include "formats/step_internal.h"

oit_status oit_read_step(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_occt_read_file(path, OIT_OCCT_STEP, desc, sink, user, info, err);
}

oit_status oit_read_iges(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_occt_read_file(path, OIT_OCCT_IGES, desc, sink, user, info, err);
}
