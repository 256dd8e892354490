/* Typed stable sorting for hot loops: the partition's kd arrays, the
 * reference renderer's hits per ray.
 *
 * qsort calls its comparator through a pointer for every comparison and
 * moves elements with memmove; on the kd's event, corner and edge arrays
 * that was a fifth of a conversion. OIT_SORT_DEFINE(name, T, less) defines
 *
 *     static void name(T *a, size_t n);
 *
 * a stable merge sort (insertion below 24 elements) ordering by the
 * expression less(x, y) on two const T *. Stable, so equal keys keep their
 * input order and the output never depends on the sort's internals. It
 * takes a scratch copy of n elements; when that allocation fails it falls
 * back to insertion sort (slow, still correct), so it cannot fail. */
#ifndef OIT_BASE_SORT_H
#define OIT_BASE_SORT_H

#include <stddef.h>
#include <stdlib.h>

#define OIT_SORT_SMALL 24

#define OIT_SORT_DEFINE(name, T, less)                                                    \
    static void name##_insertion(T *a, size_t n)                                          \
    {                                                                                     \
        for (size_t i = 1; i < n; i++) {                                                  \
            T x = a[i];                                                                   \
            size_t j = i;                                                                 \
            for (; j > 0 && less(&x, &a[j - 1]); j--)                                     \
                a[j] = a[j - 1];                                                          \
            a[j] = x;                                                                     \
        }                                                                                 \
    }                                                                                     \
    /* Sorts a[0..n) using t[0..n) as scratch. */                                         \
    static void name##_merge(T *a, T *t, size_t n)                                        \
    {                                                                                     \
        if (n <= OIT_SORT_SMALL) {                                                        \
            name##_insertion(a, n);                                                       \
            return;                                                                       \
        }                                                                                 \
        size_t h = n / 2, i = 0, j = h, k = 0;                                            \
        name##_merge(a, t, h);                                                            \
        name##_merge(a + h, t + h, n - h);                                                \
        if (!less(&a[h], &a[h - 1]))                                                      \
            return; /* already in order */                                                \
        while (i < h && j < n)                                                            \
            t[k++] = less(&a[j], &a[i]) ? a[j++] : a[i++];                                \
        while (i < h)                                                                     \
            t[k++] = a[i++];                                                              \
        for (size_t m = 0; m < k; m++)                                                    \
            a[m] = t[m];                                                                  \
    }                                                                                     \
    static void name(T *a, size_t n)                                                      \
    {                                                                                     \
        T *t = n > OIT_SORT_SMALL ? malloc(n * sizeof *t) : NULL;                         \
        if (t)                                                                            \
            name##_merge(a, t, n);                                                        \
        else                                                                              \
            name##_insertion(a, n);                                                       \
        free(t);                                                                          \
    }

#endif
