/* The helpers every file of the part file reader reports and copies through
 * (handle.h): the lowest file of the reader, so that read.c, the checks
 * (validate*.c) and the part decoder (part_blob.c) all use it and it uses none
 * of them. */
#include "partfile/handle.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
oit_status pf_bad(const oit_partfile *pf, oit_error *err, const char *fmt, ...)
{
    char msg[sizeof err->message];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return oit_error_set(err, OIT_ERR_FORMAT, "%s: %s", pf->name, msg);
}

void *pf_copy_out(const uint8_t *p, uint64_t count, size_t size)
{
    void *d = malloc(count ? count * size : 1);
    if (d && count)
        memcpy(d, p, count * size);
    return d;
}

oit_status pf_nomem(const oit_partfile *pf, oit_error *err)
{
    return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", pf->name);
}
