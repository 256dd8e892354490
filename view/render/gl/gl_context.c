/* GL 4.5 core contexts (gl_context.h). Headless contexts come from EGL with
 * no surface: the GL methods render into their own FBOs, so a pbuffer would
 * only cost memory. The display is chosen so that a machine with an NVIDIA
 * GPU uses it even when Mesa's EGL is also installed. Windows are made by
 * gl_window.c and adopted here through their ops, so that this file, which
 * liboit links, needs no window system. */
#include "view/render/gl/gl_context.h"

#include "view/render/gl/gl_util.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct oit_gl {
    EGLDisplay dpy;
    EGLContext ctx;
    void *window; /* an adopted window, or NULL when headless */
    int borrowed; /* the caller's current context (oit_gl_borrow_current) */
    const oit_gl_window_ops *ops;
    char renderer[256];
    /* Debug contexts (oit_gl_debug_wanted): error and undefined-behaviour
     * messages counted by on_debug, the first kept for the error;
     * `reported` of them were returned by oit_gl_debug_check already. */
    uint64_t debug_errors, debug_reported;
    char debug_first[320];
};

int oit_gl_debug_wanted(const oit_gl_desc *desc)
{
    const char *env = getenv("OIT_GL_DEBUG");
    return (desc && desc->debug) || (env && strcmp(env, "1") == 0);
}

static const char *debug_type_name(GLenum type)
{
    return type == GL_DEBUG_TYPE_ERROR ? "error" : "undefined behaviour";
}

/* Counts what the spec calls errors or undefined behaviour; performance and
 * portability notes only matter to a person reading the log. */
static void APIENTRY on_debug(GLenum source, GLenum type, GLuint id, GLenum severity,
                              GLsizei length, const GLchar *message, const void *user)
{
    (void)source, (void)id, (void)severity;
    if (type != GL_DEBUG_TYPE_ERROR && type != GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR)
        return;
    oit_gl *gl = (oit_gl *)(uintptr_t)user;
    int n = length < 0 ? (int)strlen(message) : (int)length;
    if (gl->debug_errors++ == gl->debug_reported)
        snprintf(gl->debug_first, sizeof gl->debug_first, "%s: %.*s", debug_type_name(type),
                 n, message);
    fprintf(stderr, "GL debug: %s: %.*s\n", debug_type_name(type), n, message);
}

/* A context made with the debug flag reports through on_debug, on the
 * calling thread, at the call that caused the message. */
static void install_debug(oit_gl *gl)
{
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT))
        return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug, gl);
}

oit_status oit_gl_debug_check(oit_gl *gl, const char *what, oit_error *err)
{
    if (!gl || gl->debug_errors == gl->debug_reported)
        return OIT_OK;
    uint64_t n = gl->debug_errors - gl->debug_reported;
    gl->debug_reported = gl->debug_errors;
    return oit_error_set(err, OIT_ERR_GL, "%s: the GL debug context reported %llu "
                         "message(s), the first: %s", what, (unsigned long long)n,
                         gl->debug_first);
}

/* An NVIDIA device of EGL_EXT_device_enumeration, or EGL_NO_DEVICE_EXT. */
static EGLDeviceEXT find_nvidia_device(void)
{
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    if (!query_devices || !query_string)
        return EGL_NO_DEVICE_EXT;
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices(16, devices, &n))
        return EGL_NO_DEVICE_EXT;
    for (EGLint i = 0; i < n; i++) {
        const char *ext = query_string(devices[i], EGL_EXTENSIONS);
        /* glvnd reports the vendor library's extensions per device; only
         * NVIDIA's driver exposes EGL_NV_device_cuda. */
        if (ext && strstr(ext, "EGL_NV_device_cuda"))
            return devices[i];
    }
    return EGL_NO_DEVICE_EXT;
}

static EGLDisplay open_display(void)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = EGL_NO_DISPLAY;
    if (get_display) {
        EGLDeviceEXT dev = find_nvidia_device();
        if (dev != EGL_NO_DEVICE_EXT)
            dpy = get_display(EGL_PLATFORM_DEVICE_EXT, dev, NULL);
        if (dpy == EGL_NO_DISPLAY)
            dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    }
    if (dpy == EGL_NO_DISPLAY)
        dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    return dpy;
}

static oit_status create_egl(const oit_gl_desc *desc, oit_gl *gl, oit_error *err)
{
    gl->dpy = open_display();
    EGLint major = 0, minor = 0;
    if (gl->dpy == EGL_NO_DISPLAY || !eglInitialize(gl->dpy, &major, &minor))
        return oit_error_set(err, OIT_ERR_GL, "EGL: no display could be initialised "
                             "(eglInitialize error 0x%x)", eglGetError());
    if (!eglBindAPI(EGL_OPENGL_API))
        return oit_error_set(err, OIT_ERR_GL, "EGL %d.%d: desktop OpenGL is not offered",
                             major, minor);
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = NULL;
    EGLint ncfg = 0;
    /* A config is only needed to create the context: with
     * EGL_KHR_no_config_context it may be absent. */
    if (!eglChooseConfig(gl->dpy, cfg_attr, &cfg, 1, &ncfg) || ncfg < 1)
        cfg = NULL;
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_CONTEXT_OPENGL_DEBUG,
                               oit_gl_debug_wanted(desc) ? EGL_TRUE : EGL_FALSE,
                               EGL_NONE};
    gl->ctx = eglCreateContext(gl->dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (gl->ctx == EGL_NO_CONTEXT)
        return oit_error_set(err, OIT_ERR_GL, "EGL: cannot create an OpenGL 4.5 core "
                             "context (error 0x%x)", eglGetError());
    if (!eglMakeCurrent(gl->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, gl->ctx))
        return oit_error_set(err, OIT_ERR_GL, "EGL: surfaceless eglMakeCurrent failed "
                             "(error 0x%x; EGL_KHR_surfaceless_context missing?)",
                             eglGetError());
    return OIT_OK;
}

static oit_gl *gl_new(void)
{
    oit_gl *gl = calloc(1, sizeof *gl);
    if (gl) {
        gl->dpy = EGL_NO_DISPLAY;
        gl->ctx = EGL_NO_CONTEXT;
    }
    return gl;
}

/* The renderer string, read once the context is current. */
static void gl_ready(oit_gl *gl)
{
    const char *r = (const char *)glGetString(GL_RENDERER);
    strncpy(gl->renderer, r ? r : "unknown", sizeof gl->renderer - 1);
    install_debug(gl);
}

oit_status oit_gl_create(const oit_gl_desc *desc, oit_gl **out, oit_error *err)
{
    static const oit_gl_desc zero;
    if (!desc)
        desc = &zero;
    *out = NULL;
    oit_gl *gl = gl_new();
    if (!gl)
        return oit_error_set(err, OIT_ERR_NOMEM, "GL context: out of memory");
    oit_status s = create_egl(desc, gl, err);
    if (s != OIT_OK) {
        oit_gl_destroy(gl);
        return s;
    }
    gl_ready(gl);
    *out = gl;
    return OIT_OK;
}

oit_status oit_gl_borrow_current(oit_gl **out, oit_error *err)
{
    *out = gl_new();
    if (!*out)
        return oit_error_set(err, OIT_ERR_NOMEM, "GL context: out of memory");
    (*out)->borrowed = 1;
    const char *r = (const char *)glGetString(GL_RENDERER);
    strncpy((*out)->renderer, r ? r : "unknown", sizeof (*out)->renderer - 1);
    return OIT_OK;
}

oit_status oit_gl_adopt_window(void *window, const oit_gl_window_ops *ops, oit_gl **out,
                               oit_error *err)
{
    *out = NULL;
    oit_gl *gl = gl_new();
    if (!gl) {
        ops->destroy(window);
        return oit_error_set(err, OIT_ERR_NOMEM, "GL window: out of memory");
    }
    gl->window = window;
    gl->ops = ops;
    gl_ready(gl);
    *out = gl;
    return OIT_OK;
}

void oit_gl_destroy(oit_gl *gl)
{
    if (!gl)
        return;
    if (gl->window)
        gl->ops->destroy(gl->window);
    if (gl->dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(gl->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (gl->ctx != EGL_NO_CONTEXT)
            eglDestroyContext(gl->dpy, gl->ctx);
        /* No eglTerminate: the display is shared by every context of the
         * process (one per thread), and terminating it would pull theirs. */
    }
    free(gl);
}

oit_status oit_gl_make_current(oit_gl *gl, oit_error *err)
{
    if (gl->borrowed)
        return OIT_OK;
    if (gl->window) {
        gl->ops->make_current(gl->window);
        return OIT_OK;
    }
    if (eglGetCurrentContext() == gl->ctx)
        return OIT_OK;
    if (!eglMakeCurrent(gl->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, gl->ctx))
        return oit_error_set(err, OIT_ERR_GL, "EGL: eglMakeCurrent failed (error 0x%x)",
                             eglGetError());
    return OIT_OK;
}

const char *oit_gl_renderer(const oit_gl *gl)
{
    return gl->renderer;
}

void *oit_gl_window(oit_gl *gl)
{
    return gl->window;
}
