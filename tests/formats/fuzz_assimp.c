/* libFuzzer target: arbitrary bytes through the assimp reader's from-memory
 * entry (formats/assimp_internal.h), built once per format with
 * OIT_FUZZ_FORMAT the extension assimp is given as its hint (fbx, dae, 3ds,
 * 3mf, ifc). Any status is fine; crashes, hangs, leaks and sanitizer reports
 * are not. A small budget and chunk keep the budget-exceeded and
 * chunk-boundary paths in reach, and the sink checks that no triangle with
 * a non-finite coordinate is delivered. The import runs in a child process
 * (assimp_internal.h), so a death inside libassimp is a failed read here,
 * not a finding, and the child's coverage is not seen by the fuzzer: these
 * targets check the parent's side (the pipe, the sink, the status) and
 * that no input takes the caller down. */
#include "formats/assimp_internal.h"
#include "tests/formats/fuzz_read.h"

#define OIT_STR2(x) #x
#define OIT_STR(x) OIT_STR2(x)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_args a = FUZZ_ARGS;
    oit_read_assimp_memory(data, size, "fuzz." OIT_STR(OIT_FUZZ_FORMAT), OIT_STR(OIT_FUZZ_FORMAT),
                           &a.desc, fuzz_check_finite, NULL, &a.info, &a.err);
    return 0;
}
