/* The tools' allocator setting (heap.h). */
#include "tools/common/heap.h"

#include <stdlib.h> /* defines __GLIBC__ on glibc */
#if defined(__GLIBC__)
#include <malloc.h>
#endif

void oit_tool_heap_setup(void)
{
#if defined(__GLIBC__)
    mallopt(M_TRIM_THRESHOLD, OIT_TOOL_HEAP_KEEP);
    mallopt(M_MMAP_THRESHOLD, OIT_TOOL_HEAP_MMAP);
#endif
}
