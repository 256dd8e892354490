/* The part-file streamer as a method (render/method.h), named "stream": it
 * renders options.stream->partfile (the mesh is then empty) with
 * options.max_layers as K and options.epsilon as its early termination. */
#ifndef OIT_STREAM_STREAM_METHOD_H
#define OIT_STREAM_STREAM_METHOD_H

#include "render/method.h"
#include "stream/streamer.h"

/* The streamer's own options (oit_streamer_desc has their meaning). */
struct oit_stream_options {
    oit_partfile *partfile;
    oit_pack_mode pack;
    oit_capture_kind capture; /* --capture: AUTO (0), STENCIL or ARRAY */
    oit_pack_schedule schedule;
    unsigned long long upload_budget; /* bytes; 0: default */
    unsigned long long slot_budget;   /* capture slots, bytes; 0: default */
    /* residency cache, bytes; 0: OIT_STREAM_CACHE_DEFAULT; OIT_STREAM_CACHE_OFF: none */
    unsigned long long cache_budget;
    int reader_threads; /* oit_streamer_desc.reader_threads */
    unsigned long long gpu_budget; /* ring + cache + capture, bytes; 0: default */
};

extern const oit_method oit_method_stream;

#endif
