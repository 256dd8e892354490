/* libFuzzer target: arbitrary bytes through the PLY reader (via fmemopen,
 * so nothing touches the disk). Any status is fine; crashes, hangs, leaks
 * and sanitizer reports are not. A small budget and chunk keep the
 * budget-exceeded and chunk-boundary paths in reach. */
#include "formats/readers_internal.h"

static oit_status discard(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return OIT_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0; /* fmemopen refuses an empty buffer */
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f)
        return 0;
    oit_read_desc desc = {.chunk_triangles = 7, .memory_budget = (size_t)64 << 20};
    oit_mesh_info info;
    oit_error err;
    oit_read_ply_stream(f, "fuzz.ply", NULL, &desc, discard, NULL, &info, &err);
    fclose(f);
    return 0;
}
