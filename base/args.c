/* Strict number parsing (args.h). */
#include "base/args.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* [s, end) is one or more digits whose value fits 64 bits. */
static int digits_u64(const char *s, const char *end, uint64_t *out)
{
    uint64_t v = 0;
    if (s == end)
        return -1;
    for (; s < end; s++) {
        if (!is_digit(*s))
            return -1;
        unsigned d = (unsigned)(*s - '0');
        if (v > (UINT64_MAX - d) / 10)
            return -1;
        v = v * 10 + d;
    }
    *out = v;
    return 0;
}

/* [s, end) is -?digits in [lo, hi]. */
static int range_ll(const char *s, const char *end, long long lo, long long hi, long long *out)
{
    int neg = s < end && *s == '-';
    uint64_t m;
    if (digits_u64(s + neg, end, &m))
        return -1;
    /* LLONG_MIN's magnitude is LLONG_MAX + 1 */
    if (m > (uint64_t)LLONG_MAX + (uint64_t)neg)
        return -1;
    long long v = neg ? (m == (uint64_t)LLONG_MAX + 1 ? LLONG_MIN : -(long long)m) : (long long)m;
    if (v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int oit_parse_int(const char *s, int lo, int hi, int *out)
{
    long long v;
    if (!s || range_ll(s, s + strlen(s), lo, hi, &v))
        return -1;
    *out = (int)v;
    return 0;
}

int oit_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    uint64_t v;
    if (!s || digits_u64(s, s + strlen(s), &v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* The end of the number that starts at s in the grammar of args.h, or NULL
 * when s does not start with one. strtod reads a superset of this grammar,
 * so on the same text it stops at the same place. */
static const char *scan_double(const char *s)
{
    const char *p = s + (*s == '-');
    const char *m = p;
    while (is_digit(*p))
        p++;
    int whole = p > m;
    if (*p == '.') {
        const char *f = ++p;
        while (is_digit(*p))
            p++;
        if (!whole && p == f)
            return NULL; /* "." or "-." */
    } else if (!whole) {
        return NULL;
    }
    if (*p == 'e' || *p == 'E') {
        const char *e = p + 1;
        e += *e == '+' || *e == '-';
        if (!is_digit(*e))
            return NULL; /* "1e", "1e+": not a number, not a prefix to keep */
        while (is_digit(*e))
            e++;
        p = e;
    }
    return p;
}

/* Reads the number at s that scan_double ended at end: finite, no overflow
 * or underflow (errno is kept as the caller had it). */
static int read_double(const char *s, const char *end, double *out)
{
    int saved = errno;
    char *e;
    errno = 0;
    double v = strtod(s, &e);
    int bad = e != end || errno == ERANGE || !isfinite(v);
    errno = saved;
    if (bad)
        return -1;
    *out = v;
    return 0;
}

int oit_parse_double(const char *s, double lo, double hi, double *out)
{
    double v;
    const char *end = s ? scan_double(s) : NULL;
    if (!end || *end || read_double(s, end, &v) || !(v >= lo && v <= hi))
        return -1;
    *out = v;
    return 0;
}

int oit_parse_size(const char *s, int lo, int hi, int *w, int *h)
{
    const char *x = s ? strchr(s, 'x') : NULL;
    long long a, b;
    if (!x || range_ll(s, x, lo, hi, &a) || range_ll(x + 1, x + 1 + strlen(x + 1), lo, hi, &b))
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

int oit_parse_bytes(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (!s)
        return -1;
    const char *p = s;
    while (is_digit(*p))
        p++;
    uint64_t whole;
    if (digits_u64(s, p, &whole))
        return -1;
    const char *frac = NULL;
    if (*p == '.') {
        frac = p;
        for (p++; is_digit(*p); p++)
            ;
    }
    char u = *p;
    uint64_t mul = u == 'K' || u == 'k'   ? 1ull << 10
                   : u == 'M' || u == 'm' ? 1ull << 20
                   : u == 'G' || u == 'g' ? 1ull << 30
                                          : 1;
    p += mul > 1;
    /* a fraction only before a suffix: a fraction of a byte means nothing */
    if (*p || (frac && mul == 1) || whole > UINT64_MAX / mul)
        return -1;
    uint64_t v = whole * mul;
    if (frac) {
        /* ".25" as a double: the part below one unit, at most 2^30 bytes,
         * which a double holds to far better than a byte (an underflow of
         * ".000...1" reads as 0: errno is the caller's, kept) */
        int saved = errno;
        double f = strtod(frac, NULL);
        errno = saved;
        uint64_t extra = (uint64_t)(f * (double)mul);
        if (v > UINT64_MAX - extra)
            return -1;
        v += extra;
    }
    if (v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int oit_parse_doubles(const char *s, char sep, double *v, int max)
{
    if (!s)
        return -1;
    int n = 0;
    for (const char *p = s;; n++) {
        const char *end = scan_double(p);
        double x;
        if (!end || (*end && *end != sep) || read_double(p, end, &x))
            return -1;
        if (n < max)
            v[n] = x;
        if (!*end)
            return n + 1;
        p = end + 1;
    }
}
