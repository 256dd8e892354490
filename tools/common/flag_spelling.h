/* liboit names its settings by their fields ("oit_renderer_desc.upload_budget
 * = 1000: expected ..."), as a library should; a command line calls them by
 * its flags. This is the one table between the two spellings, and the
 * rewrite of liboit's messages and figures into the second, applied where
 * a tool prints them. A field with no flag (binding_limit, frames) keeps
 * its name. */
#ifndef OIT_TOOLS_COMMON_FLAG_SPELLING_H
#define OIT_TOOLS_COMMON_FLAG_SPELLING_H

#include <stddef.h>

#include "oit/status.h"

/* The flag that sets field ("oit_renderer_desc.pack": "--pack"; the value
 * "OIT_RENDER_CACHE_OFF": "off"); field itself where none does (and NULL
 * for NULL). */
const char *oit_flag_of(const char *field);
/* Every field in msg (NUL-terminated, cap bytes of room) rewritten as its
 * flag, "field = value" as "flag value", the command line's own form;
 * cut at cap - 1 bytes where the flags are longer than the fields. */
void oit_flags_spell(char *msg, size_t cap);
void oit_flags_spell_error(oit_error *err);

#endif
