/* What liboit's part-file tests (test_liboit, test_liboit_depth) open first:
 * the GL context, and the file their command line names twice, as liboit's
 * scene (what is tested) and as a part file (what DFB, the reference, reads
 * directly). */
#ifndef OIT_TESTS_LIBOIT_PART_SCENE_H
#define OIT_TESTS_LIBOIT_PART_SCENE_H

#include <stdio.h>
#include <stdlib.h>

#include "oit/liboit.h"
#include "oit/partfile.h"
#include "tests/lib/test_gl.h"

/* usage: PROGRAM FILE.oitp. Exits 2 on another command line, 1 when the
 * context or the file cannot be opened (nothing can be checked then). */
static inline oit_gl *open_part_scene(int argc, char **argv, oit_scene **scene, oit_partfile **pf,
                                      oit_scene_info *info)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s FILE.oitp\n", argv[0]);
        exit(2);
    }
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    if (oit_scene_open(argv[1], NULL, scene, &err) != OIT_OK ||
        oit_partfile_open(argv[1], NULL, pf, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        exit(1);
    }
    oit_scene_get_info(*scene, info, &err);
    return gl;
}

#endif
