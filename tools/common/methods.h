/* The registry of rendering methods the tools offer (render/method.h): one
 * list, in the order --help and the viewer's keys show them. */
#ifndef OIT_TOOLS_COMMON_METHODS_H
#define OIT_TOOLS_COMMON_METHODS_H

#include <stddef.h>

#include "render/method.h"

/* NULL when no method has that name. */
const oit_method *oit_method_find(const char *name);
/* Writes "dfb|reference|array|...|f2b" (the registry's names) into buf, for
 * --help and error messages; OIT_METHOD_NAMES_MAX bytes hold them all. */
#define OIT_METHOD_NAMES_MAX 256
void oit_method_names(char *buf, size_t cap);

#endif
