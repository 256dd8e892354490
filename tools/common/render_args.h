/* The renderer's modes (oit/render_modes.h) as the tools' flags take them:
 * --capture auto|array|stencil|compute, for oitstream and oitbench alike. */
#ifndef OIT_TOOLS_COMMON_RENDER_ARGS_H
#define OIT_TOOLS_COMMON_RENDER_ARGS_H

#include "oit/render_modes.h"
#include "oit/status.h"

/* value into *out; OIT_ERR_ARGUMENT naming flag and value otherwise. */
oit_status oit_tool_parse_capture(const char *value, const char *flag, oit_render_capture *out,
                                  oit_error *err);

/* flag's K: OIT_ERR_ARGUMENT naming it outside [OIT_RENDER_K_MIN,
 * OIT_RENDER_K_MAX]. */
oit_status oit_tool_check_k(long long k, const char *flag, oit_error *err);

#endif
