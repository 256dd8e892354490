/* The GL 4.5 core context every GL method runs in: headless through EGL
 * (device platform with an NVIDIA device when present, else surfaceless
 * Mesa), or a window's for the viewer (gl_window.h, library oit_window: it
 * is the one that links GLFW, and liboit does not). The caller makes one per
 * thread and owns it; nothing here is global. */
#ifndef OIT_RENDER_GL_CONTEXT_H
#define OIT_RENDER_GL_CONTEXT_H

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_gl oit_gl;

typedef struct oit_gl_desc {
    int width, height; /* window size; default 1024x768 (windows only)  */
    const char *title; /* window title; default "oitstream" (windows)   */
    int debug;         /* 1: debug context (also OIT_GL_DEBUG=1, below)  */
} oit_gl_desc;

/* A headless EGL context, current on the calling thread (desc may be NULL). */
oit_status oit_gl_create(const oit_gl_desc *desc, oit_gl **out, oit_error *err);
void oit_gl_destroy(oit_gl *gl);
/* "llvmpipe (LLVM 15.0.6, 256 bits)" or the NVIDIA renderer string. */
const char *oit_gl_renderer(const oit_gl *gl);
/* Makes gl's context current on the calling thread again (after another
 * context was made current there). */
oit_status oit_gl_make_current(oit_gl *gl, oit_error *err);
/* Debug contexts. A context is made with the debug flag when its desc asks
 * or the environment has OIT_GL_DEBUG=1 (the test suite sets it for every
 * test), and any context of ours with that flag counts the driver's
 * error and undefined-behaviour messages (KHR_debug), printing each to
 * stderr as "GL debug: ...". The variable is read here alone; gl_window.c
 * asks through oit_gl_debug_wanted. */
int oit_gl_debug_wanted(const oit_gl_desc *desc);
/* OIT_ERR_GL naming `what` and the first message when messages arrived
 * since the last check, else OIT_OK (always for a context without the
 * flag, or gl NULL). view/render/method.c checks after every frame, so a frame
 * whose GL calls the driver flagged fails instead of passing silently. */
oit_status oit_gl_debug_check(oit_gl *gl, const char *what, oit_error *err);

/* An oit_gl for the context current on the calling thread, whatever made
 * it (a library's caller: liboit), so the GL methods draw in it: making
 * it current does nothing, destroying it frees the handle only, and no
 * debug callback replaces the caller's (oit_gl_debug_check: OK). */
oit_status oit_gl_borrow_current(oit_gl **out, oit_error *err);
/* Window only (NULL when headless): the GLFWwindow*. */
void *oit_gl_window(oit_gl *gl);

/* For a window system (gl_window.c): makes an oit_gl of a window whose GL
 * context is current on the calling thread, so that the GL methods draw in
 * it like in a headless one. oit_gl_make_current and oit_gl_destroy call
 * ops with the window; ops must outlive the oit_gl (a static const table).
 * The oit_gl owns the window from this call on: on failure it is destroyed
 * through ops->destroy too. */
typedef struct oit_gl_window_ops {
    void (*make_current)(void *window);
    void (*destroy)(void *window);
} oit_gl_window_ops;
oit_status oit_gl_adopt_window(void *window, const oit_gl_window_ops *ops, oit_gl **out,
                               oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
