/* Writes a conversion's figures (convert.h) as one JSON object to a file. */
#ifndef OIT_PREPROCESS_STATS_JSON_H
#define OIT_PREPROCESS_STATS_JSON_H

#include "oit/status.h"
#include "prepare/convert/convert.h"

oit_status oit_convert_stats_write_json(const char *path, const oit_convert_options *o,
                                        const oit_convert_stats *s, oit_error *err);

#endif
