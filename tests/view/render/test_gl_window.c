/* The windowed context (GLFW) runs the same GL methods as the headless one:
 * under a virtual display (Xvfb) a DFB frame rendered in a window equals the
 * hand-composited result, and what the window shows after presenting it (read
 * back from its default framebuffer: a screenshot) equals the frame. The
 * screenshot is written to OIT_TEST_TMP/window_screenshot.png to look at. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/lib/gl_test_scene.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_window.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/image.h"

#define GLFW_INCLUDE_NONE /* GL comes from gl_util.h (core profile prototypes) */
#include <GLFW/glfw3.h>

enum { W = 96, H = 64 };

/* Presents img in the window's default framebuffer and reads it back. */
static int present_and_read(oit_gl *gl, const oit_image *img, oit_image *shot, oit_error *err)
{
    GLuint tex = 0, fbo = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, W, H);
    /* The image's row 0 is the top; GL's is the bottom: upload flipped. */
    for (int y = 0; y < H; y++)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, H - 1 - y, W, 1, GL_RGBA, GL_FLOAT,
                        img->rgba + 4 * (size_t)y * W);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, W, H);
    glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    /* Read the back buffer just before presenting it: what the swap shows. */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    unsigned char *px = malloc((size_t)W * H * 4);
    if (!px || oit_image_alloc(shot, W, H, err) != OIT_OK) {
        free(px);
        return 0;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 4; c++)
                shot->rgba[4 * ((size_t)y * W + x) + c] =
                    px[4 * ((size_t)(H - 1 - y) * W + x) + c] / 255.0f;
    free(px);
    glfwSwapBuffers((GLFWwindow *)oit_gl_window(gl));
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    return oit_gl_check("present and read back", err) == OIT_OK;
}

int main(void)
{
    if (!getenv("DISPLAY")) {
        printf("SKIP: no DISPLAY (run under xvfb-run)\n");
        return 77;
    }
    oit_error err = {0};
    oit_gl *gl = NULL;
    oit_gl_desc desc = {.width = W, .height = H, .title = "oit window test"};
    if (oit_gl_create_window(&desc, &gl, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: window context: %s\n", err.message);
        return 1;
    }
    printf("window renderer: %s\n", oit_gl_renderer(gl));

    quad_spec q[6] = {
        {-2.0f, 0.9f, {230, 40, 40, 120}, 1}, {-4.0f, 2.5f, {40, 200, 60, 160}, 0},
        {-3.0f, 1.5f, {40, 60, 230, 90}, 1},  {-6.0f, 5.0f, {240, 220, 30, 200}, 1},
        {-2.5f, 0.4f, {255, 255, 255, 60}, 0}, {-5.0f, 3.0f, {120, 30, 160, 140}, 1},
    };
    oit_view view;
    scene_view(&view, W, H, OIT_SHADING_TRANSPARENT);
    oit_triangle *tris = scene_tris(q, 6);
    oit_gpu_mesh *mesh = NULL;
    oit_dfb *dfb = NULL;
    oit_image frame = {0}, shot = {0};
    oit_frame_stats st = {0};
    int ok = tris && oit_gpu_mesh_create(tris, 12, 0, &mesh, &err) == OIT_OK &&
             oit_dfb_create(&dfb, &err) == OIT_OK &&
             oit_dfb_render(dfb, (const oit_gpu_mesh *const *)&mesh, 1, &view, &frame, NULL,
                            &st, &err) == OIT_OK;
    if (!ok) {
        fprintf(stderr, "FAIL: DFB in a window: %s\n", err.message);
        return 1;
    }
    int failures = 0;
    double hand = hand_max_diff(&frame, &view, q, 6);
    printf("window DFB: %llu fragments, max %u layers, max diff vs hand %.3g\n",
           (unsigned long long)st.fragments, st.max_layers, hand);
    if (hand > 1.0 / 255.0) {
        fprintf(stderr, "FAIL: window DFB differs from the hand composite by %g\n", hand);
        failures++;
    }
    if (!present_and_read(gl, &frame, &shot, &err)) {
        fprintf(stderr, "FAIL: screenshot: %s\n", err.message);
        return 1;
    }
    oit_image_diff d;
    if (oit_image_compare(&frame, &shot, &d, NULL, 1.0f, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: compare: %s\n", err.message);
        return 1;
    }
    printf("pixel (48,32): frame %.3f %.3f %.3f, window %.3f %.3f %.3f\n",
           frame.rgba[4 * (32 * W + 48)], frame.rgba[4 * (32 * W + 48) + 1],
           frame.rgba[4 * (32 * W + 48) + 2], shot.rgba[4 * (32 * W + 48)],
           shot.rgba[4 * (32 * W + 48) + 1], shot.rgba[4 * (32 * W + 48) + 2]);
    printf("screenshot vs frame: max_abs %.4f, %.3f%% of pixels over 1/255\n", d.max_abs,
           d.pct_over_1_255);
    /* 8-bit quantisation of the window costs at most half a step. */
    if (d.max_abs > 0.5 / 255.0 + 1e-6) {
        fprintf(stderr, "FAIL: the window does not show the frame (max_abs %g)\n", d.max_abs);
        failures++;
    }
    const char *tmp = getenv("OIT_TEST_TMP");
    char path[1024];
    snprintf(path, sizeof path, "%s/window_screenshot.png", tmp ? tmp : ".");
    if (oit_image_write_png(&shot, path, &err) == OIT_OK)
        printf("screenshot: %s\n", path);

    oit_image_free(&frame);
    oit_image_free(&shot);
    oit_dfb_destroy(dfb);
    oit_gpu_mesh_destroy(mesh);
    free(tris);
    oit_gl_destroy(gl);
    printf("%s\n", failures ? "FAILED" : "ok");
    return failures != 0;
}
