/* The tools' exit codes, a command line's concern (the library returns
 * oit_status and says nothing of processes): 0 success, 1 runtime failure,
 * 2 usage error, 3 bad input. */
#ifndef OIT_TOOLS_COMMON_EXIT_CODE_H
#define OIT_TOOLS_COMMON_EXIT_CODE_H

#include "oit/status.h"

int oit_tool_exit_code(oit_status s);

#endif
