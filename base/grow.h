/* Growing parallel arrays (several arrays indexed alike) so that running
 * out of memory leaves each of them valid: a run of
 *     a = oit_grow(a, n, sizeof *a, &ok);
 *     b = oit_grow(b, n, sizeof *b, &ok);
 * grows every array to n elements, or, from the first that cannot grow on,
 * none (ok is then 0; those before it keep their new size, the rest their
 * old one, with their contents). */
#ifndef OIT_BASE_GROW_H
#define OIT_BASE_GROW_H

#include <stdlib.h>

/* p, an array of elements of 'size' bytes, reallocated to n of them; p as
 * it was when *ok is 0 already or there is no memory (*ok is then 0). */
static inline void *oit_grow(void *p, size_t n, size_t size, int *ok)
{
    void *q = *ok ? realloc(p, n * size) : NULL;
    if (!q) {
        *ok = 0;
        return p;
    }
    return q;
}

#endif
