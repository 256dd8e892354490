/* How fast this machine decodes a part
 * file's encoded parts (version 5) on one thread, the work the streaming
 * reader thread does per part: decode alone (a part already validated) and
 * decode with every check (a part's first use, oit_partfile_part_load). */
#ifndef OIT_PREPROCESS_DECODE_RATE_H
#define OIT_PREPROCESS_DECODE_RATE_H

#include <stdint.h>

#include "oit/status.h"

typedef struct oit_decode_rate {
    uint64_t parts;
    uint64_t stored_bytes;  /* the encoded streams read            */
    uint64_t decoded_bytes; /* the blobs they decode to            */
    double decode_s;        /* best of the passes, decode only     */
    double checked_s;       /* best of the passes, decode + checks */
} oit_decode_rate;

/* Decodes every part of path `passes` times each way, keeping the best
 * time (the first pass also pages the file in). */
oit_status oit_measure_decode(const char *path, int passes, oit_decode_rate *out,
                              oit_error *err);

#endif
