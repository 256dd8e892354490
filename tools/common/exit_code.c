/* exit_code.h */
#include "tools/common/exit_code.h"

int oit_tool_exit_code(oit_status s)
{
    switch (s) {
    case OIT_OK: return 0;
    case OIT_ERR_ARGUMENT: return 2;
    case OIT_ERR_FORMAT:
    case OIT_ERR_UNSUPPORTED: return 3;
    default: return 1;
    }
}
