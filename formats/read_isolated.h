/* A reader run in a child process (read_isolated.c), for readers over
 * libraries that crash on malformed files: assimp 5.2 (its FBX, 3MF and IFC
 * importers) and Open CASCADE 7.6 (its STEP translation). No check of ours
 * can run before their parsers, so the child reads and sends each chunk of
 * triangles through a pipe, then a trailer with the status, the info and
 * the error; the parent hands the chunks to the caller's sink as they come.
 * A child that dies is a format error naming the library and the signal,
 * never a crash of the caller. Messages the reader prints (notes) go to the
 * shared stderr. */
#ifndef OIT_FORMATS_READ_ISOLATED_H
#define OIT_FORMATS_READ_ISOLATED_H

#include <stddef.h>

#include "oit/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The read the child runs: it delivers triangles to sink(sink_user, ...)
 * in chunks of at most the chunk_cap given to oit_read_isolated, fills
 * *info and, on failure, *err. */
typedef oit_status (*oit_isolated_read)(void *arg, oit_triangle_sink sink, void *sink_user,
                                        oit_mesh_info *info, oit_error *err);

/* Runs read(arg, ...) in a child. name: the input, which errors begin with;
 * library: who crashed, for the message ("assimp", "Open CASCADE").
 * chunk_cap: the largest chunk the read delivers (a larger one from the
 * child is a format error). *info is the read's on success (the caller
 * initialises it: a failed start leaves it as it was). */
oit_status oit_read_isolated(const char *name, const char *library, size_t chunk_cap,
                             oit_isolated_read read, void *arg, oit_triangle_sink sink,
                             void *user, oit_mesh_info *info, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
