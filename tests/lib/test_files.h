/* The tests' files: where scratch files go, and whole-file reads for tests
 * that compare files byte for byte. */
#ifndef OIT_TESTS_TEST_FILES_H
#define OIT_TESTS_TEST_FILES_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* name's path in the tests' scratch folder: $OIT_TEST_TMP, else /tmp. */
static inline void test_tmp_path(char *path, size_t size, const char *name)
{
    const char *tmp = getenv("OIT_TEST_TMP");
    snprintf(path, size, "%s/%s", tmp ? tmp : "/tmp", name);
}

/* The file's bytes (free them), or NULL with *size = 0 when it cannot be
 * read whole. */
static inline uint8_t *test_read_file(const char *path, size_t *size)
{
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *b = n >= 0 ? malloc(n > 0 ? (size_t)n : 1) : NULL;
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    if (b)
        *size = (size_t)n;
    return b;
}

#endif
