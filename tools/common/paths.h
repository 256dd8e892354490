/* Output-path checks every tool runs before it starts the work, so that a
 * typo costs a usage message instead of the user's model or an hour of
 * conversion followed by "cannot create".
 *
 * - oit_output_check: the path is not empty, not a folder, names none of the
 *   inputs (the same file through a symlink or a hard link counts: device
 *   and inode are compared), and its file can be created (tried with a probe
 *   that is removed again; an existing file is opened for writing without
 *   truncation, so it stays intact).
 * - oit_output_dir_check: the same for an output folder (created when
 *   missing, as the tools would create it anyway).
 *
 * Status: OIT_ERR_ARGUMENT (exit 2) for an empty path, a folder where a file
 * is wanted, or an output that is an input; OIT_ERR_IO (exit 1) when the
 * file system refuses. Messages name the path.
 */
#ifndef OIT_COMMON_PATHS_H
#define OIT_COMMON_PATHS_H

#include <stddef.h>

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* inputs: n paths (NULL entries are skipped); what: "output" or the option's
 * name ("--stats"), for messages. */
oit_status oit_output_check(const char *out, const char *what, const char *const *inputs,
                            size_t n, oit_error *err);
/* *created (may be NULL) says whether the folder was made now, so that a
 * tool whose run then fails can remove it again (rmdir: only when empty). */
oit_status oit_output_dir_check(const char *dir, const char *what, const char *const *inputs,
                                size_t n, int *created, oit_error *err);
/* The first free numbered name PREFIX_NNN.EXT (NNN from *next up, three
 * digits or more) in the working folder, created empty with O_EXCL so that
 * no other run (or earlier one) can have it or lose it to this one: out
 * gets the name, *next the number after it. OIT_ERR_IO when the folder
 * refuses or every number up to a million is taken. */
oit_status oit_output_reserve_numbered(const char *prefix, const char *ext, int *next,
                                       char *out, size_t cap, oit_error *err);
/* 1 when a and b name the same existing file (device and inode). */
int oit_same_file(const char *a, const char *b);

#ifdef __cplusplus
}
#endif
#endif
