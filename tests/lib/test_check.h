/* The assertion every C test uses: a failed CHECK prints the file, line,
 * the condition and a formatted explanation, counts the failure and goes on,
 * so one run reports every broken figure; main returns test_verdict(). */
#ifndef OIT_TESTS_TEST_CHECK_H
#define OIT_TESTS_TEST_CHECK_H

#include <stdio.h>

static int test_failures;

#define CHECK(cond, ...)                                                   \
    do {                                                                   \
        if (!(cond)) {                                                     \
            test_failures++;                                               \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                  \
            fputc('\n', stderr);                                           \
        }                                                                  \
    } while (0)

/* What main returns, last: says "ok" or how many checks failed (each said
 * why as it failed), and gives the exit status, 1 on any failure. */
static inline int test_verdict(void)
{
    if (test_failures)
        printf("%d failure(s)\n", test_failures);
    else
        printf("ok\n");
    return test_failures != 0;
}

#endif
