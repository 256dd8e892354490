/* oit_zlib_open for the tools and the glTF plugin: zlib is linked in
 * (zlib_load.h; liboit has zlib_dlopen.c instead). */
#include "formats/zlib_load.h"

#include <string.h>

oit_status oit_zlib_open(oit_zlib *z, const char *name, oit_error *err)
{
    (void)name;
    (void)err;
    memset(z, 0, sizeof *z);
    z->inflate_init2 = inflateInit2_;
    z->inflate = inflate;
    z->inflate_reset = inflateReset;
    z->inflate_end = inflateEnd;
    z->error = zError;
    return OIT_OK;
}

void oit_zlib_close(oit_zlib *z)
{
    memset(z, 0, sizeof *z);
}
