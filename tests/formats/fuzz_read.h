/* What the reader fuzz targets share: the arguments of one read but the
 * bytes, and the sink that checks the one promise every reader makes, no
 * triangle with a non-finite coordinate delivered. A small budget and chunk
 * keep the budget-exceeded and chunk-boundary paths in reach. */
#ifndef OIT_TESTS_FORMATS_FUZZ_READ_H
#define OIT_TESTS_FORMATS_FUZZ_READ_H

#include <stdlib.h>

#include "oit/mesh.h"

typedef struct fuzz_args {
    oit_read_desc desc;
    oit_mesh_info info;
    oit_error err;
} fuzz_args;

#define FUZZ_ARGS {.desc = {.chunk_triangles = 7, .memory_budget = (size_t)64 << 20}}

static inline oit_status fuzz_check_finite(void *user, const oit_triangle *t, size_t n,
                                           oit_error *err)
{
    (void)user;
    (void)err;
    for (size_t i = 0; i < n; i++)
        if (!oit_triangle_is_finite(&t[i]))
            abort();
    return OIT_OK;
}

#endif
