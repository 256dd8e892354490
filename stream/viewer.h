/* oitstream --window: an interactive GLFW window that renders the model
 * every frame with one of the methods of render_methods.h (in the window's
 * own GL context) and presents the image with a status line of figures.
 *
 * Controls: left-drag orbits around the target; right-drag or the wheel
 * zooms; W/A/S/D fly forward/left/back/right and Space/C up/down (eye and
 * target together); 1..9 pick a method (the table's order, restricted to
 * those that can render this input); L toggles the layer heat map; T
 * transparent/translucent; E early termination (where the method has it);
 * R resets the camera; P saves a screenshot; Esc or Q quits.
 *
 * For tests the loop is scriptable: one key of `script` is pressed before
 * each frame, `frames` bounds the loop and `screenshot` receives the last
 * presented frame as read back from the window. */
#ifndef OIT_STREAM_VIEWER_H
#define OIT_STREAM_VIEWER_H

#include "stream/render_methods.h"

typedef struct oit_viewer_desc {
    const oit_mesh *mesh;         /* in core (every method but stream)       */
    oit_partfile *partfile;       /* NULL: the stream method is not offered  */
    oit_method_options options;   /* .gl is set to the window's context      */
    const char *method;           /* first method                            */
    int width, height;            /* window size                             */
    oit_camera camera;            /* first view, and R's                     */
    oit_shading shading;
    int show_layers;              /* start with the heat map                 */
    int overlay;                  /* draw the status line into the image     */
    int frames;                   /* > 0: stop after that many frames        */
    const char *script;           /* keys, one per frame; NULL: none         */
    const char *screenshot;       /* PNG of the last presented frame, or NULL */
} oit_viewer_desc;

/* Runs until the user quits, the window closes, `frames` frames were shown
 * or the script ran out (when frames is 0, a script of n keys runs n frames
 * and a screenshot alone one frame). Prints notes and the final figures on
 * stdout. */
oit_status oit_viewer_run(const oit_viewer_desc *desc, oit_error *err);

#endif
