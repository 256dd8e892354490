/* Every row of liboit/desc_ranges.h (the table oit_renderer_desc_check
 * reads) driven at its bounds through oit_renderer_desc_check: lo and hi
 * accepted, lo - 1 and hi + 1 refused (unless 0 is the default or the row's
 * one extra value), 0, the extremes of the field's type, and for floats the
 * open end, the value just below lo, infinities and NaN. The expectation is
 * written here from the row's numbers, not by the check's own comparison;
 * each refusal must be OIT_ERR_ARGUMENT starting with the field's name
 * ("oit_renderer_desc.K = "; a tool spells it as its flag). No GL. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "liboit/desc_ranges.h"
#include "tests/lib/test_check.h"

typedef struct value {
    double d;     /* F32, INT and U32 values; U64 below 2^53 */
    uint64_t u;   /* U64 values (exact) */
    int ok;
} value;

static void set(oit_renderer_desc *desc, const oit_desc_range *r, const value *v)
{
    char *p = (char *)desc + r->offset;
    if (r->type == OIT_DESC_U64) {
        memcpy(p, &v->u, sizeof v->u);
    } else if (r->type == OIT_DESC_U32) {
        uint32_t u = (uint32_t)v->d;
        memcpy(p, &u, sizeof u);
    } else if (r->type == OIT_DESC_INT) {
        int i = (int)v->d;
        memcpy(p, &i, sizeof i);
    } else {
        float f = (float)v->d;
        memcpy(p, &f, sizeof f);
    }
}

/* The values to try on row r and whether each must pass. */
static size_t values(const oit_desc_range *r, value *out)
{
    size_t n = 0;
    if (r->type == OIT_DESC_F32) {
        float lo = (float)r->lo, hi = (float)r->hi;
        out[n++] = (value){.d = lo, .ok = 1};
        out[n++] = (value){.d = nextafterf(hi, lo), .ok = 1};
        out[n++] = (value){.d = hi, .ok = 0};
        out[n++] = (value){.d = nextafterf(lo, -INFINITY), .ok = 0};
        out[n++] = (value){.d = 0.0, .ok = r->zero_default || (0.0f >= lo && 0.0f < hi)};
        out[n++] = (value){.d = NAN, .ok = 0};
        out[n++] = (value){.d = INFINITY, .ok = 0};
        out[n++] = (value){.d = -INFINITY, .ok = 0};
        out[n++] = (value){.d = FLT_MAX, .ok = 0};
        return n;
    }
    uint64_t lo = (uint64_t)r->lo, hi = (uint64_t)r->hi;
    uint64_t top = r->type == OIT_DESC_U64 ? UINT64_MAX
                   : r->type == OIT_DESC_U32 ? UINT32_MAX : (uint64_t)INT_MAX;
    const uint64_t cand[] = {lo, hi, lo - 1, hi + 1, 0, top, top - 1, r->also};
    size_t cn = sizeof cand / sizeof *cand - (r->also == 0);
    for (size_t i = 0; i < cn; i++) {
        uint64_t x = cand[i];
        if (i == 2 && lo == 0)
            continue; /* lo - 1 wraps: -1 below, for signed fields */
        int ok = (x >= lo && x <= hi) || (x == 0 && r->zero_default) ||
                 (r->also != 0 && x == r->also);
        out[n++] = (value){.d = (double)x, .u = x, .ok = ok};
    }
    if (r->type == OIT_DESC_INT) {
        out[n++] = (value){.d = (double)lo - 1.0, .ok = lo - 1 == 0 && r->zero_default};
        out[n++] = (value){.d = (double)INT_MIN, .ok = 0};
    }
    return n;
}

static void check_row(const oit_desc_range *r)
{
    value v[16];
    size_t n = values(r, v);
    char own[64];
    snprintf(own, sizeof own, "oit_renderer_desc.%s = ", r->field);
    for (size_t i = 0; i < n; i++) {
        oit_renderer_desc d = {0};
        set(&d, r, &v[i]);
        oit_error err = {0};
        oit_status s = oit_renderer_desc_check(&d, &err);
        char shown[48];
        if (r->type == OIT_DESC_U64)
            snprintf(shown, sizeof shown, "%llu", (unsigned long long)v[i].u);
        else
            snprintf(shown, sizeof shown, "%.9g", v[i].d);
        CHECK((s == OIT_OK) == v[i].ok, "%s = %s: %s, expected %s", r->field, shown,
              s == OIT_OK ? "accepted" : err.message, v[i].ok ? "accepted" : "refused");
        CHECK(s == OIT_OK ||
                  (s == OIT_ERR_ARGUMENT && strstr(err.message, own) == err.message),
              "%s = %s: the error does not start with its field: %s", r->field, shown,
              err.message);
    }
    printf("%-14s %zu values at its bounds [%.17g, %.17g]%s\n", r->field, n, r->lo, r->hi,
           r->zero_default ? ", 0 the default" : "");
}

int main(void)
{
    /* every row a distinct field, and the whole table driven */
    for (size_t i = 0; i < OIT_DESC_RANGES; i++) {
        for (size_t j = 0; j < i; j++)
            CHECK(oit_desc_ranges[i].offset != oit_desc_ranges[j].offset,
                  "rows %zu and %zu name one field", j, i);
        check_row(&oit_desc_ranges[i]);
    }
    CHECK(OIT_DESC_RANGES >= 9, "only %zu rows", (size_t)OIT_DESC_RANGES);
    /* a descriptor of every default passes */
    oit_error err = {0};
    oit_renderer_desc zero = {0};
    CHECK(oit_renderer_desc_check(&zero, &err) == OIT_OK, "defaults: %s", err.message);
    return test_verdict();
}
