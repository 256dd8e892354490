/* --stats FILE.json for oitstream: the run (model, triangles, renderer,
 * size) and one object per frame with its figures and camera. */
#ifndef OIT_OITSTREAM_STATS_JSON_H
#define OIT_OITSTREAM_STATS_JSON_H

#include <stddef.h>

#include "view/render/gl/gpu_timer.h"
#include "view/render/image/view.h"
#include "oit/liboit.h"

typedef struct oit_stats_frame {
    const char *method;
    char view[512]; /* the camera as --view accepts it (with znear,zfar) */
    char clip[512]; /* the section planes as --clip takes them, ';' between; "" none */
    oit_frame_stats st;
    int has_stream;       /* the stream method's figures follow (liboit's) */
    oit_draw_stats stream;
    float epsilon;        /* the early termination the stream ran with */
    int has_gpu;       /* the GPU timer's figures of this frame follow */
    oit_gpu_times gpu; /* view/render/gl/gpu_timer.h */
} oit_stats_frame;

typedef struct oit_stats_run {
    const char *model;
    unsigned long long triangles;
    const char *renderer;
    int width, height;
    const oit_stats_frame *frames;
    size_t frame_count;
    int opaque;      /* opaque triangles on (oit_shading_opaque) */
    int see_through; /* --see-through */
    const char *gpu_absent; /* why no frame has gpu_ms; NULL: timed */
} oit_stats_run;

/* The camera in --view syntax, round-trippable (%.9g). */
void oit_stats_format_view(const oit_camera *cam, const double origin[3], char *buf, size_t cap);

/* The section planes in --clip syntax (file coordinates), ';' between. */
void oit_stats_format_clip(const oit_clip *clip, const double origin[3], char *buf, size_t cap);

oit_status oit_stats_json_write(const char *path, const oit_stats_run *run, oit_error *err);

#endif
