/* The tools' progress form (progress_mode.h). */
#include "tools/common/progress_mode.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

oit_tool_progress oit_tool_progress_get(const char *tool)
{
    oit_tool_progress p = {isatty(STDERR_FILENO), 0.0};
    const char *env = getenv("OIT_PROGRESS_PERIOD");
    if (env && *env) {
        char *end;
        double v = strtod(env, &end);
        if (*end || !(v > 0.0) || !isfinite(v))
            fprintf(stderr, "%s: OIT_PROGRESS_PERIOD=%s is not a number of seconds > 0; "
                    "ignored (lines every 5 s)\n", tool, env);
        else
            p.period_s = v;
    }
    return p;
}
