/* Small GL helpers shared by the GL methods: program building whose errors
 * carry the driver's info log, a GL error check that names the failed call,
 * buffer allocation that reports its size, and a wall-clock timer. All need
 * a current GL 4.5 context; none keeps state. */
#ifndef OIT_RENDER_GL_UTIL_H
#define OIT_RENDER_GL_UTIL_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <stddef.h>
#include <stdint.h>

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A C constant spelled into GLSL source: "#define N " OIT_GLSL_STR(C_N). */
#define OIT_GLSL_STR_(x) #x
#define OIT_GLSL_STR(x) OIT_GLSL_STR_(x)

/* Builds a vertex+fragment program from NULL-terminated lists of source
 * strings (concatenated, as glShaderSource does). 'what' names the program
 * in the error, which quotes the info log. */
oit_status oit_gl_program_graphics(const char *what, const char *const *vs,
                                   const char *const *fs, GLuint *out, oit_error *err);
oit_status oit_gl_program_compute(const char *what, const char *const *cs, GLuint *out,
                                  oit_error *err);
/* Either of the above (cs set: compute, vs and fs unread), with
 * GL_PROGRAM_BINARY_RETRIEVABLE_HINT set before the link where retrievable
 * (program_cache.h). */
oit_status oit_gl_program_build(const char *what, const char *const *vs,
                               const char *const *fs, const char *const *cs, int retrievable,
                               GLuint *out, oit_error *err);

/* OIT_OK when glGetError reports nothing; otherwise OIT_ERR_GL naming 'call'
 * and the error (later errors are drained so they do not blame the next
 * call). */
oit_status oit_gl_check(const char *call, oit_error *err);

/* Creates *fbo, a framebuffer without attachments yet, and when
 * samples_query is set a GL_SAMPLES_PASSED query there; errors name 'what'. */
oit_status oit_gl_framebuffer_create(GLuint *fbo, GLuint *samples_query, const char *what,
                                     oit_error *err);

/* Makes *buf a buffer of at least 'bytes' (GL_DYNAMIC_COPY), keeping *cap in
 * bytes; when it must grow it allocates max(bytes, 1.5 * *cap rounded up to
 * 16 bytes) so repeated growth is geometric and a whole-buffer clear of
 * 32-bit words stays valid. Contents are not preserved. */
oit_status oit_gl_buffer_reserve(GLuint *buf, uint64_t *cap, uint64_t bytes,
                                 const char *what, oit_error *err);
/* New GL storage holds garbage (the spec promises nothing; llvmpipe happens
 * to zero it, NVIDIA does not). With OIT_GL_POISON=1 in the environment
 * (the test suite sets it; read here alone) every buffer and texture the
 * methods allocate is filled with 0xffc00001 words, a NaN as float, right
 * after allocation, so that code that reads before it writes shows on
 * llvmpipe too; without it these do nothing. */
void oit_gl_poison_buffer(GLuint buf);
void oit_gl_poison_texture(GLuint tex, GLenum format);
/* Deletes *buf (0 is fine) and sets *buf and *cap to 0. */
void oit_gl_buffer_release(GLuint *buf, uint64_t *cap);

/* Reads w*h items of 'item' bytes stored in GL row order (bottom row
 * first) into dst, top row first: from buffer obj, or from level 0 of
 * texture obj as RGBA floats (item 16). Errors name 'what'. */
oit_status oit_gl_read_rows(GLuint obj, int is_texture, int w, int h, size_t item, void *dst,
                            const char *what, oit_error *err);

/* OIT_ERR_NOMEM naming 'what' when one shader storage block cannot span
 * 'bytes' on this driver (GL_MAX_SHADER_STORAGE_BLOCK_SIZE). */
oit_status oit_gl_check_ssbo_size(uint64_t bytes, const char *what, oit_error *err);
/* GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one storage buffer binding
 * may span, which bounds what a capture stores in one pass. */
uint64_t oit_gl_ssbo_max_bytes(void);

/* GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT (16 where the driver reports
 * none): what every storage binding's offset must be a multiple of. */
uint64_t oit_gl_ssbo_align(void);

/* Workgroups of 'local' threads covering n items. */
GLuint oit_gl_groups(uint64_t n, GLuint local);

/* GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]: the most groups one dispatch may have
 * along x (the spec promises only 65535: a frame of 2^22 pixels in groups
 * of 64 is one more). */
GLuint oit_gl_max_groups_x(void);
/* Dispatches `groups` work groups of prog (current) along x in as many
 * dispatches of at most max_x as it takes, setting prog's uint uniform at
 * group0_loc to each dispatch's first group: the shader's group is
 * gl_WorkGroupID.x + that uniform, never gl_WorkGroupID.x alone. */
void oit_gl_dispatch_x(GLuint prog, GLint group0_loc, uint64_t groups, GLuint max_x);


#ifdef __cplusplus
}
#endif
#endif
