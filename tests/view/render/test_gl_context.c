/* A headless GL 4.5 core context comes up and offers what the GL methods
 * need; a window without a display fails with a message, not a crash. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/glsl_bindings.h"
#include "view/render/gl/gl_window.h"
#include "tests/lib/test_check.h"

/* A debug context (gl_context.h) turns what the driver flags into an error
 * of the next check, once, naming the message. */
static void debug_context(void)
{
    oit_error err = {0};
    oit_gl *gl = NULL;
    if (oit_gl_create(&(oit_gl_desc){.debug = 1}, &gl, &err) != OIT_OK) {
        CHECK(0, "debug context: %s", err.message);
        return;
    }
    CHECK(oit_gl_debug_check(gl, "fresh", &err) == OIT_OK, "fresh debug context: %s",
          err.message);
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, 64, NULL, 0);
    /* An offset off every alignment a driver may ask for: GL_INVALID_VALUE. */
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, buf, 3, 16);
    oit_gl_check("provoked", &err);
    oit_status s = oit_gl_debug_check(gl, "provoked", &err);
    printf("debug message: %s\n", err.message);
    CHECK(s == OIT_ERR_GL && strstr(err.message, "provoked") && strstr(err.message, "error"),
          "an invalid glBindBufferRange passed the debug check (%d: %s)", (int)s, err.message);
    CHECK(oit_gl_debug_check(gl, "again", &err) == OIT_OK, "a message reported twice: %s",
          err.message);
    glDeleteBuffers(1, &buf);
    oit_gl_destroy(gl);
}

int main(void)
{
    oit_error err = {0};
    oit_gl *gl = NULL;
    oit_status s = oit_gl_create(NULL, &gl, &err);
    if (s != OIT_OK) {
        fprintf(stderr, "FAIL: headless context: %s\n", err.message);
        return 1;
    }
    GLint major = 0, minor = 0, samples = 0, isamples = 0, profile = 0;
    GLint64 ssbo = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_MAX_SAMPLES, &samples);
    glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &isamples);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
    printf("renderer: %s\nGL %d.%d core=%d max_samples=%d max_integer_samples=%d "
           "max_ssbo_bytes=%lld\n", oit_gl_renderer(gl), major, minor,
           (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0, samples, isamples, (long long)ssbo);
    CHECK(oit_gl_renderer(gl)[0] != '\0', "empty renderer string");
    CHECK(major * 10 + minor >= 45, "GL %d.%d < 4.5", major, minor);
    CHECK(profile & GL_CONTEXT_CORE_PROFILE_BIT, "not a core profile");
    CHECK(oit_gl_window(gl) == NULL, "headless context reports a window");
    CHECK(oit_gl_check("after queries", &err) == OIT_OK, "%s", err.message);

    /* A shader error names the program and quotes the log. */
    const char *bad[] = {"#version 450 core\nvoid main() { undefined_call(); }\n", NULL};
    GLuint prog = 0;
    s = oit_gl_program_compute("broken test program", bad, &prog, &err);
    printf("compile error message: %s\n", err.message);
    CHECK(s == OIT_ERR_GL && prog == 0, "broken shader accepted");
    oit_gl_destroy(gl);
    debug_context();

    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        oit_gl_desc desc = {.width = 64, .height = 64};
        s = oit_gl_create_window(&desc, &gl, &err);
        printf("window without display: %s: %s\n", oit_status_name(s), err.message);
        CHECK(s == OIT_ERR_GL && gl == NULL, "window without a display did not fail");
    }
    return test_verdict();
}
