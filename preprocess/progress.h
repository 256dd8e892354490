/* A one-line progress bar per stage on stderr, drawn only when enabled (the
 * tool enables it when stderr is a terminal). Updates are cheap when the
 * percentage has not changed. Not thread-safe: one thread reports. */
#ifndef OIT_PREPROCESS_PROGRESS_H
#define OIT_PREPROCESS_PROGRESS_H

#include <stdint.h>

typedef struct oit_progress {
    const char *stage;
    uint64_t total;
    int enabled;
    int shown; /* last percentage drawn, -1 before the first */
} oit_progress;

void oit_progress_start(oit_progress *p, const char *stage, uint64_t total, int enabled);
void oit_progress_update(oit_progress *p, uint64_t done);
void oit_progress_end(oit_progress *p);

#endif
