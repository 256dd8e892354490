/* The part-file streamer as a method (render/method.h), named "stream": it
 * renders the part file of options.source (an oit_stream_options; the mesh
 * is then empty) with options.max_layers as K, options.store_limit as the
 * capture's, and options.threshold, where given, as its early termination
 * (oit_streamer_desc.epsilon). */
#ifndef OIT_STREAM_STREAM_METHOD_H
#define OIT_STREAM_STREAM_METHOD_H

#include "render/method.h"
#include "stream/streamer.h"

/* What oit_method_options.source points to for the stream method: the
 * file and the streamer's own descriptor, zero meaning default
 * (streamer.h; checked with oit_streamer_desc_check at open). */
typedef struct oit_stream_options {
    oit_partfile *partfile;
    oit_streamer_desc desc;
} oit_stream_options;

extern const oit_method oit_method_stream;

/* The streamer's figures of st's last frame; NULL when st is not the stream
 * method. */
const oit_stream_frame_stats *oit_method_stream_stats(const oit_method_state *st);

#endif
