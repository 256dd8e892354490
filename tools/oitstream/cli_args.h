/* oitstream's command line: what the user asked for, validated, with no
 * I/O done yet. Parsing never prints; a usage error comes back as
 * OIT_ERR_ARGUMENT with a one-line message. */
#ifndef OIT_OITSTREAM_CLI_ARGS_H
#define OIT_OITSTREAM_CLI_ARGS_H

#include <stdio.h>

#include "render/image/view.h"
#include "render/capture/capture.h"
#include "stream/pack.h"

typedef struct oit_stream_args {
    int help;
    /* --compare A B */
    int compare;
    const char *compare_a, *compare_b;
    int json;
    float gain;
    const char *mask; /* --mask: figures also outside its non-black pixels */
    /* rendering */
    const char *model;
    const char *method; /* a name from tools/common/methods.h; checked there; NULL:
                           stream for a part file, dfb otherwise */
    int width, height;
    int have_view;
    oit_camera view; /* --view, clip planes 0 unless given */
    const char *view_text; /* --view as given, re-read against the model's origin */
    const char *walk;      /* --walk FILE: a camera path, one view a line */
    float azimuth, elevation;
    float ortho; /* --ortho: view height; -1 "fit": the perspective's framing; 0: none */
    int orbit; /* 0: one view */
    const char *out;
    const char *stats_path;
    oit_shading shading; /* fields the user set; the rest 0 (defaults) */
    int max_layers;
    int show_layers;
    const char *ambiguity_out; /* --ambiguity: mask of ambiguous pixels */
    float ambiguity_px;        /* --ambiguity-px; 0: the reference's 1/64 */
    int quiet;
    oit_pack_mode pack;                /* --pack; 0: auto */
    oit_capture_kind capture;          /* --capture; 0: auto (streamer.h checks it) */
    int schedule_wave;                 /* --schedule: 0 tree (default), 1 wave */
    unsigned long long upload_budget;  /* --upload-budget; 0 (or 0 given): default */
    unsigned long long slot_budget;    /* --slot-budget; 0: default */
    unsigned long long gpu_budget;     /* --gpu-budget; 0: default (oit_streamer_desc.gpu_budget) */
    unsigned long long cache_budget;   /* --cache-budget; 0 (or 0 given): default; OIT_STREAM_CACHE_OFF: off */
    int upload_threads;                /* --upload-threads, as oit_streamer_desc.reader_threads */
    float epsilon;                     /* --epsilon (stream, f2b, guarded); < 0: not given */
    /* --window: the interactive viewer (viewer.h) */
    int window;
    int window_frames;             /* --window-frames N; 0: until quit */
    const char *window_script;     /* --window-script KEYS */
    const char *window_screenshot; /* --window-screenshot PATH */
    int no_overlay;                /* --no-overlay: no status line in the image */
    int preview;                   /* --preview: oit_viewer_preview (viewer.h); 0 auto */
    int still_ms;                  /* --still MS: stillness before the exact frame; 0: 200 */
    int up_axis;                   /* --up x|y|z: 0, 1 (default), 2 */
    /* --clip (repeatable): the planes as checked with origin 0, and their
     * text, re-read against the model's origin (render/image/clip.h) */
    oit_clip clip;
    const char *clip_text[OIT_CLIP_MAX];
    int have_preview;              /* --preview was given */
} oit_stream_args;

oit_status oit_stream_args_parse(int argc, char **argv, oit_stream_args *a, oit_error *err);

/* The --help text; method_list names the methods that exist. */
void oit_stream_usage(FILE *f, const char *method_list);

#endif
