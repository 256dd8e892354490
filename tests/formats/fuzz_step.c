/* libFuzzer target: arbitrary bytes through the STEP reader's from-memory
 * entry (formats/step_internal.h): Open CASCADE's STEP parser, its XDE
 * translation, BRepMesh and our walk of the assembly. Nothing touches the
 * disk. Any status is fine; crashes, hangs, leaks and sanitizer reports are
 * not (an exception must stop at the adapter's C boundary). A small chunk
 * keeps the chunk-boundary path in reach, and the sink checks that no
 * triangle with a non-finite coordinate is delivered. IGES has no stream
 * reader in Open CASCADE, so it is not fuzzed from memory. */
#include "formats/step_internal.h"
#include "tests/formats/fuzz_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_args a = FUZZ_ARGS;
    oit_read_step_memory(data, size, "fuzz.step", &a.desc, fuzz_check_finite, NULL, &a.info,
                         &a.err);
    return 0;
}
