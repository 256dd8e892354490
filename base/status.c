#include "oit/status.h"

#include <stdio.h>
#include <string.h>

oit_status oit_error_setv(oit_error *err, oit_status s, const char *fmt, va_list ap)
{
    if (err) {
        err->status = s;
        vsnprintf(err->message, sizeof err->message, fmt, ap);
    }
    return s;
}

oit_status oit_error_set(oit_error *err, oit_status s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    oit_error_setv(err, s, fmt, ap);
    va_end(ap);
    return s;
}

void oit_error_prefix(oit_error *err, const char *what)
{
    if (!err || !what)
        return;
    /* The prefix goes in front; the old message may lose its tail. */
    char tmp[sizeof err->message];
    size_t n = strlen(what);
    if (n > sizeof tmp - 3)
        n = sizeof tmp - 3;
    memcpy(tmp, what, n);
    tmp[n] = ':';
    tmp[n + 1] = ' ';
    size_t rest = sizeof tmp - n - 2;
    memcpy(tmp + n + 2, err->message, rest - 1);
    tmp[sizeof tmp - 1] = '\0';
    memcpy(err->message, tmp, sizeof tmp);
}

const char *oit_status_name(oit_status s)
{
    switch (s) {
    case OIT_OK: return "ok";
    case OIT_ERR_IO: return "i/o error";
    case OIT_ERR_FORMAT: return "bad input";
    case OIT_ERR_NOMEM: return "out of memory";
    case OIT_ERR_ARGUMENT: return "invalid argument";
    case OIT_ERR_UNSUPPORTED: return "unsupported";
    case OIT_ERR_GL: return "GL error";
    case OIT_ERR_CALLBACK: return "stopped by callback";
    }
    return "unknown status";
}
