/* The viewer's state and what its files share (viewer.h is the
 * interface). viewer.c: messages and the loop; viewer_camera.c: the orbit
 * camera; viewer_input.c: keys, mouse and dropped files and the methods
 * they switch; viewer_overlay.c: the status line and panels drawn over the
 * image; viewer_frames.c: rendering, previews, presenting. Each function is
 * documented at its definition. */
#ifndef OIT_TOOLS_OITSTREAM_VIEWER_INTERNAL_H
#define OIT_TOOLS_OITSTREAM_VIEWER_INTERNAL_H

#include "tools/oitstream/viewer.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/vec.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/gl_window.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "tools/common/paths.h"
#include "tools/oitstream/stats_json.h"
#include "tools/oitstream/viewer_clip.h"
#include "view/plot/text_overlay.h"
#include "tools/common/method_run.h"

#define GLFW_INCLUDE_NONE /* GL comes from gl_util.h (core profile prototypes) */
#include <GLFW/glfw3.h>

/* Keys 1..9, 0 reach the first KEYED_METHODS of the table; M/N cycle all. */
enum { MAX_METHODS = 16, KEYED_METHODS = 10, KEY_QUEUE = 64, KEY_ESC = 27 };
enum { SHOWN_NONE = 0, SHOWN_EXACT = 1, SHOWN_PREVIEW = 2 };
enum { DEFAULT_STILL_MS = 200, PREVIEW_MAX_SCALE = 4 };
enum { VIEWER_PICK_ROWS = 12 }; /* layers the pick's panel lists */
/* auto: preview when an exact frame takes longer than this (25 fps) */
#define AUTO_PREVIEW_MS 40.0
#define MESSAGE_SECONDS 5.0

typedef struct viewer {
    const oit_viewer_desc *desc;
    oit_run_options options; /* desc's, with the current scene's part file and K */
    oit_run_source stream;   /* options.source points here */
    char stream_path[4096];     /* stream.path: the part file shown */
    oit_gl *gl;
    GLFWwindow *win;
    const oit_render_method_info *methods[MAX_METHODS]; /* the whole table, in its order */
    int method_count, current;
    oit_run *state;
    const oit_render_method_info *pv_method; /* wboit/unsorted preview, opened when first needed */
    oit_run *pv_state;
    /* the scene shown: the caller's, or one O opened (owned) */
    const oit_mesh *mesh;
    oit_partfile *pf;
    oit_viewer_scene owned;
    int have_owned;
    char model_name[512];
    oit_view view;
    oit_camera home;      /* R's */
    oit_viewer_clip clip; /* section planes: X, [ and ] (viewer_clip.h) */
    int up_axis;
    float centre[3], radius; /* bounding sphere, for the clip planes */
    int show_layers, quit, drag;
    double mouse_x, mouse_y;
    char keys[KEY_QUEUE];
    int key_count;
    uint32_t *counts;
    size_t counts_cap;
    oit_image base, shown, shot;
    GLuint tex, fbo;
    int tex_w, tex_h;
    oit_frame_stats st;
    /* The newest GPU time polled from gpu_state (a frame or two behind the
     * one shown: timer queries are read without waiting); frame 0: none. */
    oit_gpu_times gpu;
    const oit_run *gpu_state;
    const char *gpu_absent;
    int frames, exact_frames, preview_frames, presents, screenshots;
    int grab_pending; /* G: save the next presented image, as the window shows it */
    /* The threshold the methods open with (options.threshold; E toggles
     * it): has_epsilon 0, none given, each method's default. */
    float epsilon;
    int has_epsilon;
    /* what needs doing: moved (camera: preview), changed (exact now),
     * recompose (overlays only: no rendering) */
    int moved, changed, recompose;
    double last_move;
    int shown_kind, shown_scale; /* what the image is; its preview's scale */
    int preview_scale;
    double preview_ms_at[PREVIEW_MAX_SCALE + 2]; /* the last preview's ms at each scale */
    double last_exact_wall_ms, last_preview_wall_ms, last_wall_ms;
    double last_present_ms; /* overlays, upload, blit and swap of the last image shown */
    int help;
    /* I, or a click: the layers under the cursor (viewer_pick.c);
     * press_time when the left button went down */
    double press_time;
    int picked, pick_x, pick_y;
    size_t pick_count;
    oit_pick_layer pick[VIEWER_PICK_ROWS];
    int entering, skip_char, open_pending;
    char entry[512];
    size_t entry_len;
    char message[400];
    double message_until;
    int status_rows;
    char status[512]; /* the fields on one line: the title and the summary */
} viewer;

/* The up axis's letter (0 x, 1 y, 2 z). */
static inline char viewer_axis_name(int axis)
{
    return "xyz"[axis];
}

/* viewer.c: messages and the loop */
void viewer_say(viewer *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* viewer_camera.c: the orbit camera */
void viewer_fit_clip(viewer *v);
void viewer_fly(viewer *v, int forward, int right, int up_dir);
void viewer_orbit(viewer *v, double dx, double dy);
void viewer_toggle_ortho(viewer *v);
void viewer_zoom(viewer *v, double factor);

/* viewer_input.c: keys, the mouse, dropped files and the methods they switch */
const char *viewer_unavailable(const viewer *v, const oit_render_method_info *m);
oit_status viewer_switch_method(viewer *v, int i, oit_error *err);
void viewer_close_preview_method(viewer *v);
void viewer_fit_scene(viewer *v);
void viewer_handle_key(viewer *v, char key);
void viewer_key_label(int i, char *buf, size_t cap);
void viewer_list_methods(viewer *v);
void viewer_moved(viewer *v);
void viewer_on_button(GLFWwindow *w, int button, int action, int mods);
void viewer_on_char(GLFWwindow *w, unsigned int codepoint);
void viewer_on_cursor(GLFWwindow *w, double x, double y);
void viewer_on_drop(GLFWwindow *w, int count, const char **paths);
void viewer_on_key(GLFWwindow *w, int key, int scancode, int action, int mods);
void viewer_on_refresh(GLFWwindow *w);
void viewer_on_resize(GLFWwindow *w, int width, int height);
void viewer_on_scroll(GLFWwindow *w, double dx, double dy);
void viewer_open_entry(viewer *v);
void viewer_push_key(viewer *v, char key);
void viewer_save_screenshot(viewer *v);
void viewer_save_window(viewer *v);

/* viewer_pick.c: the layers under the cursor */
void viewer_pick_at(viewer *v, double wx, double wy);
void viewer_pick_button(viewer *v, int pressed);

/* viewer_overlay.c: the status line and the panels drawn over the image */
oit_status viewer_compose(viewer *v, oit_error *err);

/* viewer_frames.c: rendering, previews, presenting and the stats file */
oit_status viewer_one_frame(viewer *v, int kind, oit_error *err);
oit_status viewer_present(viewer *v, oit_error *err);
oit_status viewer_render_shot(viewer *v, int width, int height, oit_image *out, oit_error *err);
void viewer_write_stats(viewer *v);

#endif
