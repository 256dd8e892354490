/* Doubling growth of the kd result's arrays (kd.c, kd_emit.c, kd_fast.c).
 *
 * Grows *arr (count elements of elem bytes used, *cap allocated) so that it
 * holds need more, doubling from 16; returns 0, or -1 with *arr and *cap
 * unchanged when memory runs out. */
#ifndef OIT_PARTITION_GROW_H
#define OIT_PARTITION_GROW_H

#include <stdlib.h>

static inline int oit_grow(void **arr, size_t elem, size_t count, size_t *cap, size_t need)
{
    if (count + need <= *cap)
        return 0;
    size_t nc = *cap ? *cap : 16;
    while (nc < count + need)
        nc *= 2;
    void *q = realloc(*arr, nc * elem);
    if (!q)
        return -1;
    *arr = q;
    *cap = nc;
    return 0;
}

#endif
