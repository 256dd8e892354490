/* libFuzzer target: the MTL parser, through the OBJ reader that calls it.
 * The input is an OBJ and its material library, split at the first NUL
 * byte (no text format holds one): "OBJ\0MTL". Without a NUL the whole
 * input is the library, read by a fixed OBJ that loads it and uses its
 * likely material names, so that a plain .mtl is a seed too. Every mtllib
 * statement reads the library (oit_read_obj_stream_mtl), from memory:
 * nothing touches the disk. Any status is fine; crashes, hangs, leaks and
 * sanitizer reports are not. */
#include "formats/readers_internal.h"
#include "tests/formats/fuzz_read.h"

static oit_status discard(void *user, const oit_triangle *t, size_t n, oit_error *err)
{
    return OIT_OK;
}

static const char kObj[] = "mtllib fuzz.mtl\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                           "usemtl a\nf 1 2 3\nusemtl red\nf 1 2 3\nusemtl blue\nf -3 -2 -1\n"
                           "mtllib fuzz.mtl\nusemtl a\nf 1 2 3\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nul = memchr(data, 0, size);
    const void *obj = kObj, *mtl = data;
    size_t obj_n = sizeof kObj - 1, mtl_n = size;
    if (nul) {
        obj = data;
        obj_n = (size_t)(nul - data);
        mtl = nul + 1;
        mtl_n = size - obj_n - 1;
    }
    static const char empty[] = "\n"; /* fmemopen refuses an empty buffer */
    if (obj_n == 0)
        obj = empty, obj_n = 1;
    if (mtl_n == 0)
        mtl = empty, mtl_n = 1;
    FILE *f = fmemopen((void *)obj, obj_n, "rb");
    FILE *m = fmemopen((void *)mtl, mtl_n, "rb");
    if (f && m) {
        fuzz_args a = FUZZ_ARGS;
        oit_read_obj_stream_mtl(f, "fuzz.obj", m, "fuzz.mtl", &a.desc, discard, NULL, &a.info,
                                &a.err);
    }
    if (f)
        fclose(f);
    if (m)
        fclose(m);
    return 0;
}
