/* libFuzzer target: arbitrary bytes through one streaming mesh reader (via
 * fmemopen, so nothing touches the disk). Built once per format with
 * OIT_FUZZ_FORMAT set to ply, obj, off, stl, vtk or vtp. Any status is fine; crashes,
 * hangs, leaks and sanitizer reports are not. A small budget and chunk keep
 * the budget-exceeded and chunk-boundary paths in reach. */
#include "formats/readers_internal.h"
#include "tests/formats/fuzz_read.h"
#ifdef OIT_FUZZ_VTK
#include "formats/vtk_internal.h" /* oit_read_vtk_stream, oit_read_vtp_stream */
#endif

#define OIT_CAT3(a, b, c) a##b##c
#define OIT_READER(fmt) OIT_CAT3(oit_read_, fmt, _stream)
#define OIT_STR2(x) #x
#define OIT_STR(x) OIT_STR2(x)

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
    fuzz_args a = FUZZ_ARGS;
    OIT_READER(OIT_FUZZ_FORMAT)(f, "fuzz." OIT_STR(OIT_FUZZ_FORMAT), NULL, &a.desc, discard, NULL,
                                &a.info, &a.err);
    fclose(f);
    return 0;
}
