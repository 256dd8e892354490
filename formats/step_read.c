/* oit_read_step and oit_read_iges (mesh.h): the one reader of both, Open
 * CASCADE's, linked in or loaded (oit_occt_read, step_internal.h). */
#include "formats/step_internal.h"

oit_status oit_read_step(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_occt_read(path, OIT_OCCT_STEP, desc, sink, user, info, err);
}

oit_status oit_read_iges(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    return oit_occt_read(path, OIT_OCCT_IGES, desc, sink, user, info, err);
}
