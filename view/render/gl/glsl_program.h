/* A GL program as data: its stages as lists of GLSL pieces (the files of
 * view/render/<folder>/glsl/, embedded at build time, and a few C strings of
 * #defines), assembled in one place, built by GL, and listed whole for
 * the offline check (tests/view/render/test_glsl_offline.sh: glslang compiles
 * every variant the renderer can build, on a machine without a GPU). */
#ifndef OIT_RENDER_GLSL_PROGRAM_H
#define OIT_RENDER_GLSL_PROGRAM_H

#include "view/render/gl/gl_util.h"
#include "view/render/gl/program_cache.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A method's programs as a table, one entry each: a vertex + fragment
 * program (oit_glsl_vertex; oit_glsl_fragment_gen, then fs) when fs[0] is
 * set and vs[0] is not; vs then fs as they are, without the fragment
 * library, when both are set (a full-screen pass); else a compute program
 * of cs. Every stage starts with oit_glsl_version; a list ends at its first
 * NULL (or after OIT_GLSL_PARTS_MAX). 'what' names the program in errors. */
#define OIT_GLSL_PARTS_MAX 8
typedef struct oit_glsl_program {
    const char *what;
    const char *fs[OIT_GLSL_PARTS_MAX];
    const char *cs[OIT_GLSL_PARTS_MAX];
    const char *vs[OIT_GLSL_PARTS_MAX];
} oit_glsl_program;

/* A program's stages, as GL compiles them. */
typedef enum oit_glsl_stage { OIT_GLSL_VERTEX, OIT_GLSL_FRAGMENT, OIT_GLSL_COMPUTE } oit_glsl_stage;
/* The sources of p's stage into src (NULL-terminated, at most
 * OIT_GLSL_SOURCES_MAX entries with the NULL); 0 when p has no such stage,
 * else 1. The one assembly of a program's text: what GL compiles
 * (oit_glsl_programs_build) and what the offline check compiles
 * (tests/view/render/test_glsl_offline.sh) come from here. */
#define OIT_GLSL_SOURCES_MAX (OIT_GLSL_PARTS_MAX + 3)
int oit_glsl_program_stage(const oit_glsl_program *p, oit_glsl_stage stage, const char **src);

/* A 64-bit hash of p's assembled stages (FNV-1a over each stage's tag
 * and text): names a program across the built and the offline lists. */
uint64_t oit_glsl_program_hash(const oit_glsl_program *p);

/* Every program a module can build, each variant once (the offline check,
 * tests/view/render/glsl_variants.c, compiles all of them): a module that builds
 * programs has an oit_<module>_glsl_variants(visit, user) that calls
 * visit(user, p) for each, from the same tables or functions its create
 * builds from, so the two cannot drift. p lives only during the call. */
typedef void oit_glsl_visit(void *user, const oit_glsl_program *p);
/* view/render/gl's own: the prefix sum's two passes (scan_glsl.h) and the
 * multi-draw gate (gpu_mesh.h). */
void oit_gl_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_gpu_draws_glsl_variants(oit_glsl_visit *visit, void *user);

/* Builds out[i] from table[i] for i in [0, n), in order, up to the first
 * failure (what was built stays in out for oit_glsl_programs_delete),
 * through pc's entries (NULL: compiled). Where the environment names a
 * file in OIT_GLSL_LOG (the test suite does), appends a line to it for
 * each program built, "HASH what", so that a test can check that every
 * program the suite built is one the offline check compiled
 * (tests/view/render/test_glsl_offline.sh). */
oit_status oit_glsl_programs_build(oit_program_cache *pc, const oit_glsl_program *table, int n, GLuint *out,
                                   oit_error *err);
/* Deletes progs[0..n) (0 is fine) and sets them to 0. */
void oit_glsl_programs_delete(GLuint *progs, int n);
/* The state of a module of one program (opaque keys, opaque tiles,
 * saturated tiles): `size` bytes, zeroed, whose first member is the GLuint
 * that p is built into. NULL with *st set when memory (the error naming
 * what) or the build fails; nothing is left allocated then. */
void *oit_glsl_module_create(size_t size, const oit_glsl_program *p, const char *what,
                             oit_status *st, oit_error *err);

#ifdef __cplusplus
}
#endif

#endif
