/* oit_plugin_open (plugin_load.h). */
#define _GNU_SOURCE /* dladdr */
#include "formats/plugin_load.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* An object of this library for dladdr to place. A static one: an exported
 * function's address could be an executable's definition of it (a program
 * that links both liboit and the readers). */
static const char here;

/* The plugin's path: beside the file that holds this code (liboit.so, or a
 * plugin-loading build of our libraries in the build tree or an installed
 * tree), else, when nothing of that name is there, in the lib folder beside
 * that file's folder (bin/oitprep -> lib/liboit-occt.so: the tools' layout,
 * built and installed alike). The bare name (dlopen then searches the
 * library path) when that file's name has no folder. 0 when the path does
 * not fit in cap bytes. */
static int plugin_path(const char *file, char *buf, size_t cap)
{
    Dl_info at;
    const char *lib = dladdr(&here, &at) && at.dli_fname ? at.dli_fname : "";
    const char *slash = strrchr(lib, '/');
    if (!slash) {
        int n = snprintf(buf, cap, "%s", file);
        return n > 0 && (size_t)n < cap;
    }
    int dir = (int)(slash - lib);
    int n = snprintf(buf, cap, "%.*s/%s", dir, lib, file);
    if (n <= 0 || (size_t)n >= cap)
        return 0;
    char up[4096];
    int m = snprintf(up, sizeof up, "%.*s/../lib/%s", dir, lib, file);
    /* beside it when there, else ../lib when there; else beside it, which
     * dlerror then names */
    if (access(buf, F_OK) != 0 && m > 0 && (size_t)m < cap && (size_t)m < sizeof up &&
        access(up, F_OK) == 0)
        memcpy(buf, up, (size_t)m + 1);
    return 1;
}

oit_status oit_plugin_open(const oit_plugin_desc *d, const char *path, const char *what,
                           oit_plugin *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    char plugin[4096];
    if (!plugin_path(d->file, plugin, sizeof plugin))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the path of the "
                             "%s plugin %s is too long", path, what, d->name, d->file);
    void *h = dlopen(plugin, RTLD_NOW | RTLD_LOCAL | (d->keep ? RTLD_NODELETE : 0));
    if (!h) {
        const char *why = dlerror();
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the %s plugin %s "
                             "could not be loaded (%s)", path, what, d->name, plugin,
                             why ? why : "no reason given");
    }
    void *entry = dlsym(h, d->entry);
    if (!entry) {
        dlclose(h);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: cannot read %s: the %s plugin %s "
                             "lacks its entry %s (not this liboit's plugin?)", path, what,
                             d->name, plugin, d->entry);
    }
    *out = (oit_plugin){h, entry};
    return OIT_OK;
}

void oit_plugin_close(oit_plugin *p)
{
    if (p->handle)
        dlclose(p->handle);
    memset(p, 0, sizeof *p);
}

oit_status oit_plugin_read(const oit_plugin_desc *d, const char *what, const char *path,
                           const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                           oit_mesh_info *info, oit_error *err)
{
    oit_plugin p;
    oit_status s = oit_plugin_open(d, path, what, &p, err);
    if (s != OIT_OK)
        return s;
    s = ((oit_plugin_read_fn *)p.entry)(path, desc, sink, user, info, err);
    oit_plugin_close(&p);
    return s;
}
