/* Output-path checks (paths.h). */
#include "tools/common/paths.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int oit_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (!a || !b || stat(a, &sa) != 0 || stat(b, &sb) != 0)
        return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

static oit_status check_not_input(const char *out, const char *what, const char *const *inputs,
                                  size_t n, oit_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (inputs[i] && oit_same_file(out, inputs[i]))
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: %s would replace the input %s (the same file); "
                                 "choose another name", out, what, inputs[i]);
    return OIT_OK;
}

static oit_status check_named(const char *out, const char *what, oit_error *err)
{
    if (!out || !*out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: the path is empty",
                             what ? what : "output");
    return OIT_OK;
}

/* Opening an existing file for writing (no O_TRUNC) proves it writable and
 * leaves it as it was; a new file is created and removed again. */
static oit_status probe_file(const char *out, oit_error *err)
{
    int fd = open(out, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
        close(fd);
        unlink(out);
        return OIT_OK;
    }
    if (errno == EEXIST && (fd = open(out, O_WRONLY | O_CLOEXEC)) >= 0) {
        close(fd);
        return OIT_OK;
    }
    return oit_error_set(err, OIT_ERR_IO, "%s: cannot create: %s", out, strerror(errno));
}

oit_status oit_output_check(const char *out, const char *what, const char *const *inputs,
                            size_t n, oit_error *err)
{
    oit_status s = check_named(out, what, err);
    if (s)
        return s;
    struct stat st;
    size_t len = strlen(out);
    if (out[len - 1] == '/' || (stat(out, &st) == 0 && S_ISDIR(st.st_mode)))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s is a folder, not a file name", out,
                             what ? what : "output");
    if ((s = check_not_input(out, what ? what : "output", inputs, n, err)))
        return s;
    return probe_file(out, err);
}

oit_status oit_output_dir_check(const char *dir, const char *what, const char *const *inputs,
                                size_t n, int *created, oit_error *err)
{
    if (created)
        *created = 0;
    oit_status s = check_named(dir, what, err);
    if (s)
        return s;
    struct stat st;
    if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s is a file, not a folder", dir,
                             what ? what : "output");
    if ((s = check_not_input(dir, what ? what : "output", inputs, n, err)))
        return s;
    if (mkdir(dir, 0777) == 0) {
        if (created)
            *created = 1;
    } else if (errno != EEXIST) {
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create folder: %s", dir, strerror(errno));
    }
    if (access(dir, W_OK | X_OK) != 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write into folder: %s", dir,
                             strerror(errno));
    return OIT_OK;
}

oit_status oit_output_reserve_numbered(const char *prefix, const char *ext, int *next,
                                       char *out, size_t cap, oit_error *err)
{
    for (int i = *next > 0 ? *next : 0; i < 1000000; i++) {
        int len = snprintf(out, cap, "%s_%03d.%s", prefix, i, ext);
        if (len < 0 || (size_t)len >= cap)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s_%03d.%s: name too long", prefix, i,
                                 ext);
        int fd = open(out, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            *next = i + 1;
            return OIT_OK;
        }
        if (errno != EEXIST)
            return oit_error_set(err, OIT_ERR_IO, "%s: cannot create: %s", out, strerror(errno));
    }
    return oit_error_set(err, OIT_ERR_IO, "%s_NNN.%s: every number up to 999999 is taken",
                         prefix, ext);
}
