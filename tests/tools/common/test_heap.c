/* The tools' allocator setting (tools/common/heap.h): after it, a block of
 * up to OIT_TOOL_HEAP_MMAP comes from the heap and, freed, stays there for
 * the next one, so a frame that frees and allocates its driver's blocks
 * again faults no page in. Without the mmap threshold (only the trim
 * threshold set, which freezes glibc's at 128 KiB) the first check fails;
 * without the trim threshold, the second. */
#include "tools/common/heap.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
#define SANITIZED_MALLOC 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SANITIZED_MALLOC 1
#endif

#if defined(__GLIBC__) && !defined(SANITIZED_MALLOC) && __GLIBC_PREREQ(2, 33)
#include <malloc.h>

static int fails;

static void check(int ok, const char *what, size_t got)
{
    if (!ok) {
        fprintf(stderr, "FAIL: %s (got %zu)\n", what, got);
        fails++;
    }
}

int main(void)
{
    oit_tool_heap_setup();
    /* the size of llvmpipe's larger blocks: well over glibc's 128 KiB */
    const size_t block = OIT_TOOL_HEAP_MMAP - (1u << 20);
    char *a = malloc(block);
    if (!a) {
        fprintf(stderr, "FAIL: malloc(%zu)\n", block);
        return 1;
    }
    memset(a, 1, block);
    struct mallinfo2 m = mallinfo2();
    check(m.hblks == 0, "a block under OIT_TOOL_HEAP_MMAP is mapped on its own", m.hblks);
    free(a);
    size_t kept = mallinfo2().arena;
    check(kept >= block, "the freed block went back to the kernel", kept);
    char *b = malloc(block);
    m = mallinfo2();
    check(b && m.arena == kept, "the next block of that size grew the heap", m.arena);
    free(b);
    if (fails)
        return 1;
    printf("ok: a %zu-byte block is the heap's, kept when freed, reused\n", block);
    return 0;
}
#else
int main(void)
{
    puts("SKIP: not glibc's own malloc (a sanitizer's, or another C library)");
    return 77;
}
#endif
