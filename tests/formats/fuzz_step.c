/* libFuzzer target: arbitrary bytes through the STEP reader's from-memory
 * entry (formats/step_internal.h): Open CASCADE's STEP parser, its XDE
 * translation, BRepMesh and our walk of the assembly. Nothing touches the
 * disk. Any status is fine; crashes, hangs, leaks and sanitizer reports are
 * not (an exception must stop at the adapter's C boundary). A small chunk
 * keeps the chunk-boundary path in reach, and the sink checks that no
 * triangle with a non-finite coordinate is delivered. IGES has no stream
 * reader in Open CASCADE, so it is not fuzzed from memory. */
#include <stdlib.h>

#include "formats/step_internal.h"

static oit_status check_finite(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    (void)user;
    (void)err;
    for (size_t i = 0; i < n; i++)
        if (!oit_triangle_is_finite(&t[i]))
            abort();
    return OIT_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    oit_read_desc desc = {.chunk_triangles = 7, .memory_budget = (size_t)64 << 20};
    oit_mesh_info info;
    oit_error err;
    oit_read_step_memory(data, size, "fuzz.step", &desc, check_finite, NULL, &info, &err);
    return 0;
}
