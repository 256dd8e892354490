/* base/sort.h: OIT_SORT_DEFINE's sort is ordered and stable at every size
 * around its insertion threshold and far above it, with many equal keys. */
#include <stdint.h>
#include <stdlib.h>

#include "base/sort.h"
#include "tests/lib/test_check.h"

static uint32_t lcg_next(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

typedef struct keyed {
    uint32_t key, order;
} keyed;
#define KEYED_LESS(x, y) ((x)->key < (y)->key)
OIT_SORT_DEFINE(sort_keyed, keyed, KEYED_LESS)

/* Sorted and stable at every size around the insertion threshold and far
 * above it, with many equal keys. */
static void test_sort(void)
{
    uint32_t seed = 7;
    const size_t sizes[] = {0, 1, 2, 23, 24, 25, 48, 49, 1000, 4097};
    keyed *a = malloc(4097 * sizeof *a);
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        for (size_t i = 0; i < n; i++)
            a[i] = (keyed){lcg_next(&seed) % 17, (uint32_t)i};
        sort_keyed(a, n);
        for (size_t i = 1; i < n; i++)
            CHECK(a[i - 1].key < a[i].key ||
                      (a[i - 1].key == a[i].key && a[i - 1].order < a[i].order),
                  "sort of %zu: element %zu out of order or unstable", n, i);
    }
    free(a);
}


int main(void)
{
    test_sort();
    return test_verdict();
}
