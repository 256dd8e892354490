/* Strict number parsing for command lines and small text headers.
 *
 * strtol, strtoull and strtod accept more than a number: leading blanks, a
 * prefix followed by junk ("12x"), a minus sign that wraps to a huge
 * unsigned value ("-1"), "inf" and "nan", values that overflow (clamped,
 * with only errno to say so). Each tool used to guard against a different
 * subset of those. These parsers accept the whole string as one number or
 * nothing:
 *
 *   integers   -?[0-9]+      (unsigned: no sign at all), decimal only
 *   doubles    -?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?
 *
 * so no blanks, no '+', no hexadecimal, no "inf"/"nan"; a double must be
 * finite and neither overflow nor underflow. Every bound is inclusive.
 *
 * Each returns 0 and stores the value, or returns -1 and leaves *out (and
 * every other output) untouched, so a caller can keep its default and
 * print its own message: the message names the option, which only the
 * tool knows. None prints, allocates, keeps state or changes errno. */
#ifndef OIT_BASE_ARGS_H
#define OIT_BASE_ARGS_H

#include <stdint.h>

/* A decimal integer in [lo, hi]. */
int oit_parse_int(const char *s, int lo, int hi, int *out);

/* An unsigned decimal integer in [lo, hi]; "-1" is refused, never wrapped. */
int oit_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out);

/* A finite double in [lo, hi] (a range of -DBL_MAX..DBL_MAX: any finite
 * number; -FLT_MAX..FLT_MAX: one a float holds). An exclusive bound is the
 * caller's test after this one: "in (0, 1]" is [0, 1] and v > 0. */
int oit_parse_double(const char *s, double lo, double hi, double *out);

/* "WxH": two integers in [lo, hi] joined by one 'x'. "12x", "x12", "0x0"
 * (below lo = 1) and "12x12x" fail. */
int oit_parse_size(const char *s, int lo, int hi, int *w, int *h);

/* A byte count in [lo, hi]: an unsigned integer, optionally with a fraction
 * when a suffix follows, and an optional suffix K, M or G (either case:
 * 1024, 1024^2, 1024^3); "64K", "1.5M". A fraction of a byte is dropped
 * ("0.5K" is 512, "1.0001K" is 1024). Overflowing 64 bits fails. */
int oit_parse_bytes(const char *s, uint64_t lo, uint64_t hi, uint64_t *out);

/* A list of finite doubles separated by sep ("1,0.5,0"), each as
 * oit_parse_double reads one (no range). Stores the first max values in v
 * and returns how many the list holds (which may exceed max, so that a
 * caller can say "more than max"); returns -1, storing nothing useful, when
 * an item is empty or not a number ("", "1,", ",1", "1,,2"). */
int oit_parse_doubles(const char *s, char sep, double *v, int max);

#endif
