/* The registry (methods.h). */
#include "tools/common/methods.h"

#include <stdio.h>
#include <string.h>

#include "render/baselines/methods.h"
#include "render/reference/reference.h"
#include "tools/common/method_stream.h"

static const oit_method *const methods[] = {
    &oit_method_dfb,      &oit_method_reference, &oit_method_array, &oit_method_stencil,
    &oit_method_stream,   &oit_method_unsorted,  &oit_method_wboit, &oit_method_pll,
    &oit_method_dp,       &oit_method_ppll4,     &oit_method_b3d,   &oit_method_ddp,
    &oit_method_guarded,  &oit_method_f2b,       &oit_method_compute,
};

const oit_method *oit_method_find(const char *name)
{
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        if (!strcmp(methods[i]->name, name))
            return methods[i];
    return NULL;
}

void oit_method_names(char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = 0;
    for (size_t i = 0; i < sizeof methods / sizeof methods[0] && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s", i ? "|" : "", methods[i]->name);
}
