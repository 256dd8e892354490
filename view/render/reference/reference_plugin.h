/* The Embree reference as a plugin, liboit-reference.so (reference_plugin.c):
 * liboit loads it with dlopen (liboit/liboit_reference.h) so that liboit
 * itself links no C++, Embree or TBB. liboit and the plugin come from one
 * build, so the table's types (view/render/method.h) agree on both sides. */
#ifndef OIT_RENDER_REFERENCE_PLUGIN_H
#define OIT_RENDER_REFERENCE_PLUGIN_H

#include "oit/export.h"
#include "view/render/method.h"

/* The plugin's one export (reference_plugin.map), looked up by this name. */
#define OIT_REFERENCE_PLUGIN_ENTRY "oit_reference_plugin_method"
typedef const oit_method *oit_reference_plugin_fn(void);
/* Visible although the build hides symbols by default: dlsym must find it. */
OIT_API oit_reference_plugin_fn oit_reference_plugin_method;

#endif
