/* Exclusive prefix sum of a GPU uint buffer in compute shaders: blocks of
 * 1024 elements scanned in shared memory, block sums scanned recursively,
 * then added back (work-efficient, O(n)). The first level also accumulates
 * the 64-bit total, the maximum element and the number of elements over a
 * threshold, which callers read back to size their fragment store, fill
 * stats and (capture_counted.h) tell how many pixels a first-K pack of the
 * same parts would send through its second pass. */
#ifndef OIT_RENDER_SCAN_GLSL_H
#define OIT_RENDER_SCAN_GLSL_H

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/host_wait.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_SCAN_LEVELS 4 /* 1024^4 elements */

typedef struct oit_scan {
    GLuint block, add;                  /* programs */
    GLuint sums[OIT_SCAN_LEVELS];       /* block sums per level */
    uint64_t sums_cap[OIT_SCAN_LEVELS];
    GLuint totals;                      /* uint lo, hi, max, pad */
    /* Groups one dispatch takes (GL_MAX_COMPUTE_WORK_GROUP_COUNT[0], read
     * by oit_scan_init); more are dispatched in turn. Lower only to test. */
    GLuint max_groups;
    /* Elements greater than this are counted in oit_scan_result.over
     * (0, as oit_scan_init leaves it: the nonzero ones). */
    uint32_t over;
} oit_scan;

typedef struct oit_scan_result {
    uint64_t total;
    uint32_t max;
    /* Elements greater than oit_scan.over (32-bit: exact for up to 2^32
     * elements, more than one binding's pixels). */
    uint32_t over;
} oit_scan_result;

/* pc: where its programs are built through (program_cache.h; NULL: compiled). */
oit_status oit_scan_init(oit_scan *s, oit_program_cache *pc, oit_error *err);
/* Its programs, for the offline check (glsl_program.h). */
void oit_scan_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_scan_release(oit_scan *s);
/* Scans buf[0..n) in place (exclusive) and reads back total, maximum and over;
 * with res NULL reads nothing back, so that the host does not wait for
 * the GPU (the totals stay in s->totals); the read-back is a wait counted
 * on waits (host_wait.h; NULL: not counted). */
oit_status oit_scan_run(oit_scan *s, GLuint buf, uint64_t n, oit_scan_result *res,
                        oit_host_waits *waits, oit_error *err);
uint64_t oit_scan_bytes(const oit_scan *s);

#ifdef __cplusplus
}
#endif
#endif
