/* oit_read_isolated (read_isolated.h). */
#define _GNU_SOURCE /* strsignal */
#include "formats/read_isolated.h"

#include <errno.h>
#include <stdarg.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define TRAILER (~(uint64_t)0)

static int write_all(int fd, const void *p, size_t n)
{
    const char *b = p;
    while (n) {
        ssize_t w = write(fd, b, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return 0;
        b += w, n -= (size_t)w;
    }
    return 1;
}

/* 1 read, 0 end of stream before the first byte, -1 short or failed. */
static int read_all(int fd, void *p, size_t n)
{
    char *b = p;
    size_t got = 0;
    while (got < n) {
        ssize_t r = read(fd, b + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return got == 0 && r == 0 ? 0 : -1;
        got += (size_t)r;
    }
    return 1;
}

static oit_status pipe_sink(void *user, const oit_triangle *tris, size_t count, oit_error *err)
{
    int fd = *(const int *)user;
    uint64_t n = count;
    if (write_all(fd, &n, sizeof n) && write_all(fd, tris, count * sizeof *tris))
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_IO, "the reader's pipe closed");
}

_Noreturn static void child(int fd, oit_isolated_read read, void *arg, oit_mesh_info *info)
{
    /* the library's crash must end this process quietly, not run a
     * sanitizer's or a fuzzer's report and hooks that belong to the parent */
    static const int sigs[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
        signal(sigs[i], SIG_DFL);
    oit_error err = {0};
    oit_status s = read(arg, pipe_sink, &fd, info, &err);
    uint64_t mark = TRAILER;
    int ok = write_all(fd, &mark, sizeof mark) && write_all(fd, &s, sizeof s) &&
             write_all(fd, info, sizeof *info) && write_all(fd, &err, sizeof err);
    _exit(ok ? 0 : 1);
}

typedef struct job {
    const char *name, *library;
    size_t chunk_cap;
    oit_triangle_sink sink;
    void *user;
    oit_mesh_info *info;
    oit_error *err;
    pid_t pid;
} job;

static oit_status fail(const job *j, oit_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static oit_status fail(const job *j, oit_status s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    oit_error_setv(j->err, s, fmt, ap);
    va_end(ap);
    oit_error_prefix(j->err, j->name);
    return s;
}

/* Waits for the child (killed first when kill_it); a child ended by a
 * signal turns an OK s into the crash's error. */
static oit_status reap(const job *j, int kill_it, oit_status s)
{
    if (kill_it)
        kill(j->pid, SIGKILL);
    int ws = 0;
    while (waitpid(j->pid, &ws, 0) < 0 && errno == EINTR) {
    }
    if (s == OIT_OK && WIFSIGNALED(ws)) {
        return fail(j, OIT_ERR_FORMAT, "%s crashed reading it (signal %d, %s)", j->library,
                    WTERMSIG(ws), strsignal(WTERMSIG(ws)));
    }
    return s;
}

/* The child died before its trailer or inside a chunk: its crash, or what. */
static oit_status cut_short(const job *j, const char *what)
{
    oit_status s = reap(j, 0, OIT_OK);
    return s == OIT_OK ? fail(j, OIT_ERR_FORMAT, "%s", what) : s;
}

static oit_status trailer(const job *j, int fd)
{
    oit_status s;
    oit_error err;
    oit_mesh_info info;
    if (read_all(fd, &s, sizeof s) != 1 || read_all(fd, &info, sizeof info) != 1 ||
        read_all(fd, &err, sizeof err) != 1)
        return reap(j, 1, fail(j, OIT_ERR_FORMAT, "the reader's result is cut short"));
    err.message[sizeof err.message - 1] = '\0';
    *j->info = info;
    if (s != OIT_OK && j->err)
        *j->err = err;
    return reap(j, 0, s);
}

static oit_status parent(const job *j, int fd)
{
    oit_triangle *buf = NULL;
    size_t cap = 0;
    oit_status s = OIT_OK;
    for (;;) {
        uint64_t n = 0;
        int r = read_all(fd, &n, sizeof n);
        if (r <= 0) {
            s = cut_short(j, "the reader ended without a result");
            break;
        }
        if (n == TRAILER) {
            s = trailer(j, fd);
            break;
        }
        if (n == 0 || n > j->chunk_cap) {
            s = reap(j, 1, fail(j, OIT_ERR_FORMAT, "the reader sent a chunk of %llu triangles",
                                (unsigned long long)n));
            break;
        }
        if (n > cap) {
            oit_triangle *b = realloc(buf, (size_t)n * sizeof *buf);
            if (!b) {
                s = reap(j, 1, fail(j, OIT_ERR_NOMEM, "out of memory for a chunk"));
                break;
            }
            buf = b, cap = (size_t)n;
        }
        if (read_all(fd, buf, (size_t)n * sizeof *buf) != 1) {
            s = cut_short(j, "the reader ended inside a chunk");
            break;
        }
        s = j->sink(j->user, buf, (size_t)n, j->err);
        if (s != OIT_OK) {
            s = reap(j, 1, s);
            break;
        }
    }
    free(buf);
    return s;
}

oit_status oit_read_isolated(const char *name, const char *library, size_t chunk_cap,
                             oit_isolated_read read, void *arg, oit_triangle_sink sink,
                             void *user, oit_mesh_info *info, oit_error *err)
{
    job j = {name ? name : "(memory)", library, chunk_cap, sink, user, info, err, 0};
    int fds[2];
    if (pipe(fds) != 0)
        return fail(&j, OIT_ERR_IO, "cannot make a pipe for the %s reader: %s", library,
                    strerror(errno));
    fflush(NULL); /* nothing buffered is written twice */
    j.pid = fork();
    if (j.pid < 0) {
        int e = errno;
        close(fds[0]);
        close(fds[1]);
        return fail(&j, OIT_ERR_IO, "cannot start the %s reader: %s", library, strerror(e));
    }
    if (j.pid == 0) {
        close(fds[0]);
        child(fds[1], read, arg, info);
    }
    close(fds[1]);
    oit_status s = parent(&j, fds[0]);
    close(fds[0]);
    return s;
}
