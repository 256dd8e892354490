/* The Embree reference method for liboit, from its plugin
 * liboit-reference.so (view/render/reference/reference_plugin.h): loaded, not
 * linked, so that liboit links no C++, Embree or TBB. */
#ifndef OIT_LIBOIT_REFERENCE_H
#define OIT_LIBOIT_REFERENCE_H

#include "formats/plugin_load.h"
#include "view/render/method.h"

/* Loads the plugin beside liboit.so (formats/plugin_load.h) and gives its
 * method table in *out, valid until oit_plugin_close(plugin). The plugin is
 * never unloaded (Embree and TBB keep process-wide state), so closing only
 * drops the handle. On failure the error says the plugin could not be
 * loaded, where it was looked for and why, and *out is NULL. */
oit_status oit_lib_reference_load(oit_plugin *plugin, const oit_method **out, oit_error *err);

#endif
