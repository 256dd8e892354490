/* libFuzzer target: arbitrary bytes through the glTF reader's from-memory
 * entry, as .glb (bytes starting "glTF") or JSON text. No folder is given,
 * so external buffers are refused and nothing touches the disk. Any status
 * is fine; crashes, hangs, leaks and sanitizer reports are not. A small
 * budget and chunk keep the budget-exceeded and chunk-boundary paths in
 * reach, and the sink checks the one promise every reader makes: no
 * triangle with a non-finite coordinate is delivered. */
#include "formats/gltf_internal.h"
#include "tests/formats/fuzz_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_args a = FUZZ_ARGS;
    oit_read_gltf_memory(data, size, "fuzz.gltf", NULL, &a.desc, fuzz_check_finite, NULL, &a.info,
                         &a.err);
    return 0;
}
