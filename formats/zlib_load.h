/* zlib's inflate as a table of functions, filled one of two ways behind the
 * one declaration of oit_zlib_open:
 * - zlib_link.c (the tools, the glTF plugin): the functions zlib links in;
 * - zlib_dlopen.c (liboit): libz.so.1 loaded with dlopen when a gzip file is
 *   met, so that liboit links no zlib and a viewer that reads no .gz never
 *   loads it.
 * formats/CMakeLists.txt builds the readers with each (oit_formats_linked,
 * oit_formats_loaded). The table lives in the object that inflates (the
 * gzip stream's state, one oit_gunzip call) and is closed with it: nothing
 * is cached in a global. */
#ifndef OIT_FORMATS_ZLIB_LOAD_H
#define OIT_FORMATS_ZLIB_LOAD_H

#include <zlib.h>

#include "oit/status.h"

typedef struct oit_zlib {
    void *handle; /* dlopen's handle, NULL when zlib is linked */
    int (*inflate_init2)(z_streamp strm, int window_bits, const char *version, int stream_size);
    int (*inflate)(z_streamp strm, int flush);
    int (*inflate_reset)(z_streamp strm);
    int (*inflate_end)(z_streamp strm);
    const char *(*error)(int code);
} oit_zlib;

/* Fills *z. Fails (OIT_ERR_UNSUPPORTED, naming `name`, the file being read,
 * and zlib's library) only when zlib cannot be loaded. */
oit_status oit_zlib_open(oit_zlib *z, const char *name, oit_error *err);
/* Releases what oit_zlib_open took; z may be zeroed or closed already. */
void oit_zlib_close(oit_zlib *z);

/* inflateInit2 for gzip members only (window 15, +16: the gzip wrapper), as
 * zlib's macro of that name would call it. */
static inline int oit_zlib_init_gzip(const oit_zlib *z, z_stream *zs)
{
    return z->inflate_init2(zs, 15 + 16, ZLIB_VERSION, (int)sizeof(z_stream));
}

#endif
