/* The ground floor's parsers and JSON writer (base/args.h, base/json.h):
 * every boundary a tool's option meets (the ends of a range and one past,
 * overflow, trailing junk, empty text, a sign on an unsigned number, NaN and
 * infinity, "12x", "0x0"), and the writer's bytes compared whole, so that a
 * wrong comma, space or escape fails. */
#include "base/args.h"
#include "base/json.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/lib/test_check.h"

/* ---- args ---- */

static void test_int(void)
{
    static const struct {
        const char *s;
        int lo, hi, ok, v;
    } cases[] = {
        {"0", 0, 10, 1, 0},
        {"10", 0, 10, 1, 10},
        {"11", 0, 10, 0, 0},
        {"-1", 0, 10, 0, 0},
        {"-7", -10, 10, 1, -7},
        {"-0", 0, 0, 1, 0},
        {"007", 0, 10, 1, 7},
        {"2147483647", INT_MIN, INT_MAX, 1, INT_MAX},
        {"2147483648", INT_MIN, INT_MAX, 0, 0},
        {"-2147483648", INT_MIN, INT_MAX, 1, INT_MIN},
        {"-2147483649", INT_MIN, INT_MAX, 0, 0},
        {"9223372036854775808", INT_MIN, INT_MAX, 0, 0},
        {"99999999999999999999999", INT_MIN, INT_MAX, 0, 0},
        {"", 0, 10, 0, 0},
        {"-", 0, 10, 0, 0},
        {"12x", 0, 100, 0, 0},
        {"1.0", 0, 10, 0, 0},
        {"1e1", 0, 100, 0, 0},
        {" 1", 0, 10, 0, 0},
        {"1 ", 0, 10, 0, 0},
        {"+1", 0, 10, 0, 0},
        {"0x10", 0, 100, 0, 0},
        {"--1", -10, 10, 0, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int v = 12345;
        int rc = oit_parse_int(cases[i].s, cases[i].lo, cases[i].hi, &v);
        CHECK(rc == (cases[i].ok ? 0 : -1), "oit_parse_int(\"%s\", %d, %d): %d", cases[i].s,
              cases[i].lo, cases[i].hi, rc);
        CHECK(v == (cases[i].ok ? cases[i].v : 12345), "oit_parse_int(\"%s\") stored %d",
              cases[i].s, v);
    }
    int v = 5;
    CHECK(oit_parse_int(NULL, 0, 10, &v) == -1 && v == 5, "NULL text");
}

/* oit_parse_u64 and oit_parse_bytes: one table, the parser named per row. */
static void test_unsigned(void)
{
    enum { U64, BYTES };
    static const struct {
        int parser;
        const char *s;
        uint64_t lo, hi;
        int ok;
        uint64_t v;
    } cases[] = {
        {U64, "0", 0, UINT64_MAX, 1, 0},
        {U64, "18446744073709551615", 0, UINT64_MAX, 1, UINT64_MAX},
        {U64, "18446744073709551616", 0, UINT64_MAX, 0, 0},
        {U64, "36893488147419103232", 0, UINT64_MAX, 0, 0},
        {U64, "-1", 0, UINT64_MAX, 0, 0},
        {U64, "-0", 0, UINT64_MAX, 0, 0},
        {U64, "+1", 0, UINT64_MAX, 0, 0},
        {U64, "1", 2, 64, 0, 0},
        {U64, "2", 2, 64, 1, 2},
        {U64, "64", 2, 64, 1, 64},
        {U64, "65", 2, 64, 0, 0},
        {U64, "", 0, 10, 0, 0},
        {U64, "12x", 0, 100, 0, 0},
        {U64, "1K", 0, UINT64_MAX, 0, 0},
        {U64, " 5", 0, 10, 0, 0},
        {BYTES, "64K", 0, UINT64_MAX, 1, 65536},
        {BYTES, "64k", 0, UINT64_MAX, 1, 65536},
        {BYTES, "1M", 0, UINT64_MAX, 1, 1048576},
        {BYTES, "1m", 0, UINT64_MAX, 1, 1048576},
        {BYTES, "2G", 0, UINT64_MAX, 1, 2147483648ull},
        {BYTES, "1.5M", 0, UINT64_MAX, 1, 1572864},
        {BYTES, "0.5K", 0, UINT64_MAX, 1, 512},
        {BYTES, "1.0001K", 0, UINT64_MAX, 1, 1024},
        {BYTES, "100", 0, UINT64_MAX, 1, 100},
        {BYTES, "18446744073709551615", 0, UINT64_MAX, 1, UINT64_MAX},
        {BYTES, "17179869184G", 0, UINT64_MAX, 0, 0}, /* 2^64 */
        {BYTES, "17179869183G", 0, UINT64_MAX, 1, 18446744072635809792ull},
        {BYTES, "65535", 65536, UINT64_MAX, 0, 0},
        {BYTES, "64K", 65536, UINT64_MAX, 1, 65536},
        {BYTES, "1024G", 0, 1ull << 40, 1, 1ull << 40},
        {BYTES, "1025G", 0, 1ull << 40, 0, 0},
        {BYTES, "100.5", 0, UINT64_MAX, 0, 0}, /* a fraction of a byte */
        {BYTES, "K", 0, UINT64_MAX, 0, 0},
        {BYTES, ".5K", 0, UINT64_MAX, 0, 0},
        {BYTES, "1KB", 0, UINT64_MAX, 0, 0},
        {BYTES, "1T", 0, UINT64_MAX, 0, 0},
        {BYTES, "-1K", 0, UINT64_MAX, 0, 0},
        {BYTES, "", 0, UINT64_MAX, 0, 0},
        {BYTES, "1e6", 0, UINT64_MAX, 0, 0},
        {BYTES, " 1K", 0, UINT64_MAX, 0, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *name = cases[i].parser == U64 ? "oit_parse_u64" : "oit_parse_bytes";
        uint64_t v = 777;
        int rc = cases[i].parser == U64 ? oit_parse_u64(cases[i].s, cases[i].lo, cases[i].hi, &v)
                                        : oit_parse_bytes(cases[i].s, cases[i].lo, cases[i].hi, &v);
        CHECK(rc == (cases[i].ok ? 0 : -1), "%s(\"%s\"): %d", name, cases[i].s, rc);
        CHECK(v == (cases[i].ok ? cases[i].v : 777), "%s(\"%s\") stored %llu", name, cases[i].s,
              (unsigned long long)v);
    }
}

static void test_double(void)
{
    static const struct {
        const char *s;
        double lo, hi;
        double v; /* NAN: refused (no parse gives NaN) */
    } cases[] = {
        {"0.5", 0, 1, 0.5},
        {"1", 0, 1, 1.0},
        {"0", 0, 1, 0.0},
        {"1.0000001", 0, 1, NAN},
        {"-0.0000001", 0, 1, NAN},
        {"-.5", -1, 1, -0.5},
        {"5.", 0, 10, 5.0},
        {".25", 0, 1, 0.25},
        {"1e3", 0, DBL_MAX, 1000.0},
        {"1E-3", 0, 1, 0.001},
        {"2.5e+2", 0, 1000, 250.0},
        {"1e308", -DBL_MAX, DBL_MAX, 1e308},
        {"1e309", -DBL_MAX, DBL_MAX, NAN},  /* overflow */
        {"1e-400", -DBL_MAX, DBL_MAX, NAN}, /* underflow */
        {"0e-400", -DBL_MAX, DBL_MAX, 0.0}, /* zero is exact */
        {"1e39", -FLT_MAX, FLT_MAX, NAN},   /* finite, not as a float */
        {"nan", -DBL_MAX, DBL_MAX, NAN},
        {"NAN", -DBL_MAX, DBL_MAX, NAN},
        {"inf", -DBL_MAX, DBL_MAX, NAN},
        {"-inf", -DBL_MAX, DBL_MAX, NAN},
        {"infinity", -DBL_MAX, DBL_MAX, NAN},
        {"0x1p3", -DBL_MAX, DBL_MAX, NAN},
        {"", -DBL_MAX, DBL_MAX, NAN},
        {".", -DBL_MAX, DBL_MAX, NAN},
        {"-", -DBL_MAX, DBL_MAX, NAN},
        {"-.", -DBL_MAX, DBL_MAX, NAN},
        {"1e", -DBL_MAX, DBL_MAX, NAN},
        {"1e+", -DBL_MAX, DBL_MAX, NAN},
        {"e5", -DBL_MAX, DBL_MAX, NAN},
        {"1.5x", -DBL_MAX, DBL_MAX, NAN},
        {"1,5", -DBL_MAX, DBL_MAX, NAN},
        {" 1", -DBL_MAX, DBL_MAX, NAN},
        {"1 ", -DBL_MAX, DBL_MAX, NAN},
        {"+1", -DBL_MAX, DBL_MAX, NAN},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int ok = !isnan(cases[i].v);
        double v = 42.0;
        int rc = oit_parse_double(cases[i].s, cases[i].lo, cases[i].hi, &v);
        CHECK(rc == (ok ? 0 : -1), "oit_parse_double(\"%s\"): %d", cases[i].s, rc);
        CHECK(v == (ok ? cases[i].v : 42.0), "oit_parse_double(\"%s\") stored %.17g", cases[i].s,
              v);
    }
    /* errno is the caller's: a refused overflow leaves it as it was */
    errno = 0;
    double v;
    oit_parse_double("1e999", -DBL_MAX, DBL_MAX, &v);
    CHECK(errno == 0, "errno %d after an overflow", errno);
}

static void test_size(void)
{
    static const struct {
        const char *s;
        int ok, w, h;
    } cases[] = {
        {"640x480", 1, 640, 480},
        {"1x1", 1, 1, 1},
        {"16384x16384", 1, 16384, 16384},
        {"16385x1", 0, 0, 0},
        {"1x16385", 0, 0, 0},
        {"0x0", 0, 0, 0},
        {"0x5", 0, 0, 0},
        {"12x", 0, 0, 0},
        {"x12", 0, 0, 0},
        {"x", 0, 0, 0},
        {"12", 0, 0, 0},
        {"", 0, 0, 0},
        {"12x12x", 0, 0, 0},
        {"1x1x1", 0, 0, 0},
        {"12X12", 0, 0, 0},
        {"-1x5", 0, 0, 0},
        {" 1x1", 0, 0, 0},
        {"1 x1", 0, 0, 0},
        {"99999999999999999999x1", 0, 0, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int w = -1, h = -1;
        int rc = oit_parse_size(cases[i].s, 1, 16384, &w, &h);
        CHECK(rc == (cases[i].ok ? 0 : -1), "oit_parse_size(\"%s\"): %d", cases[i].s, rc);
        if (cases[i].ok)
            CHECK(w == cases[i].w && h == cases[i].h, "oit_parse_size(\"%s\"): %dx%d", cases[i].s,
                  w, h);
        else
            CHECK(w == -1 && h == -1, "oit_parse_size(\"%s\") stored %dx%d", cases[i].s, w, h);
    }
}

static void test_doubles(void)
{
    double v[3] = {9, 9, 9};
    CHECK(oit_parse_doubles("1,0.5,0", ',', v, 3) == 3 && v[0] == 1.0 && v[1] == 0.5 && v[2] == 0.0,
          "three values: %g %g %g", v[0], v[1], v[2]);
    CHECK(oit_parse_doubles("7", ',', v, 3) == 1 && v[0] == 7.0, "one value");
    double w[2] = {9, 9};
    CHECK(oit_parse_doubles("1,2,3,4", ',', w, 2) == 4 && w[0] == 1.0 && w[1] == 2.0,
          "more than max: the count of all, the first max stored");
    CHECK(oit_parse_doubles("1;-2e1", ';', v, 3) == 2 && v[1] == -20.0, "another separator");
    static const char *const bad[] = {"",      ",",    "1,",   ",1",   "1,,2", "1,nan",
                                      "inf,1", "1,2x", "1, 2", "1 ,2", "1;2",  "1e999,1"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(oit_parse_doubles(bad[i], ',', v, 3) == -1, "\"%s\" is not a list", bad[i]);
}

/* ---- json ---- */

/* Each case writes through one of these; the table below holds the bytes
 * it must produce, compared whole. */

static void write_escapes(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_string(w, "q\"k", "say \"hi\"");
    oit_json_string(w, "b", "a\\b");
    oit_json_string(w, "c", "\n\t\r\b\f\x01\x1f");
    oit_json_string(w, "d", "\x7f/");
    oit_json_string(w, "u", "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80"); /* e-acute, euro, emoji */
    oit_json_string(w, "e", "");
    oit_json_string(w, "n", NULL);
    oit_json_end(w);
}

static void write_numbers(oit_json *w)
{
    oit_json_begin_array(w, NULL, OIT_JSON_INLINE);
    oit_json_int(w, NULL, -42);
    oit_json_int(w, NULL, LLONG_MIN);
    oit_json_uint(w, NULL, ULLONG_MAX);
    oit_json_fixed(w, NULL, 0.1235, 3);
    oit_json_fixed(w, NULL, 2.0, 6);
    oit_json_fixed(w, NULL, -0.5, 0);
    oit_json_general(w, NULL, 1.0 / 3.0, 9);
    oit_json_general(w, NULL, 1e-20, 6);
    oit_json_general(w, NULL, 0.1, 17);
    oit_json_fixed(w, NULL, NAN, 3);
    oit_json_fixed(w, NULL, INFINITY, 3);
    oit_json_general(w, NULL, -INFINITY, 9);
    oit_json_bool(w, NULL, 1);
    oit_json_bool(w, NULL, 0);
    oit_json_null(w, NULL);
    oit_json_end(w);
}

/* Containers in containers, empty ones too. */
static void write_inline(oit_json *w)
{
    static const oit_json_uint_member run[] = {{"x", 0}, {"y", 18446744073709551615ull}};
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_begin_object(w, "empty", OIT_JSON_INLINE);
    oit_json_end(w);
    oit_json_begin_array(w, "none", OIT_JSON_INLINE);
    oit_json_end(w);
    oit_json_begin_object(w, "s", OIT_JSON_INLINE);
    oit_json_fixed(w, "t", 1.5, 3);
    oit_json_begin_object(w, "in", OIT_JSON_INLINE);
    OIT_JSON_UINTS(w, run);
    oit_json_end(w);
    oit_json_end(w);
    oit_json_begin_array(w, "g", OIT_JSON_INLINE);
    for (int i = 1; i <= 3; i++)
        oit_json_uint(w, NULL, (unsigned)i);
    oit_json_begin_array(w, NULL, OIT_JSON_INLINE);
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    for (int close = 0; close < 4; close++)
        oit_json_end(w);
}

static void write_block(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_BLOCK);
    oit_json_string(w, "model", "m.ply");
    oit_json_begin_array(w, "frames", OIT_JSON_BLOCK);
    for (int i = 0; i < 2; i++) {
        oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
        oit_json_int(w, "i", i);
        oit_json_bool(w, "ok", i);
        oit_json_end(w);
    }
    oit_json_end(w);
    oit_json_begin_array(w, "none", OIT_JSON_BLOCK);
    oit_json_end(w);
    oit_json_end(w);
}

static void write_breaks(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_break(w, 2);
    oit_json_uint(w, "a", 1);
    oit_json_uint(w, "b", 2);
    oit_json_break(w, 2);
    oit_json_begin_array(w, "v", OIT_JSON_INLINE);
    oit_json_uint(w, NULL, 3);
    oit_json_break(w, 5);
    oit_json_uint(w, NULL, 4);
    oit_json_end(w);
    oit_json_break(w, 0);
    oit_json_end(w);
}

/* A top-level scalar, then two documents. */
static void write_documents(oit_json *w)
{
    oit_json_uint(w, NULL, 7);
    for (int doc = 0; doc < 2; doc++) {
        oit_json_begin_array(w, NULL, OIT_JSON_INLINE);
        oit_json_end(w);
    }
}

/* Misuses: output stops at the first, which close reports. */
static void write_key_in_array(oit_json *w)
{
    oit_json_begin_array(w, NULL, OIT_JSON_INLINE);
    oit_json_uint(w, NULL, 1);
    oit_json_uint(w, "k", 2);
    oit_json_uint(w, NULL, 3);
    oit_json_end(w);
}

static void write_no_key(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_uint(w, NULL, 1);
    oit_json_end(w);
}

static void write_top_key(oit_json *w)
{
    oit_json_bool(w, "k", 1);
}

static void write_extra_end(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_end(w);
    oit_json_end(w);
    oit_json_null(w, NULL);
}

static void write_top_break(oit_json *w)
{
    oit_json_break(w, 2);
}

static void write_left_open(oit_json *w)
{
    oit_json_begin_object(w, NULL, OIT_JSON_INLINE);
    oit_json_uint(w, "a", 1);
}

static void write_too_deep(oit_json *w)
{
    for (int i = 0; i <= OIT_JSON_MAX_DEPTH; i++)
        oit_json_begin_array(w, NULL, OIT_JSON_INLINE);
}

static void test_json_bytes(void)
{
    static const struct {
        const char *what;
        void (*write)(oit_json *w);
        oit_status status;
        const char *bytes;
    } cases[] = {
        {"escapes", write_escapes, OIT_OK,
         "{\"q\\\"k\": \"say \\\"hi\\\"\", \"b\": \"a\\\\b\", "
         "\"c\": \"\\u000a\\u0009\\u000d\\u0008\\u000c\\u0001\\u001f\", "
         "\"d\": \"\x7f/\", \"u\": \"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\", "
         "\"e\": \"\", \"n\": null}\n"},
        {"numbers", write_numbers, OIT_OK,
         "[-42, -9223372036854775808, 18446744073709551615, 0.123, 2.000000, -0, "
         "0.333333333, 1e-20, 0.10000000000000001, null, null, null, true, false, null]\n"},
        {"inline", write_inline, OIT_OK,
         "{\"empty\": {}, \"none\": [], \"s\": {\"t\": 1.500, \"in\": {\"x\": 0, "
         "\"y\": 18446744073709551615}}, \"g\": [1, 2, 3, [{}]]}\n"},
        {"block", write_block, OIT_OK,
         "{\n  \"model\": \"m.ply\",\n  \"frames\": [\n    {\"i\": 0, \"ok\": false},\n"
         "    {\"i\": 1, \"ok\": true}\n  ],\n  \"none\": [\n  ]\n}\n"},
        {"breaks", write_breaks, OIT_OK, "{\n  \"a\": 1, \"b\": 2,\n  \"v\": [3,\n     4]\n}\n"},
        {"documents", write_documents, OIT_OK, "7[]\n[]\n"},
        {"a key in an array", write_key_in_array, OIT_ERR_ARGUMENT, "[1"},
        {"no key in an object", write_no_key, OIT_ERR_ARGUMENT, "{"},
        {"a key at the top", write_top_key, OIT_ERR_ARGUMENT, ""},
        {"an end too many", write_extra_end, OIT_ERR_ARGUMENT, "{}\n"},
        {"a break at the top", write_top_break, OIT_ERR_ARGUMENT, ""},
        {"left open", write_left_open, OIT_ERR_ARGUMENT, "{\"a\": 1"},
        {"too deep", write_too_deep, OIT_ERR_ARGUMENT, "[[[[[[[[[[[[[[[["},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *buf = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&buf, &len);
        CHECK(f != NULL, "open_memstream");
        if (!f)
            return;
        oit_json w;
        oit_json_init(&w, f, "mem.json");
        cases[i].write(&w);
        oit_error err = {0};
        oit_status s = oit_json_close(&w, &err);
        CHECK(s == cases[i].status, "%s: status %d (%s), want %d", cases[i].what, (int)s,
              err.message, (int)cases[i].status);
        /* a misuse names the file and says what went wrong */
        if (cases[i].status == OIT_ERR_ARGUMENT)
            CHECK(strstr(err.message, "mem.json: JSON writer misuse: ") == err.message,
                  "%s: message \"%s\"", cases[i].what, err.message);
        size_t n = strlen(cases[i].bytes);
        CHECK(len == n && memcmp(buf, cases[i].bytes, n) == 0,
              "%s:\n got  [%.*s] (%zu bytes)\n want [%s]", cases[i].what, (int)len, buf ? buf : "",
              len, cases[i].bytes);
        free(buf);
    }
    CHECK(strlen("[[[[[[[[[[[[[[[[") == OIT_JSON_MAX_DEPTH, "the too-deep case's bytes");
}

/* A full disk: the failure comes back as OIT_ERR_IO naming the path. */
static void test_json_write_error(void)
{
    if (access("/dev/full", W_OK) != 0) {
        printf("skip: no /dev/full\n");
        return;
    }
    FILE *f = fopen("/dev/full", "w");
    CHECK(f != NULL, "open /dev/full");
    if (!f)
        return;
    oit_json w;
    oit_json_init(&w, f, "/dev/full");
    oit_json_begin_array(&w, NULL, OIT_JSON_INLINE);
    for (int i = 0; i < 10000; i++) /* more than a stdio buffer */
        oit_json_string(&w, NULL, "0123456789");
    oit_json_end(&w);
    oit_error err = {0};
    oit_status s = oit_json_close(&w, &err);
    CHECK(s == OIT_ERR_IO && strstr(err.message, "/dev/full: write failed") == err.message,
          "disk full: status %d, \"%s\"", (int)s, err.message);

    /* small enough to sit in the buffer until the flush */
    f = fopen("/dev/full", "w");
    oit_json_init(&w, f, "full.json");
    oit_json_uint(&w, NULL, 1);
    s = oit_json_flush(&w, &err);
    CHECK(s == OIT_ERR_IO && strstr(err.message, "full.json: write failed") == err.message,
          "buffered: status %d, \"%s\"", (int)s, err.message);
    fclose(f);
}

int main(void)
{
    test_int();
    test_unsigned();
    test_double();
    test_size();
    test_doubles();
    test_json_bytes();
    test_json_write_error();
    return test_verdict();
}
