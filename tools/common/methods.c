/* The registry (methods.h). */
#include "tools/common/methods.h"

#include <stdio.h>
#include <string.h>

const oit_render_method_info *oit_method_find(const char *name)
{
    uint32_t n = 0;
    const oit_render_method_info *m = oit_render_methods(&n);
    for (uint32_t i = 0; i < n; i++)
        if (!strcmp(m[i].name, name))
            return &m[i];
    return NULL;
}

void oit_method_names(char *buf, size_t cap)
{
    uint32_t n = 0;
    const oit_render_method_info *m = oit_render_methods(&n);
    size_t used = 0;
    buf[0] = 0;
    for (uint32_t i = 0; i < n && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s", i ? "|" : "", m[i].name);
}
