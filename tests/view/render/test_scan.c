/* The prefix scan (scan_glsl.h) past one dispatch's work groups: GL
 * promises 65535 groups along x, which 2^26 elements in blocks of 1024
 * (an 8192x8192 frame's counts) pass by one. Three checks:
 *   - 2^26 + 1 ones on this driver's own limit: the total, the maximum and
 *     sampled prefixes (the scan would fail with GL_INVALID_VALUE if it
 *     dispatched them at once);
 *   - random counts with the groups of one dispatch lowered to 3 and to 1,
 *     so that every level takes several dispatches: every prefix, the
 *     total, the maximum and the elements over 8 as the CPU has them;
 *   - the same with the driver's limit (one dispatch a level). */
#include <stdio.h>
#include <stdlib.h>

#include "view/render/gl/scan_glsl.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

static GLuint upload(const uint32_t *v, uint64_t n)
{
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferData(buf, (GLsizeiptr)(n * 4), v, GL_DYNAMIC_COPY);
    return buf;
}

static void check_random(GLuint max_groups, uint64_t n)
{
    uint32_t *v = malloc(n * 4), *got = malloc(n * 4);
    uint32_t r = 99u, mx = 0, lng = 0;
    uint64_t total = 0;
    for (uint64_t i = 0; i < n; i++) {
        r = r * 1664525u + 1013904223u;
        v[i] = (r >> 16) % 7 == 0 ? (r >> 8) % 64 : (r >> 8) % 5;
    }
    GLuint buf = upload(v, n);
    oit_scan s;
    oit_error err = {0};
    CHECK(oit_scan_init(&s, NULL, &err) == OIT_OK, "%s", err.message);
    if (max_groups)
        s.max_groups = max_groups;
    s.over = 8; /* the deep elements: a seventh, of up to 63 */
    oit_scan_result res = {0};
    CHECK(oit_scan_run(&s, buf, n, &res, NULL, &err) == OIT_OK, "%s", err.message);
    glGetNamedBufferSubData(buf, 0, (GLsizeiptr)(n * 4), got);
    uint64_t bad = 0, first_bad = n;
    for (uint64_t i = 0; i < n; i++) {
        if (got[i] != (uint32_t)total && bad++ == 0)
            first_bad = i;
        total += v[i];
        mx = v[i] > mx ? v[i] : mx;
        lng += v[i] > s.over;
    }
    printf("%llu elements, %u groups a dispatch: total %llu (%llu), max %u (%u), over %u (%u), "
           "%llu prefixes wrong\n",
           (unsigned long long)n, s.max_groups, (unsigned long long)res.total,
           (unsigned long long)total, res.max, mx, res.over, lng,
           (unsigned long long)bad);
    CHECK(bad == 0, "%llu prefixes wrong, the first at %llu: %u, want the sum before it",
          (unsigned long long)bad, (unsigned long long)first_bad,
          first_bad < n ? got[first_bad] : 0);
    CHECK(res.total == total && res.max == mx && res.over == lng,
          "total %llu max %u long %u, want %llu %u %u", (unsigned long long)res.total, res.max,
          res.over, (unsigned long long)total, mx, lng);
    oit_scan_release(&s);
    glDeleteBuffers(1, &buf);
    free(v);
    free(got);
}

/* 2^26 + 1 ones: 65537 blocks at the first level. */
static void check_past_one_dispatch(void)
{
    const uint64_t n = (1ull << 26) + 1;
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferData(buf, (GLsizeiptr)(n * 4), NULL, GL_DYNAMIC_COPY);
    static const GLuint one = 1;
    glClearNamedBufferData(buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &one);
    oit_scan s;
    oit_error err = {0};
    CHECK(oit_scan_init(&s, NULL, &err) == OIT_OK, "%s", err.message);
    oit_scan_result res = {0};
    oit_status st = oit_scan_run(&s, buf, n, &res, NULL, &err);
    CHECK(st == OIT_OK, "%llu elements: %s", (unsigned long long)n, err.message);
    const uint64_t at[] = {
        0, 1, 1023, 1024, 65535ull * 1024 - 1, 65535ull * 1024, 65536ull * 1024, n - 1};
    for (size_t i = 0; st == OIT_OK && i < sizeof at / sizeof *at; i++) {
        GLuint v = 0;
        glGetNamedBufferSubData(buf, (GLintptr)(at[i] * 4), 4, &v);
        CHECK(v == at[i], "prefix %llu is %u", (unsigned long long)at[i], v);
    }
    printf("%llu ones (%u groups a dispatch here): total %llu, max %u\n", (unsigned long long)n,
           s.max_groups, (unsigned long long)res.total, res.max);
    CHECK(st != OIT_OK || (res.total == n && res.max == 1), "total %llu max %u, want %llu 1",
          (unsigned long long)res.total, res.max, (unsigned long long)n);
    oit_scan_release(&s);
    glDeleteBuffers(1, &buf);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    check_past_one_dispatch();
    check_random(3, 1024 * 1024 * 3 + 517); /* 3 levels: 3073, 4, 1 blocks */
    check_random(1, 1024 * 9 + 5);
    check_random(0, 1024 * 1024 * 3 + 517);
    oit_gl_destroy(gl);
    return test_verdict();
}
