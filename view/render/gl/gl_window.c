/* GLFW windows as oit_gl contexts (gl_window.h). GLFW's state is the
 * process's and glfwTerminate closes every window, so each window
 * initialises GLFW and terminates it when destroyed: one window at a time,
 * which is what the viewer opens. */
#include "view/render/gl/gl_window.h"

#include <GLFW/glfw3.h>

static void window_make_current(void *window)
{
    glfwMakeContextCurrent(window);
}

static void window_destroy(void *window)
{
    glfwDestroyWindow(window);
    glfwTerminate();
}

static const oit_gl_window_ops glfw_ops = {window_make_current, window_destroy};

oit_status oit_gl_create_window(const oit_gl_desc *desc, oit_gl **out, oit_error *err)
{
    static const oit_gl_desc zero;
    if (!desc)
        desc = &zero;
    *out = NULL;
    if (!glfwInit()) {
        const char *why = NULL;
        glfwGetError(&why);
        return oit_error_set(err, OIT_ERR_GL, "GLFW: cannot initialise (%s); is there a "
                             "display (DISPLAY / WAYLAND_DISPLAY)?", why ? why : "no reason given");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, oit_gl_debug_wanted(desc) ? GLFW_TRUE : GLFW_FALSE);
    int w = desc->width > 0 ? desc->width : 1024, h = desc->height > 0 ? desc->height : 768;
    GLFWwindow *window =
        glfwCreateWindow(w, h, desc->title ? desc->title : "oitstream", NULL, NULL);
    if (!window) {
        const char *why = NULL;
        glfwGetError(&why);
        glfwTerminate();
        return oit_error_set(err, OIT_ERR_GL, "GLFW: cannot open a %dx%d OpenGL 4.5 core "
                             "window: %s", w, h, why ? why : "no reason given");
    }
    glfwMakeContextCurrent(window);
    return oit_gl_adopt_window(window, &glfw_ops, out, err);
}
