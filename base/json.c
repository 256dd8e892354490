/* The streaming JSON writer (json.h). */
#include "base/json.h"

#include <errno.h>
#include <math.h>
#include <string.h>

static int stopped(const oit_json *w)
{
    return w->write_errno != 0 || w->misuse != NULL;
}

/* Records the first misuse; everything after it is dropped, so the file
 * ends short rather than holding JSON that says something else. */
static void misuse(oit_json *w, const char *what)
{
    if (!stopped(w))
        w->misuse = what;
}

/* rc < 0: the write failed; keeps the first failure's errno. */
static void wrote(oit_json *w, int rc)
{
    if (rc < 0 && !w->write_errno)
        w->write_errno = errno ? errno : -1;
}

static void put(oit_json *w, const char *s)
{
    if (!stopped(w))
        wrote(w, fputs(s, w->f) == EOF ? -1 : 0);
}

static void newline(oit_json *w, int indent)
{
    put(w, "\n");
    for (int i = 0; i < indent && !stopped(w); i++)
        wrote(w, putc(' ', w->f) == EOF ? -1 : 0);
}

static void put_string(oit_json *w, const char *s)
{
    put(w, "\"");
    for (const unsigned char *p = (const unsigned char *)s; *p && !stopped(w); p++) {
        int rc;
        if (*p == '"' || *p == '\\')
            rc = fprintf(w->f, "\\%c", *p);
        else if (*p < 0x20)
            rc = fprintf(w->f, "\\u%04x", *p);
        else
            rc = putc(*p, w->f) == EOF ? -1 : 0;
        wrote(w, rc);
    }
    put(w, "\"");
}

/* Everything before a value: the comma, the line break or space, the key.
 * Returns 0 when the value may follow. */
static int item(oit_json *w, const char *key)
{
    if (stopped(w))
        return -1;
    if (w->depth == 0) {
        if (key)
            misuse(w, "a key outside any object");
        return stopped(w) ? -1 : 0;
    }
    int last = w->depth - 1;
    int in_object = w->open[last].close == '}';
    if (in_object && !key)
        misuse(w, "a value without a key in an object");
    else if (!in_object && key)
        misuse(w, "a key in an array");
    if (stopped(w))
        return -1;
    if (w->open[last].items)
        put(w, ",");
    if (w->brk >= 0)
        newline(w, w->brk);
    else if (w->open[last].block)
        newline(w, 2 * w->depth);
    else if (w->open[last].items)
        put(w, " ");
    w->open[last].items = 1;
    w->brk = -1;
    if (key) {
        put_string(w, key);
        put(w, ": ");
    }
    return stopped(w) ? -1 : 0;
}

void oit_json_init(oit_json *w, FILE *f, const char *path)
{
    memset(w, 0, sizeof *w);
    w->f = f;
    w->path = path ? path : "(JSON output)";
    w->brk = -1;
}

static void begin(oit_json *w, const char *key, oit_json_layout layout, char open, char close)
{
    if (w->depth == OIT_JSON_MAX_DEPTH)
        misuse(w, "nesting deeper than OIT_JSON_MAX_DEPTH");
    if (item(w, key))
        return;
    char s[2] = {open, 0};
    put(w, s);
    w->open[w->depth].close = close;
    w->open[w->depth].block = layout == OIT_JSON_BLOCK;
    w->open[w->depth].items = 0;
    w->depth++;
}

void oit_json_begin_object(oit_json *w, const char *key, oit_json_layout layout)
{
    begin(w, key, layout, '{', '}');
}

void oit_json_begin_array(oit_json *w, const char *key, oit_json_layout layout)
{
    begin(w, key, layout, '[', ']');
}

void oit_json_end(oit_json *w)
{
    if (w->depth == 0)
        misuse(w, "an end with no container open");
    if (stopped(w))
        return;
    int last = w->depth - 1;
    if (w->brk >= 0)
        newline(w, w->brk);
    else if (w->open[last].block)
        newline(w, 2 * last);
    char s[2] = {w->open[last].close, 0};
    put(w, s);
    w->brk = -1;
    w->depth--;
    if (w->depth == 0)
        put(w, "\n");
}

void oit_json_break(oit_json *w, int indent)
{
    if (w->depth == 0)
        misuse(w, "a break outside any container");
    else if (indent < 0)
        misuse(w, "a break with a negative indent");
    else
        w->brk = indent;
}

void oit_json_string(oit_json *w, const char *key, const char *s)
{
    if (item(w, key) == 0) {
        if (s)
            put_string(w, s);
        else
            put(w, "null");
    }
}

void oit_json_int(oit_json *w, const char *key, long long v)
{
    if (item(w, key) == 0)
        wrote(w, fprintf(w->f, "%lld", v));
}

void oit_json_uint(oit_json *w, const char *key, unsigned long long v)
{
    if (item(w, key) == 0)
        wrote(w, fprintf(w->f, "%llu", v));
}

void oit_json_bool(oit_json *w, const char *key, int v)
{
    if (item(w, key) == 0)
        put(w, v ? "true" : "false");
}

void oit_json_null(oit_json *w, const char *key)
{
    if (item(w, key) == 0)
        put(w, "null");
}

/* v as "%.*f" (conv 'f') or "%.*g"; null when not finite (JSON has neither
 * infinity nor NaN). */
static void put_double(oit_json *w, const char *key, char conv, int precision, double v)
{
    if (item(w, key) != 0)
        return;
    if (!isfinite(v))
        put(w, "null");
    else if (conv == 'f')
        wrote(w, fprintf(w->f, "%.*f", precision, v));
    else
        wrote(w, fprintf(w->f, "%.*g", precision, v));
}

void oit_json_fixed(oit_json *w, const char *key, double v, int decimals)
{
    put_double(w, key, 'f', decimals, v);
}

void oit_json_general(oit_json *w, const char *key, double v, int digits)
{
    put_double(w, key, 'g', digits, v);
}

void oit_json_uints(oit_json *w, const oit_json_uint_member *m, size_t n)
{
    for (size_t i = 0; i < n; i++)
        oit_json_uint(w, m[i].key, m[i].v);
}

static oit_status report(const oit_json *w, oit_error *err)
{
    if (w->misuse)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: JSON writer misuse: %s", w->path,
                             w->misuse);
    if (w->write_errno > 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed: %s", w->path,
                             strerror(w->write_errno));
    if (w->write_errno)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed", w->path);
    return OIT_OK;
}

oit_status oit_json_flush(oit_json *w, oit_error *err)
{
    if (w->depth > 0)
        misuse(w, "a container left open");
    if (!stopped(w) && fflush(w->f) != 0)
        wrote(w, -1);
    if (!stopped(w) && ferror(w->f))
        w->write_errno = -1; /* a write the stream hid (buffered) */
    return report(w, err);
}

oit_status oit_json_close(oit_json *w, oit_error *err)
{
    oit_status s = oit_json_flush(w, err);
    errno = 0;
    if (fclose(w->f) != 0 && s == OIT_OK) {
        wrote(w, -1);
        s = report(w, err);
    }
    w->f = NULL;
    return s;
}
