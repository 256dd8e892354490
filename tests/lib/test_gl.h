/* The headless GL context a GL test opens before anything else. */
#ifndef OIT_TESTS_TEST_GL_H
#define OIT_TESTS_TEST_GL_H

#include <stdio.h>
#include <stdlib.h>

#include "render/gl_context.h"

/* The context (EGL; surfaceless under ctest), its renderer printed so that a
 * log says which driver its figures come from. Without one nothing can be
 * checked: the test exits 1 here, naming the reason. */
static inline oit_gl *test_gl_open(void)
{
    oit_error err = {0};
    oit_gl *gl = NULL;
    if (oit_gl_create(NULL, &gl, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: context: %s\n", err.message);
        exit(1);
    }
    printf("renderer: %s\n", oit_gl_renderer(gl));
    return gl;
}

#endif
