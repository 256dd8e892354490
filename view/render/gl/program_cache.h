/* Linked GL programs kept across processes (GL 4.1 program binaries), so a
 * one-image run does not pay the driver's compiler for programs an earlier
 * run already built. The one owner of the setting "where": a folder given
 * by the caller (liboit's oit_renderer_desc.program_cache), else OIT_PROGRAM_CACHE from the environment, else
 * $XDG_CACHE_HOME/oit, else $HOME/.cache/oit; the word "off" (either way)
 * turns it off. A file a program is named by a hash of GL_VENDOR,
 * GL_RENDERER, GL_VERSION and the full source of every stage; it carries a
 * second, independent hash of the same key and a checksum of the binary.
 * An entry that is missing, short, of another key, of a wrong checksum or
 * that the driver refuses (GL_LINK_STATUS false after glProgramBinary) is
 * compiled from source and written again (a temporary file renamed over
 * it); a folder that cannot be made, read or written just means no cache:
 * the cache never fails a build that compiling would pass. Needs a current
 * GL context; an object serves the context it was opened in. */
#ifndef OIT_RENDER_GL_PROGRAM_CACHE_H
#define OIT_RENDER_GL_PROGRAM_CACHE_H

#include "view/render/gl/gl_util.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_program_cache oit_program_cache;

/* What a cache did since it was opened. */
typedef struct oit_program_cache_stats {
    unsigned hits;     /* programs loaded from an entry */
    unsigned misses;   /* no entry: compiled */
    unsigned rejected; /* an entry was there but not ours, not whole or not this
                          program's (its header, size or checksum): compiled */
    unsigned refused;  /* an entry passed those checks but the driver refused it
                          (GL_LINK_STATUS false after glProgramBinary): compiled */
    unsigned written;  /* entries written */
} oit_program_cache_stats;

/* The folder `asked` names (NULL: the default above; "off": none) into
 * out (size bytes); "" when there is none. Reads the environment only. */
void oit_program_cache_folder(const char *asked, char *out, size_t size);

/* A cache on the folder `asked` resolves to; *out is NULL when there is
 * none: off, no folder, or a driver with no program binary format
 * (GL_NUM_PROGRAM_BINARY_FORMATS 0). Fails only for lack of memory. */
oit_status oit_program_cache_open(const char *asked, oit_program_cache **out, oit_error *err);
void oit_program_cache_close(oit_program_cache *pc);
/* The folder in use ("" for NULL). */
const char *oit_program_cache_dir(const oit_program_cache *pc);
oit_program_cache_stats oit_program_cache_get_stats(const oit_program_cache *pc);

/* An entry is a 40-byte header (magic "OITPBIN1", the key's second hash,
 * the key's length, this checksum of the binary, all uint64 in the host's
 * order; then the binary's format and length, uint32) and the binary. The
 * checksum, for tests that forge an entry the driver must refuse. */
uint64_t oit_program_cache_checksum(const void *data, size_t n);

/* As oit_gl_program_graphics (cs NULL) or oit_gl_program_compute (vs and fs
 * NULL), through pc's entries; pc NULL compiles. */
oit_status oit_program_cache_build(oit_program_cache *pc, const char *what,
                                   const char *const *vs, const char *const *fs,
                                   const char *const *cs, GLuint *out, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
