/* oitstream's command line: what the user asked for, validated, with no
 * I/O done yet. Parsing never prints; a usage error comes back as
 * OIT_ERR_ARGUMENT with a one-line message. */
#ifndef OIT_OITSTREAM_CLI_ARGS_H
#define OIT_OITSTREAM_CLI_ARGS_H

#include <stdio.h>

#include "oit/liboit.h"
#include "view/render/image/clip.h"
#include "view/render/image/view.h"

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
    /* The stream's settings in liboit's public descriptor, each option
     * parsed onto its field and checked by oit_renderer_desc_check (zero:
     * default): --pack, --capture, --schedule, --upload-budget,
     * --slot-budget, --store-budget, --cache-budget, --gpu-budget, --upload-threads
     * (reader_threads; 0: read_on_draw_thread), --epsilon. K is
     * --max-layers (or the file's), the shading the view's; the rest 0. */
    oit_renderer_desc stream;
    /* --epsilon was given: stream.epsilon is also the threshold of the
     * other methods flagged OIT_RENDER_METHOD_EPSILON (oit/render_modes.h) */
    int have_epsilon;
    /* --window: the interactive viewer (viewer.h) */
    int window;
    int window_frames;             /* --window-frames N; 0: until quit */
    const char *window_script;     /* --window-script KEYS */
    const char *window_screenshot; /* --window-screenshot PATH */
    int shot_width, shot_height;   /* --shot-size WxH: P's screenshots; 0: the window's */
    int no_overlay;                /* --no-overlay: no status line in the image */
    int preview;                   /* --preview: oit_viewer_preview (viewer.h); 0 auto */
    int still_ms;                  /* --still MS: stillness before the exact frame; 0: 200 */
    int up_axis;                   /* --up x|y|z: 0, 1, 2; auto (default): -1 */
    /* --clip (repeatable): the planes as given, parsed and checked once,
     * placed at the model's origin once it is read (view/render/image/clip.h) */
    oit_clip_given clip;
    int have_preview;              /* --preview was given */
    /* --pick X,Y: the layers of pixel (X, Y), y = 0 the top row, as JSON
     * on stdout instead of an image (pick_json.h) */
    int pick, pick_x, pick_y;
} oit_stream_args;

oit_status oit_stream_args_parse(int argc, char **argv, oit_stream_args *a, oit_error *err);

/* The --help text; method_list names the methods that exist. */
void oit_stream_usage(FILE *f, const char *method_list);

#endif
