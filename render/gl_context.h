/* The GL 4.5 core context every GL method runs in: headless through EGL
 * (device platform with an NVIDIA device when present, else surfaceless
 * Mesa), or a GLFW window for the viewer. The caller makes one per thread and
 * owns it; nothing here is global. */
#ifndef OIT_RENDER_GL_CONTEXT_H
#define OIT_RENDER_GL_CONTEXT_H

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_gl oit_gl;

typedef struct oit_gl_desc {
    int window;        /* 0: headless EGL; 1: GLFW window               */
    int width, height; /* window size; default 1024x768                 */
    const char *title; /* window title; default "oitstream"             */
    int debug;         /* 1: debug context with a message callback      */
} oit_gl_desc;

oit_status oit_gl_create(const oit_gl_desc *desc, oit_gl **out, oit_error *err);
void oit_gl_destroy(oit_gl *gl);
/* "llvmpipe (LLVM 15.0.6, 256 bits)" or the NVIDIA renderer string. */
const char *oit_gl_renderer(const oit_gl *gl);
/* Makes gl's context current on the calling thread again (after another
 * context was made current there). */
oit_status oit_gl_make_current(oit_gl *gl, oit_error *err);
/* Window only (NULL when headless): the GLFWwindow*. */
void *oit_gl_window(oit_gl *gl);

#ifdef __cplusplus
}
#endif
#endif
