/* The registry of rendering methods the tools offer: liboit's list
 * (oit_render_methods), in the order --help and the viewer's keys show
 * them; method_run.h runs them. */
#ifndef OIT_TOOLS_COMMON_METHODS_H
#define OIT_TOOLS_COMMON_METHODS_H

#include <stddef.h>

#include "oit/liboit.h"

/* NULL when no method has that name. */
const oit_render_method_info *oit_method_find(const char *name);
/* Writes "dfb|reference|array|...|f2b" (the registry's names) into buf, for
 * --help and error messages; OIT_METHOD_NAMES_MAX bytes hold them all. */
#define OIT_METHOD_NAMES_MAX 256
void oit_method_names(char *buf, size_t cap);

#endif
