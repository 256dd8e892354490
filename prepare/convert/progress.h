/* Progress of each stage on stderr, in one of two forms the tool picks:
 * - OIT_PROGRESS_BAR (stderr is a terminal): a one-line bar redrawn in
 *   place, cheap when the percentage has not changed;
 * - OIT_PROGRESS_LINES (piped or logged, where \r would pile up): a line
 *   "progress: STAGE  43%  6.2 s" at most every period_s seconds (0: every
 *   5 s), and the stage's 100% line when it printed any, so a log shows a
 *   long conversion moving and a short one stays quiet.
 * Not thread-safe: one thread reports. */
#ifndef OIT_PREPROCESS_PROGRESS_H
#define OIT_PREPROCESS_PROGRESS_H

#include <stdint.h>

typedef enum oit_progress_mode {
    OIT_PROGRESS_OFF = 0,
    OIT_PROGRESS_BAR = 1,
    OIT_PROGRESS_LINES = 2
} oit_progress_mode;

#define OIT_PROGRESS_PERIOD_S 5.0 /* lines mode: seconds between lines by default */

typedef struct oit_progress {
    const char *stage;
    uint64_t total;
    oit_progress_mode mode;
    int shown;       /* last percentage drawn, -1 before the first */
    int seen;        /* last percentage reported (lines mode reads the
                        clock only when it changes) */
    double period_s; /* lines mode */
    double start, last;
    int lines;       /* lines printed for this stage */
} oit_progress;

void oit_progress_start(oit_progress *p, const char *stage, uint64_t total,
                        oit_progress_mode mode, double period_s);
void oit_progress_update(oit_progress *p, uint64_t done);
void oit_progress_end(oit_progress *p);

#endif
