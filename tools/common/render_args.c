/* render_args.h */
#include "tools/common/render_args.h"

#include <string.h>

oit_status oit_tool_parse_capture(const char *value, const char *flag, oit_render_capture *out,
                                  oit_error *err)
{
    static const struct {
        const char *name;
        oit_render_capture capture;
    } names[] = {{"auto", OIT_RENDER_CAPTURE_AUTO},
                 {"stencil", OIT_RENDER_CAPTURE_STENCIL},
                 {"array", OIT_RENDER_CAPTURE_ARRAY},
                 {"compute", OIT_RENDER_CAPTURE_COMPUTE}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (value && !strcmp(value, names[i].name)) {
            *out = names[i].capture;
            return OIT_OK;
        }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: '%s' is not auto, stencil, array or compute",
                         flag, value ? value : "");
}

oit_status oit_tool_check_k(long long k, const char *flag, oit_error *err)
{
    if (k >= OIT_RENDER_K_MIN && k <= OIT_RENDER_K_MAX)
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %lld is outside [%d, %d]", flag, k,
                         OIT_RENDER_K_MIN, OIT_RENDER_K_MAX);
}
