/* A GL 4.5 core context in a GLFW window, for the interactive viewer: an
 * oit_gl like the headless ones of gl_context.h (make it current, destroy
 * it, draw any GL method in it), with oit_gl_window giving the GLFWwindow*.
 * Its own library (oit_window), so that only what opens a window links
 * GLFW: liboit, which draws in its caller's context, does not. */
#ifndef OIT_RENDER_GL_WINDOW_H
#define OIT_RENDER_GL_WINDOW_H

#include "view/render/gl/gl_context.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Opens a desc->width x desc->height window (default 1024x768) titled
 * desc->title (default "oitstream"), its context current on the calling
 * thread; desc may be NULL. No display is an OIT_ERR_GL that says so. */
oit_status oit_gl_create_window(const oit_gl_desc *desc, oit_gl **out, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
