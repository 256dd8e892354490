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
 * much resident memory beyond what is in use.
 *
 * Setting the trim threshold also freezes glibc's mmap threshold, which it
 * otherwise raises to the largest block freed: every block over 128 KiB
 * (llvmpipe's scene data, GL buffers and images) was then mapped fresh and
 * unmapped at each use, each of its pages faulted in and zeroed again.
 * Blocks up to OIT_TOOL_HEAP_MMAP (glibc's largest allowed) now come from
 * the heap and are reused: the 332K-triangle CAD assembly streamed at
 * 1024x1024 took 95,000 page faults in its first frame and 23,000 in its
 * second (1,450 and 530 ms); now 57,000 and 6,000 (1,300 and 460 ms). */
#ifndef OIT_COMMON_HEAP_H
#define OIT_COMMON_HEAP_H

#define OIT_TOOL_HEAP_KEEP (64 << 20)
#define OIT_TOOL_HEAP_MMAP (32 << 20)

/* Sets both thresholds where the C library has them (glibc). */
void oit_tool_heap_setup(void);

#endif
