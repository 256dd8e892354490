/* oitbench bus [--bytes B] [--repeat N]: the host-to-device rate, two ways,
 * each timed on the GPU (GL_TIME_ELAPSED around the transfer alone) and on
 * the wall (glFinish'ed), median of N:
 *  - subdata: glNamedBufferSubData from host memory into a GPU-only buffer;
 *  - mapped copy: the streamer's path, a persistently mapped coherent
 *    buffer written by the CPU (not timed), then glCopyNamedBufferSubData
 *    into a GPU-only buffer (the residency cache's fill).
 * GB/s are 1e9 bytes a second. No timestamps: the GPU figures are -1 and
 * "timer" says why. */
#include "tools/oitbench/bench_bus.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/args.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"

typedef struct bus_figures {
    double gpu_ms, wall_ms; /* medians; gpu -1: not timed */
} bus_figures;

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* One transfer of `bytes` (copy: from the mapped buffer, else from host),
 * timed both ways. */
static void transfer(int copy, GLuint src, GLuint dst, const void *host, uint64_t bytes,
                     GLuint query, int timed, double *gpu_ms, double *wall_ms)
{
    glFinish();
    double t0 = oit_time_ms();
    if (timed)
        glBeginQuery(GL_TIME_ELAPSED, query);
    if (copy)
        glCopyNamedBufferSubData(src, dst, 0, 0, (GLsizeiptr)bytes);
    else
        glNamedBufferSubData(dst, 0, (GLsizeiptr)bytes, host);
    if (timed)
        glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    *wall_ms = oit_time_ms() - t0;
    GLuint64 ns = 0;
    if (timed)
        glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    *gpu_ms = timed ? (double)ns / 1e6 : -1.0;
}

static bus_figures measure(int copy, GLuint src, GLuint dst, const void *host, uint64_t bytes,
                           int repeat, GLuint query, int timed)
{
    double *g = calloc((size_t)repeat * 2, sizeof *g), *w = g + repeat;
    bus_figures f = {-1.0, -1.0};
    if (!g)
        return f;
    transfer(copy, src, dst, host, bytes, query, timed, &g[0], &w[0]); /* first touch */
    for (int i = 0; i < repeat; i++)
        transfer(copy, src, dst, host, bytes, query, timed, &g[i], &w[i]);
    f.gpu_ms = timed ? median(g, repeat) : -1.0;
    f.wall_ms = median(w, repeat);
    free(g);
    return f;
}

static double gbps(uint64_t bytes, double ms)
{
    return ms > 0 ? (double)bytes / (ms * 1e6) : -1.0;
}

static int usage(const char *why)
{
    fprintf(stderr, "oitbench bus: %s\nusage: oitbench bus [--bytes B] [--repeat N]\n"
            "  --bytes B   bytes a transfer (>= 1M, K/M/G suffix; default 256M)\n"
            "  --repeat N  transfers timed, the median reported (1..1000; default 5)\n", why);
    return 2;
}

int oit_bench_bus_main(int argc, char **argv)
{
    uint64_t bytes = 256ull << 20;
    int repeat = 5;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--bytes") && i + 1 < argc) {
            if (oit_parse_bytes(argv[++i], 1ull << 20, 1ull << 36, &bytes))
                return usage("--bytes: a byte count >= 1M expected");
        } else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) {
            if (oit_parse_int(argv[++i], 1, 1000, &repeat))
                return usage("--repeat: 1..1000 expected");
        } else {
            return usage(argv[i]);
        }
    }
    oit_error err = {0};
    oit_gl *gl = NULL;
    if (oit_gl_create(&(oit_gl_desc){0}, &gl, &err) != OIT_OK) {
        fprintf(stderr, "oitbench bus: %s\n", err.message);
        return 1;
    }
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    int timed = glGetError() == GL_NO_ERROR && bits > 0;
    GLuint buf[3] = {0, 0, 0}, query = 0; /* host-visible source, GPU-only, sub-data target */
    glCreateBuffers(3, buf);
    glGenQueries(1, &query);
    GLbitfield map = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(buf[0], (GLsizeiptr)bytes, NULL, map);
    glNamedBufferStorage(buf[1], (GLsizeiptr)bytes, NULL, 0);
    glNamedBufferStorage(buf[2], (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    void *mapped = glMapNamedBufferRange(buf[0], 0, (GLsizeiptr)bytes, map);
    void *host = malloc(bytes);
    int code = 0;
    if (!mapped || !host || oit_gl_check("oitbench bus: buffers", &err) != OIT_OK) {
        fprintf(stderr, "oitbench bus: %s\n", err.message[0] ? err.message
                                                            : "cannot allocate the buffers");
        code = 1;
    } else {
        memset(host, 0x5a, bytes);
        memcpy(mapped, host, bytes);
        bus_figures sub = measure(0, 0, buf[2], host, bytes, repeat, query, timed);
        bus_figures cp = measure(1, buf[0], buf[1], NULL, bytes, repeat, query, timed);
        printf("{\"renderer\": \"%s\", \"bytes\": %llu, \"repeat\": %d, \"timer\": \"%s\",\n"
               " \"subdata_gpu_gbps\": %.3f, \"subdata_wall_gbps\": %.3f,\n"
               " \"mapped_copy_gpu_gbps\": %.3f, \"mapped_copy_wall_gbps\": %.3f}\n",
               oit_gl_renderer(gl), (unsigned long long)bytes, repeat,
               timed ? "GL_TIME_ELAPSED" : "none (the driver has no timer queries)",
               timed ? gbps(bytes, sub.gpu_ms) : -1.0, gbps(bytes, sub.wall_ms),
               timed ? gbps(bytes, cp.gpu_ms) : -1.0, gbps(bytes, cp.wall_ms));
    }
    free(host);
    if (mapped)
        glUnmapNamedBuffer(buf[0]);
    glDeleteQueries(1, &query);
    glDeleteBuffers(3, buf);
    oit_gl_destroy(gl);
    return code;
}
