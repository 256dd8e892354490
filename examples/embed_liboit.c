/* Embedding liboit: the application owns the GL context, the framebuffer and
 * the matrices; liboit composites a scene over what the application drew.
 *
 *   embed_liboit SCENE OUT.ppm [WIDTH HEIGHT]
 *
 * SCENE: a part file (.oitp, streamed) or a mesh file (.ply .obj .off .stl
 * .gltf .glb, drawn in core); the same calls draw either. Only liboit's
 * public headers, EGL and GL: it builds against an installed liboit alone,
 *
 *   cc embed_liboit.c $(pkg-config --cflags --libs oit opengl egl) -lm
 *
 * or with find_package(oit) and find_package(OpenGL COMPONENTS OpenGL EGL)
 * (tests/liboit/test_install.sh does both). The image is written as a binary PPM
 * to keep the example free of an image library. */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <oit/oit.h>

static int fail(const char *what, const char *message)
{
    fprintf(stderr, "embed_liboit: %s: %s\n", what, message);
    return 1;
}

/* The application's context: headless EGL, OpenGL 4.5 core, no surface
 * (Mesa's surfaceless platform where it is offered, else the default
 * display). A windowed application would have its own already. */
static int make_context(EGLDisplay *dpy, EGLContext *ctx)
{
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    *dpy = EGL_NO_DISPLAY;
    if (get_display && ext && strstr(ext, "EGL_MESA_platform_surfaceless"))
        *dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (*dpy == EGL_NO_DISPLAY)
        *dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (*dpy == EGL_NO_DISPLAY || !eglInitialize(*dpy, NULL, NULL) ||
        !eglBindAPI(EGL_OPENGL_API))
        return 0;
    const EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                           EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                           EGL_NONE};
    *ctx = eglCreateContext(*dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attr);
    return *ctx != EGL_NO_CONTEXT && eglMakeCurrent(*dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, *ctx);
}

/* The application's camera, as glm::lookAt and glm::perspective build it:
 * column-major, m[col * 4 + row]. */
static void look_at(const double eye[3], const double target[3], float m[16])
{
    double f[3], s[3], u[3], up[3] = {0, 1, 0}, n = 0.0;
    for (int k = 0; k < 3; k++)
        f[k] = target[k] - eye[k], n += f[k] * f[k];
    for (int k = 0; k < 3; k++)
        f[k] /= sqrt(n);
    s[0] = f[1] * up[2] - f[2] * up[1], s[1] = f[2] * up[0] - f[0] * up[2],
    s[2] = f[0] * up[1] - f[1] * up[0];
    n = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; k++)
        s[k] /= n;
    u[0] = s[1] * f[2] - s[2] * f[1], u[1] = s[2] * f[0] - s[0] * f[2],
    u[2] = s[0] * f[1] - s[1] * f[0];
    memset(m, 0, 16 * sizeof *m);
    for (int k = 0; k < 3; k++) {
        m[k * 4 + 0] = (float)s[k];
        m[k * 4 + 1] = (float)u[k];
        m[k * 4 + 2] = (float)-f[k];
    }
    m[12] = (float)-(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    m[13] = (float)-(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    m[14] = (float)(f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2]);
    m[15] = 1.0f;
}

static void perspective(double fovy_deg, double aspect, double n, double f, float m[16])
{
    double t = 1.0 / tan(fovy_deg * 3.14159265358979323846 / 360.0);
    memset(m, 0, 16 * sizeof *m);
    m[0] = (float)(t / aspect);
    m[5] = (float)t;
    m[10] = (float)((f + n) / (n - f));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * f * n / (n - f));
}

/* Reads the framebuffer back (GL rows are bottom first) and writes a PPM. */
static int save_ppm(GLuint fbo, int w, int h, const char *path)
{
    unsigned char *px = malloc((size_t)w * h * 4);
    FILE *f = px ? fopen(path, "wb") : NULL;
    if (!f) {
        free(px);
        return 0;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++)
            fwrite(px + ((size_t)y * w + x) * 4, 1, 3, f);
    free(px);
    return fclose(f) == 0;
}

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: embed_liboit SCENE OUT.ppm [WIDTH HEIGHT]\n");
        return 2;
    }
    int w = argc == 5 ? atoi(argv[3]) : 800, h = argc == 5 ? atoi(argv[4]) : 600;
    if (w <= 0 || h <= 0)
        return fail("size", "WIDTH and HEIGHT must be positive");
    EGLDisplay dpy;
    EGLContext ctx;
    if (!make_context(&dpy, &ctx))
        return fail("GL context", "no headless OpenGL 4.5 core context through EGL");

    oit_error err = {0};
    oit_scene *scene = NULL;
    if (oit_scene_open(argv[1], NULL, &scene, &err) != OIT_OK)
        return fail("open", err.message);
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);

    oit_renderer_desc rd = {0}; /* K, budgets, packing, shading: all defaults */
    oit_renderer *r = NULL;
    if (oit_renderer_create(&rd, &r, &err) != OIT_OK)
        return fail("renderer", err.message);

    /* The application's frame: an RGBA8 framebuffer cleared to a sky blue. */
    GLuint tex, fbo;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    const float sky[4] = {0.45f, 0.62f, 0.85f, 1.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, sky);

    /* The application's camera: the bounding sphere from 20 degrees up. */
    double c[3], r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)info.bounds_min[k] + info.bounds_max[k]);
        r2 += 0.25 * pow((double)info.bounds_max[k] - info.bounds_min[k], 2.0);
    }
    double radius = r2 > 0.0 ? sqrt(r2) : 1.0, dist = radius / sin(22.5 * 3.14159265 / 180.0);
    double el = 20.0 * 3.14159265358979323846 / 180.0;
    double eye[3] = {c[0], c[1] + dist * sin(el), c[2] + dist * cos(el)};
    oit_frame frame = {.viewport_width = w, .viewport_height = h, .framebuffer = fbo};
    look_at(eye, c, frame.view);
    perspective(45.0, (double)w / h, fmax(dist - 1.05 * radius, 1e-4 * dist),
                dist + 1.05 * radius, frame.projection);

    oit_draw_stats st;
    if (oit_renderer_draw(r, scene, &frame, &st, &err) != OIT_OK)
        return fail("draw", err.message);
    printf("%s: %llu triangles, %s; %.1f ms, %llu fragments, %u packs, %llu parts drawn, "
           "%llu overflow pixels\n", argv[1], (unsigned long long)info.triangles,
           info.in_core ? "in core" : "streamed", st.ms, (unsigned long long)st.fragments,
           st.packs, (unsigned long long)st.parts_drawn,
           (unsigned long long)st.overflow_pixels);
    if (!save_ppm(fbo, w, h, argv[2]))
        return fail("write", argv[2]);

    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    oit_renderer_destroy(r);
    oit_scene_close(scene);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    return 0;
}
