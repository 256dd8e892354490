/* Result codes and error messages shared by every liboit call.
 *
 * Every fallible call returns an oit_status and, when it fails, fills the
 * caller's oit_error (if non-NULL) with one line that names the input and what
 * is wrong ("bunny.off: line 12: vertex index 9000 out of range (8000
 * vertices)"). Library code never prints, exits or aborts.
 */
#ifndef OIT_STATUS_H
#define OIT_STATUS_H

#include "oit/export.h"

#include <stdarg.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum oit_status {
    OIT_OK = 0,
    OIT_ERR_IO,          /* a file could not be opened, read or written   */
    OIT_ERR_FORMAT,      /* the input is malformed                        */
    OIT_ERR_NOMEM,       /* an allocation failed or a budget was exceeded */
    OIT_ERR_ARGUMENT,    /* the caller passed something invalid           */
    OIT_ERR_UNSUPPORTED, /* valid input we do not handle                  */
    OIT_ERR_GL,          /* the GL/EGL driver failed or lacks a feature   */
    OIT_ERR_CALLBACK     /* a caller's callback asked to stop             */
} oit_status;

typedef struct oit_error {
    oit_status status;
    char message[512];
} oit_error;

/* Fills err (when non-NULL) with a printf-formatted message and returns s, so
 * that failures read as `return oit_error_set(err, OIT_ERR_FORMAT, ...)`. */
OIT_API oit_status oit_error_set(oit_error *err, oit_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
OIT_API oit_status oit_error_setv(oit_error *err, oit_status s, const char *fmt, va_list ap);

/* Prefixes an existing message with "what: " (e.g. the file name) so that a
 * low-level error names its input without every layer re-formatting it. */
OIT_API void oit_error_prefix(oit_error *err, const char *what);

OIT_API const char *oit_status_name(oit_status s);

#ifdef __cplusplus
}
#endif
#endif
