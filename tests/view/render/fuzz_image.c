/* libFuzzer target: arbitrary bytes through the PNG and PFM readers that
 * `oitstream --compare` uses (via fmemopen). The first byte picks the
 * format so one corpus covers both. Errors are fine; crashes, leaks, huge
 * allocations from a lying header and sanitizer reports are not. */
#include <stdint.h>
#include <stdio.h>

#include "view/render/image/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    int png = data[0] & 1;
    FILE *f = fmemopen((void *)(data + 1), size - 1, "rb");
    if (!f)
        return 0;
    oit_image img;
    oit_error err;
    if (oit_image_read_stream(f, png ? "fuzz.png" : "fuzz.pfm", png, &img, &err) == OIT_OK)
        oit_image_free(&img);
    fclose(f);
    return 0;
}
