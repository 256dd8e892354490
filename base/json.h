/* A small streaming JSON writer: the tools' stats and reports.
 *
 * Values go straight to a FILE* in the order they are written; nothing is
 * held in memory but the open containers. The writer places the commas, the
 * ": " after a key and the escapes, so a caller writes only what the file
 * says. The bytes are those the tools always wrote:
 *   - an inline container separates its items with ", " ({"a": 1, "b": 2});
 *   - a block container puts each item on its own line, indented two spaces
 *     a level, and its closing bracket on a line of its own;
 *   - oit_json_break puts one chosen item (or the closing bracket) on a new
 *     line with a given indent, for the few hand-laid files;
 *   - closing the outermost container ends the line ("}\n").
 *
 * Numbers are written with the printf format each field always had:
 * integers exactly, doubles as %.*f (oit_json_fixed) or %.*g
 * (oit_json_general). JSON has no infinity or NaN: a non-finite double is
 * written as null. Strings are escaped: '"' and '\\' with a backslash, bytes
 * below 0x20 as \u00XX (lowercase hex); every other byte, UTF-8 included,
 * is copied as it is (the text is expected to be UTF-8 already).
 *
 * Every value function takes the member's key: a key inside an object, NULL
 * inside an array and at the top level. Errors are kept, not returned at
 * each call: a failed write (disk full) stops all further output, and a
 * misuse (a key in an array, none in an object, an end with nothing open,
 * nesting deeper than OIT_JSON_MAX_DEPTH) stops it too; oit_json_flush or
 * oit_json_close reports the first of them. The writer holds no global
 * state; one oit_json per file. */
#ifndef OIT_BASE_JSON_H
#define OIT_BASE_JSON_H

#include <stddef.h>
#include <stdio.h>

#include "oit/status.h"

#define OIT_JSON_MAX_DEPTH 16

typedef enum oit_json_layout {
    OIT_JSON_INLINE, /* items on one line, ", " between them */
    OIT_JSON_BLOCK   /* one item a line, two spaces a level */
} oit_json_layout;

/* The writer's state; its fields are the writer's own. */
typedef struct oit_json {
    FILE *f;
    const char *path;   /* for messages only */
    int depth;          /* open containers */
    int brk;            /* indent of a pending oit_json_break, or -1 */
    int write_errno;    /* errno of the first failed write; -1: failed, errno unknown */
    const char *misuse; /* the first misuse, or NULL */
    struct {
        char close;          /* '}' or ']' */
        unsigned char block; /* OIT_JSON_BLOCK */
        unsigned char items; /* 0 until the first item */
    } open[OIT_JSON_MAX_DEPTH];
} oit_json;

/* Starts a document on f (opened by the caller, who chooses its messages);
 * path names f in the messages of oit_json_flush and oit_json_close. */
void oit_json_init(oit_json *w, FILE *f, const char *path);

/* Opens an object or an array as the value of key. */
void oit_json_begin_object(oit_json *w, const char *key, oit_json_layout layout);
void oit_json_begin_array(oit_json *w, const char *key, oit_json_layout layout);

/* Closes the innermost open container; the outermost one ends its line. */
void oit_json_end(oit_json *w);

/* The next item of the innermost container, or its closing bracket if it is
 * closed first, starts a new line indented by indent spaces (after the
 * comma, when one is due), whatever the container's layout. */
void oit_json_break(oit_json *w, int indent);

/* Values. s must be text; NULL is written as null. */
void oit_json_string(oit_json *w, const char *key, const char *s);
void oit_json_int(oit_json *w, const char *key, long long v);
void oit_json_uint(oit_json *w, const char *key, unsigned long long v);
void oit_json_bool(oit_json *w, const char *key, int v);
void oit_json_null(oit_json *w, const char *key);
/* v as printf's %.*f with decimals; null when v is not finite. */
void oit_json_fixed(oit_json *w, const char *key, double v, int decimals);
/* v as printf's %.*g with digits significant digits; null when not finite. */
void oit_json_general(oit_json *w, const char *key, double v, int digits);

/* One member of a run of counters (oit_json_uints). */
typedef struct oit_json_uint_member {
    const char *key;
    unsigned long long v;
} oit_json_uint_member;

/* Writes n unsigned members in order, as n calls of oit_json_uint would: a
 * file's counters read as one table rather than a call each. */
void oit_json_uints(oit_json *w, const oit_json_uint_member *m, size_t n);
#define OIT_JSON_UINTS(w, table) oit_json_uints((w), (table), sizeof(table) / sizeof((table)[0]))

/* Flushes f (left open: stdout) and reports the first failure: OIT_ERR_IO
 * "PATH: write failed[: reason]" for a write, OIT_ERR_ARGUMENT
 * "PATH: JSON writer misuse: what" for a misuse or a container left open. */
oit_status oit_json_flush(oit_json *w, oit_error *err);

/* oit_json_flush's checks, then fclose(f) (always, whatever they found),
 * whose failure is a write failure too. */
oit_status oit_json_close(oit_json *w, oit_error *err);

#endif
