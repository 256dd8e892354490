/* The tools' allocator setting, made once at the start of main (never in
 * the library: the host's allocator is the host's business).
 *
 * Why: glibc gives the top of its heap back to the kernel whenever more
 * than M_TRIM_THRESHOLD (128 KiB, unless a large mmap'ed block was freed
 * earlier) lies free there. Mesa's llvmpipe grows and frees its vertex
 * buffers at every draw, so each draw faulted its pages back in and the
 * kernel zeroed them again: 15,000 brk calls in 6 frames of the 1M plant at
 * 128x128, 28% of the stream's CPU time there (and of DFB's on the part
 * file's triangles). Keeping OIT_TOOL_HEAP_KEEP bytes costs at most that
 * much resident memory beyond what is in use. */
#ifndef OIT_COMMON_HEAP_H
#define OIT_COMMON_HEAP_H

#define OIT_TOOL_HEAP_KEEP (64 << 20)

/* Sets the trim threshold where the C library has one (glibc). */
void oit_tool_heap_setup(void);

#endif
