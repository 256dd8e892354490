/* oit_lib_reference_load (liboit_reference.h). */
#include "liboit/liboit_reference.h"

#include "view/render/reference/reference_plugin.h"

#ifndef OIT_REFERENCE_PLUGIN_FILE /* the plugin's file name, from CMake */
#error "OIT_REFERENCE_PLUGIN_FILE (the reference plugin's file name) is not defined"
#endif

oit_status oit_lib_reference_load(oit_plugin *plugin, const oit_method **out, oit_error *err)
{
    *out = NULL;
    /* keep: Embree's TBB threads and their state are not made to be unloaded */
    static const oit_plugin_desc d = {OIT_REFERENCE_PLUGIN_FILE, OIT_REFERENCE_PLUGIN_ENTRY,
                                      "Embree reference", 1};
    /* plugin_load's messages open with the file read; a method has none, so
     * the method's name stands there, as in the method's own errors */
    oit_status s = oit_plugin_open(&d, "method reference", "the reference method", plugin, err);
    if (s == OIT_OK)
        *out = ((oit_reference_plugin_fn *)plugin->entry)();
    return s;
}
