/* oit_zlib_open for liboit: libz.so.1 (zlib's soname since 1.0) is loaded
 * with dlopen when a gzip file is read and closed with the reader's state
 * (zlib_load.h), so that liboit.so does not link zlib. */
#include "formats/zlib_load.h"

#include <dlfcn.h>
#include <string.h>

#define OIT_ZLIB_SONAME "libz.so.1"

oit_status oit_zlib_open(oit_zlib *z, const char *name, oit_error *err)
{
    memset(z, 0, sizeof *z);
    void *h = dlopen(OIT_ZLIB_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *why = dlerror();
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: gzip data, but zlib (%s) could not "
                             "be loaded to inflate it: %s", name, OIT_ZLIB_SONAME,
                             why ? why : "no reason given");
    }
    /* dlsym hands out object pointers; POSIX guarantees they convert to
     * function pointers. */
    z->inflate_init2 = (int (*)(z_streamp, int, const char *, int))dlsym(h, "inflateInit2_");
    z->inflate = (int (*)(z_streamp, int))dlsym(h, "inflate");
    z->inflate_reset = (int (*)(z_streamp))dlsym(h, "inflateReset");
    z->inflate_end = (int (*)(z_streamp))dlsym(h, "inflateEnd");
    z->error = (const char *(*)(int))dlsym(h, "zError");
    if (!z->inflate_init2 || !z->inflate || !z->inflate_reset || !z->inflate_end || !z->error) {
        dlclose(h);
        memset(z, 0, sizeof *z);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: gzip data, but the zlib loaded as "
                             "%s lacks inflateInit2_, inflate, inflateReset, inflateEnd or "
                             "zError", name, OIT_ZLIB_SONAME);
    }
    z->handle = h;
    return OIT_OK;
}

void oit_zlib_close(oit_zlib *z)
{
    if (z->handle)
        dlclose(z->handle);
    memset(z, 0, sizeof *z);
}
