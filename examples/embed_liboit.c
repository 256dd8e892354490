/* Embedding liboit: the application owns the GL context, the framebuffer and
 * the matrices; liboit composites a part file over what the application drew.
 *
 *   embed_liboit SCENE.oitp OUT.png [WIDTH HEIGHT]
 *
 * The context and the PNG writer come from this repository's internal
 * libraries to keep the example short; an application would use its own. */
#include <stdio.h>
#include <stdlib.h>

#include "oit/liboit.h"
#include "render/gl_context.h"
#include "render/gl_util.h"
#include "render/image.h"

static int fail(const char *what, const oit_error *err)
{
    fprintf(stderr, "embed_liboit: %s: %s\n", what, err->message);
    return 1;
}

/* The application's own frame: an RGBA8 framebuffer cleared to a sky blue. */
static GLuint app_framebuffer(int w, int h, GLuint *tex)
{
    GLuint fbo;
    glCreateTextures(GL_TEXTURE_2D, 1, tex);
    glTextureStorage2D(*tex, 1, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, *tex, 0);
    const float sky[4] = {0.45f, 0.62f, 0.85f, 1.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, sky);
    return fbo;
}

/* Reads the framebuffer back (GL rows are bottom first) and writes a PNG. */
static oit_status save_png(GLuint tex, int w, int h, const char *path, oit_error *err)
{
    oit_image img = {0};
    oit_status s = oit_image_alloc(&img, w, h, err);
    if (s != OIT_OK)
        return s;
    float *rows = malloc((size_t)w * h * 4 * sizeof *rows);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)((size_t)w * h * 4 * sizeof *rows),
                      rows);
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w * 4; i++)
            img.rgba[(size_t)y * w * 4 + i] = rows[(size_t)(h - 1 - y) * w * 4 + i];
    free(rows);
    s = oit_image_write_png(&img, path, err);
    oit_image_free(&img);
    return s;
}

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: embed_liboit SCENE.oitp OUT.png [WIDTH HEIGHT]\n");
        return 2;
    }
    int w = argc == 5 ? atoi(argv[3]) : 800, h = argc == 5 ? atoi(argv[4]) : 600;
    oit_error err = {0};
    oit_gl *gl = NULL; /* headless EGL; any current GL 4.5 core context will do */
    if (oit_gl_create(NULL, &gl, &err) != OIT_OK)
        return fail("GL context", &err);

    oit_scene *scene = NULL;
    if (oit_scene_open(argv[1], NULL, &scene, &err) != OIT_OK)
        return fail("open", &err);
    oit_scene_info info;
    oit_scene_get_info(scene, &info, &err);

    oit_renderer_desc rd = {0}; /* K, budget, packing, shading: all defaults */
    oit_renderer *r = NULL;
    if (oit_renderer_create(&rd, &r, &err) != OIT_OK)
        return fail("renderer", &err);

    /* The application's matrices (here from the repository's camera helper;
     * glm::lookAt / glm::perspective give the same column-major arrays). */
    oit_camera cam;
    oit_camera_default(&cam, info.bounds_min, info.bounds_max, 30.0f, 20.0f);
    oit_frame frame = {.viewport_width = w, .viewport_height = h};
    oit_camera_view_matrix(&cam, frame.view);
    oit_camera_proj_matrix(&cam, (float)w / (float)h, frame.projection);
    GLuint tex;
    frame.framebuffer = app_framebuffer(w, h, &tex);

    oit_draw_stats st;
    if (oit_renderer_draw(r, scene, &frame, &st, &err) != OIT_OK)
        return fail("draw", &err);
    printf("%s: %llu triangles in %llu parts; %.1f ms, %llu fragments, %u packs, "
           "%llu parts drawn, %llu culled, %llu overflow pixels\n", argv[1],
           (unsigned long long)info.triangles, (unsigned long long)info.parts, st.ms,
           (unsigned long long)st.fragments, st.packs, (unsigned long long)st.parts_drawn,
           (unsigned long long)st.parts_culled, (unsigned long long)st.overflow_pixels);
    if (save_png(tex, w, h, argv[2], &err) != OIT_OK)
        return fail("write", &err);

    glDeleteFramebuffers(1, &frame.framebuffer);
    glDeleteTextures(1, &tex);
    oit_renderer_destroy(r);
    oit_scene_close(scene);
    oit_gl_destroy(gl);
    return 0;
}
