/* Transparent gzip input for the mesh readers (zlib).
 *
 * Compressed meshes (.obj.gz, .stl.gz, a .ply that is really gzip) are common;
 * the readers never see the difference: oit_gz_open wraps a FILE* whose first
 * bytes are the gzip magic (1f 8b) in a stdio stream (fopencookie) that
 * inflates as it is read, so memory stays one input block and zlib's window
 * whatever the file's size. Concatenated members are read in turn; bytes
 * after the last member that are not another member end the stream, as
 * gzip(1) treats them. A corrupt or truncated stream makes the wrapping
 * stream's read fail; oit_gz_message then says why, for the reader's error.
 *
 * oit_gunzip inflates a whole buffer (for the glTF adapter, which parses
 * from memory), under a byte limit.
 */
#ifndef OIT_FORMATS_GZIP_INPUT_H
#define OIT_FORMATS_GZIP_INPUT_H

#include <stddef.h>
#include <stdio.h>

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_gz oit_gz;

/* 1 when the n bytes at b start with the gzip magic. */
int oit_gz_magic(const unsigned char *b, size_t n);

/* Looks at f's first two bytes. Not gzip: *out = NULL, f is left where it
 * was. Gzip: *out is a new read-only stream of the inflated bytes (fclose it
 * before f; it does not close f) and *state its state for oit_gz_message.
 * Fails only when f cannot be rewound, memory runs out or zlib cannot be
 * loaded (liboit loads it at run time: zlib_load.h). */
oit_status oit_gz_open(FILE *f, const char *name, FILE **out, oit_gz **state, oit_error *err);
/* Why the last read failed ("" when it did not): "corrupt data (invalid
 * distance too far back)", "truncated (the file ends inside the stream)". */
const char *oit_gz_message(const oit_gz *g);

/* Inflates all gzip members of in[0, n) into a malloc'ed buffer (*out, *out_n
 * bytes; free it); more than limit bytes is OIT_ERR_NOMEM, a corrupt or
 * truncated stream OIT_ERR_FORMAT, both naming `name` (and, as for
 * oit_gz_open, zlib that cannot be loaded). */
oit_status oit_gunzip(const unsigned char *in, size_t n, size_t limit, const char *name,
                      unsigned char **out, size_t *out_n, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
