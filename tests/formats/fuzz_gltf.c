/* libFuzzer target: arbitrary bytes through the glTF reader's from-memory
 * entry, as .glb (bytes starting "glTF") or JSON text. No folder is given,
 * so external buffers are refused and nothing touches the disk. Any status
 * is fine; crashes, hangs, leaks and sanitizer reports are not. A small
 * budget and chunk keep the budget-exceeded and chunk-boundary paths in
 * reach, and the sink checks the one promise every reader makes: no
 * triangle with a non-finite coordinate is delivered. */
#include <stdlib.h>

#include "formats/gltf_internal.h"

static oit_status check_finite(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
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
    oit_read_gltf_memory(data, size, "fuzz.gltf", NULL, &desc, check_finite, NULL, &info, &err);
    return 0;
}
