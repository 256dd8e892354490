/* The headless GL context a GL test opens before anything else. */
#ifndef OIT_TESTS_TEST_GL_H
#define OIT_TESTS_TEST_GL_H

#include <stdio.h>
#include <stdlib.h>

#include "view/render/gl/gl_context.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_partfile.h"

/* The context (EGL; surfaceless under ctest), its renderer printed so that a
 * log says which driver its figures come from. Without one nothing can be
 * checked: the test exits 1 here, naming the reason. */
static inline oit_gl *test_gl_open(void)
{
    oit_error err = {0};
    oit_gl *gl = NULL;
    /* A debug context: test_gl_verdict fails on any error or undefined
     * behaviour the driver reports, even where no figure changed. */
    if (oit_gl_create(&(oit_gl_desc){.debug = 1}, &gl, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: context: %s\n", err.message);
        exit(1);
    }
    printf("renderer: %s\n", oit_gl_renderer(gl));
    return gl;
}

/* For a test run as "TEST FILE.oitp": a plain context (no debug: these
 * tests check byte counts and images, not the driver's messages) and the
 * part file, both open, or the test exits: 2 for another command line, 1
 * naming what failed to open. */
static inline oit_gl *test_gl_open_partfile(int argc, char **argv, oit_partfile **pf)
{
    *pf = test_partfile_arg(argc, argv);
    oit_error err = {0};
    oit_gl *gl = NULL;
    if (oit_gl_create(NULL, &gl, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        oit_partfile_close(*pf);
        exit(1);
    }
    return gl;
}

/* test_verdict, failing too when the driver reported errors or undefined
 * behaviour on gl since the last check; destroys gl. */
static inline int test_gl_verdict(oit_gl *gl)
{
    oit_error err = {0};
    if (oit_gl_debug_check(gl, "GL debug context", &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        test_failures++;
    }
    oit_gl_destroy(gl);
    return test_verdict();
}

#endif
