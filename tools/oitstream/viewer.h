/* oitstream --window: an interactive GLFW window that renders the model with
 * one of the methods of tools/common/methods.h (in the window's own GL context)
 * and presents the image with a status line of named figures.
 *
 * It renders only when something changed: the loop blocks on window events
 * (or on a timeout for the stillness deadline below), so a still view costs
 * no frames and no CPU. While the camera moves it shows a preview (by
 * default the same exact method at a reduced resolution, upscaled, its scale
 * adapted to keep frames near 30 ms) and, once the camera was still for
 * still_ms, the exact full-resolution frame; the status line says which.
 *
 * Controls: left-drag orbits around the target; right-drag or the wheel
 * zooms; W/A/S/D fly forward/left/back/right and Space/C up/down (eye and
 * target together); 1..9, 0 pick the first ten methods of the method table
 * (the same key means the same method for every input; a method this input
 * or this machine cannot run says why on screen) and M/N cycle through all
 * of them; L toggles the layer heat map; T transparent/translucent; E early
 * termination (where the method has it); U cycles the up axis (y, z, x) and
 * frames the model for it; V toggles perspective and orthographic (as high
 * as the perspective view at the target: the model keeps its size); X makes a section plane through the model's
 * centre facing the viewer, or turns the planes off and on, and [ and ]
 * move the first plane along its normal (viewer_clip.h); R resets the camera; O opens another file (type
 * its path, Enter loads, Esc cancels; a file dropped on the window opens
 * too); H or ? toggles the help overlay; P saves a screenshot (the view
 * rendered offscreen at shot_width x shot_height), G one of the window as
 * shown; Esc or Q
 * quits.
 *
 * For tests the loop is also scriptable: one key of `script` is pressed
 * before each frame and every iteration renders an exact frame, `frames`
 * bounds that loop, and `screenshot` receives the last presented frame as
 * read back from the window. */
#ifndef OIT_OITSTREAM_VIEWER_H
#define OIT_OITSTREAM_VIEWER_H

#include "oit/partfile.h"
#include "tools/common/method_run.h"
#include "tools/common/methods.h"

/* A model the viewer shows: its triangles in core (every method but
 * stream), the part file when it is one (NULL otherwise) and the K its
 * captures use. */
typedef struct oit_viewer_scene {
    oit_mesh mesh;
    oit_partfile *partfile;
    int max_layers;
} oit_viewer_scene;

/* O (and a dropped file): loads path into *out, or fails with a message the
 * viewer shows. Scenes the viewer loaded it frees with close_model. */
typedef oit_status (*oit_viewer_open_fn)(void *ctx, const char *path, oit_viewer_scene *out,
                                         oit_error *err);
typedef void (*oit_viewer_close_fn)(void *ctx, oit_viewer_scene *scene);

typedef enum oit_viewer_preview {
    OIT_PREVIEW_AUTO = 0, /* lowres while the exact frame takes > 40 ms, else exact */
    OIT_PREVIEW_LOWRES,   /* always the same method at a reduced resolution */
    OIT_PREVIEW_WBOIT,    /* weighted blended OIT at full size */
    OIT_PREVIEW_UNSORTED, /* unsorted blending at full size */
    OIT_PREVIEW_OFF       /* exact frames while moving too */
} oit_viewer_preview;

typedef struct oit_viewer_desc {
    const oit_mesh *mesh;         /* in core (every method but stream)       */
    oit_partfile *partfile;       /* NULL: the stream method is not offered  */
    oit_run_options options;   /* .gl is set to the window's context      */
    const char *method;           /* first method                            */
    int width, height;            /* window size                             */
    oit_camera camera;            /* first view, and R's (until U or O frame anew) */
    float azimuth, elevation;     /* the default view's, for U and O         */
    int up_axis;                  /* 0 x, 1 y, 2 z                           */
    oit_shading shading;
    oit_clip clip;                /* section planes (--clip); X, [ and ] change them */
    int show_layers;              /* start with the heat map                 */
    int overlay;                  /* draw the status line into the image     */
    int frames;                   /* > 0: stop after that many frames        */
    const char *script;           /* keys, one per frame; NULL: none         */
    const char *screenshot;       /* PNG of the last presented frame, or NULL */
    int shot_width, shot_height;  /* P's screenshots; 0: the window's size   */
    oit_viewer_preview preview;   /* what moving shows                       */
    int still_ms;                 /* stillness before the exact frame; 0: 200 */
    const char *stats_path;       /* JSON of the frame counters, rewritten after each frame */
    const char *model_path;       /* for the title                           */
    oit_viewer_open_fn open_model;   /* NULL: O says it cannot open files    */
    oit_viewer_close_fn close_model;
    void *model_ctx;
} oit_viewer_desc;

/* Runs until the user quits, the window closes, `frames` frames were shown
 * or the script ran out (when frames is 0, a script of n keys runs n frames
 * and a screenshot alone one frame). Prints notes and the final figures on
 * stdout: "viewer: N frames rendered (E exact, P preview), X presented". */
oit_status oit_viewer_run(const oit_viewer_desc *desc, oit_error *err);

#endif
