/* What liboit's part-file tests (test_liboit, _image, _depth, _sizes) open first:
 * the GL context, and the file their command line names twice, as liboit's
 * scene (what is tested) and as a part file (what DFB, the reference, reads
 * directly). */
#ifndef OIT_TESTS_LIBOIT_PART_SCENE_H
#define OIT_TESTS_LIBOIT_PART_SCENE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "oit/partfile.h"
#include "tests/lib/test_gl.h"

typedef struct part_scene {
    oit_gl *gl;
    oit_scene *scene;
    oit_partfile *pf;
    oit_scene_info info;
} part_scene;

/* usage: PROGRAM FILE.oitp. Exits 2 on another command line, 1 when the
 * context or the file cannot be opened (nothing can be checked then). */
static inline part_scene open_part_scene(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s FILE.oitp\n", argv[0]);
        exit(2);
    }
    part_scene ps = {.gl = test_gl_open()};
    oit_error err = {0};
    if (oit_scene_open(argv[1], NULL, &ps.scene, &err) != OIT_OK ||
        oit_partfile_open(argv[1], NULL, &ps.pf, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        exit(1);
    }
    oit_scene_get_info(ps.scene, &ps.info, &err);
    return ps;
}

/* The triangles of m as the caller's arrays of oit_scene_create_mesh: a
 * soup, 3 positions (*pos) and 3 RGBA colours (*rgba) a triangle, allocated
 * here for the caller to free. */
static inline void mesh_soup(const oit_mesh *m, float **pos, uint8_t **rgba)
{
    *pos = malloc(m->count * 9 * sizeof **pos);
    *rgba = malloc(m->count * 12);
    if (!*pos || !*rgba) {
        fprintf(stderr, "FAIL: no memory for %zu triangles\n", m->count);
        exit(1);
    }
    for (size_t t = 0; t < m->count; t++)
        for (int c = 0; c < 3; c++) {
            memcpy(*pos + (t * 3 + c) * 3, m->tris[t].v[c].pos, 12);
            memcpy(*rgba + (t * 3 + c) * 4, m->tris[t].v[c].rgba, 4);
        }
}

#endif
