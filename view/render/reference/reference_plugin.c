/* liboit-reference.so's entry (reference_plugin.h). It exists so that liboit
 * can offer the Embree reference while linking no C++, Embree or TBB: liboit
 * loads this plugin and takes the table through this one function, which
 * is the table the tools link statically (reference_method.c). */
#include "view/render/reference/reference_plugin.h"

#include "view/render/reference/reference.h"

const oit_method *oit_reference_plugin_method(void)
{
    return &oit_method_reference;
}
