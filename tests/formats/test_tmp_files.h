/* The files the reader tests write and read back: under $OIT_TEST_TMP
 * (else /tmp), a failed write ends the test. */
#ifndef OIT_TESTS_FORMATS_TEST_TMP_FILES_H
#define OIT_TESTS_FORMATS_TEST_TMP_FILES_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* name's path in the test's folder, in a buffer the next call overwrites. */
static inline const char *tmp_path(const char *name)
{
    static char path[2048];
    const char *t = getenv("OIT_TEST_TMP");
    snprintf(path, sizeof path, "%s/%s", t ? t : "/tmp", name);
    return path;
}

static inline void write_bytes(const char *name, const void *data, size_t n)
{
    FILE *f = fopen(tmp_path(name), "wb");
    if (!f || fwrite(data, 1, n, f) != n) {
        printf("cannot write %s\n", tmp_path(name));
        exit(1);
    }
    fclose(f);
}

static inline void write_text(const char *name, const char *text)
{
    write_bytes(name, text, strlen(text));
}

#endif
