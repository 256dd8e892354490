/* liboit offscreen: a scene rendered into memory, for scripts and batch
 * jobs that have no GL context of their own (the Python package, python/oit,
 * calls this).
 *
 *   oit_offscreen_create  makes a headless EGL context (GL 4.5 core: an
 *                         NVIDIA device when present, else Mesa's llvmpipe)
 *                         and an oit_renderer in it
 *   oit_offscreen_render  draws any scene (part file or in core) over a
 *                         background into the caller's RGBA buffer
 *
 * The image is what oit_renderer_draw composites over a framebuffer cleared
 * to the background (liboit.h, Result): rgb = C + T * bg.rgb,
 * a = (1 - t) + t * bg.a with t = mean(T), so over an opaque background
 * alpha is 1. Values are as computed (sRGB-encoded like the inputs; no
 * conversion), 8-bit output rounds v * 255 as the tools' PNGs do.
 *
 * Threads: an oit_offscreen is used by one thread at a time. create and
 * render make its context current on the calling thread and leave it
 * current; a caller that also has a context of its own on that thread makes
 * its own current again afterwards. destroy releases the context.
 */
#ifndef OIT_OFFSCREEN_H
#define OIT_OFFSCREEN_H

#include "oit/export.h"

#include <stddef.h>
#include <stdint.h>

#include "liboit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_offscreen oit_offscreen;

typedef struct oit_offscreen_desc {
    oit_renderer_desc renderer; /* zero: liboit's defaults */
} oit_offscreen_desc;

/* desc may be NULL. Fails with OIT_ERR_GL when no EGL display or GL 4.5
 * core context can be had (the message says which step). */
OIT_API oit_status oit_offscreen_create(const oit_offscreen_desc *desc, oit_offscreen **out,
                                        oit_error *err);
OIT_API void oit_offscreen_destroy(oit_offscreen *o);
/* oit_renderer_release_scene for o's renderer (liboit.h, Lifetime): a
 * scene o drew last stays in memory, closed or not, until o draws another,
 * releases it or is destroyed. */
OIT_API void oit_offscreen_release_scene(oit_offscreen *o, const oit_scene *scene);
/* The GL renderer string of the context ("llvmpipe (LLVM 15.0.6, 256 bits)"). */
OIT_API const char *oit_offscreen_gl_renderer(const oit_offscreen *o);
/* o's renderer descriptor with every default resolved, as
 * oit_renderer_get_desc gives it (after a render of a part file: K, the
 * budgets, capture, read_on_draw_thread; after any render: the shading). */
OIT_API void oit_offscreen_get_desc(const oit_offscreen *o, oit_offscreen_desc *out);

typedef enum oit_pixel_format {
    OIT_PIXELS_RGBA8 = 0,  /* 4 uint8_t a pixel             */
    OIT_PIXELS_RGBA32F = 1, /* 4 floats a pixel, 0..1, sRGB-encoded like RGBA8 */
    /* 4 floats a pixel: the frame itself, for compositing with other
     * frames (oit_scene_desc.share_count): rgb its premultiplied colour C
     * and a = 1 - t (t = mean(T), T itself for transparent shading), in the
     * compositing space (linear light, not encoded, for
     * OIT_RENDER_COLOUR_LINEAR), with no background (background is not
     * read). Frames A in front of B combine with the over operator,
     * A + (1 - A.a) B, and a background last: rgb + (1 - a) bg. */
    OIT_PIXELS_PREMUL32F = 2
} oit_pixel_format;

typedef struct oit_offscreen_view {
    int width, height; /* pixels; required, each 1..the GL limit */
    oit_pixel_format format;
    /* The camera, in the scene's coordinates (its positions, which are
     * relative to oit_scene_info.origin). One of:
     * - use_matrices = 1: view and projection as oit_frame takes them
     *   (rigid view; a perspective, symmetric, off-centre or with an
     *   infinite far plane, or an orthographic projection: liboit.h);
     * - eye != target: a look-at camera; up 0: +y; fovy_deg 0: 45;
     *   znear = zfar = 0: planes fitted to the scene's bounding sphere seen
     *   from eye;
     * - eye = target = 0: the tools' default view (the scene's bounds
     *   seen from azimuth 0, elevation 20, fovy 45, the bounding sphere
     *   filling the height), turned about up when
     *   it is given (+x, +y or +z, any length, as the tools' up axis; any
     *   other direction is OIT_ERR_ARGUMENT), else about the scene's own
     *   (oit_scene_info.up_axis: z for a STEP file), fovy_deg moving the eye so
     *   the sphere still fills the height, znear/zfar replacing the fitted
     *   planes when given. oit_offscreen_default_view gives the other
     *   azimuths and elevations. */
    int use_matrices;
    float view[16], projection[16];
    float eye[3], target[3], up[3];
    float fovy_deg, znear, zfar;
    /* Straight RGBA the scene is composited over, rgb sRGB-encoded (decoded
     * to linear light when desc's shading.colour_space is
     * OIT_RENDER_COLOUR_LINEAR). All 0 (default): opaque
     * white, the tools' background. A negative component stands for 0, so
     * {-1, -1, -1, -1} is transparent black. */
    float background[4];
    /* Section planes in the scene's coordinates, as oit_frame.clip_count
     * and oit_frame.clip take them (liboit.h); 0: none. */
    uint32_t clip_count;
    float clip[6][4];
} oit_offscreen_view;

/* The up axis of oit_offscreen_default_view, in the order the viewer's U
 * key steps through them; zero is the tools' default, y. */
typedef enum oit_up_axis {
    OIT_UP_Y = 0,
    OIT_UP_Z = 1, /* CAD models: seen from -y, x to the right */
    OIT_UP_X = 2
} oit_up_axis;

/* Sets view's camera (eye, target, up, fovy_deg 45, znear, zfar fitted to
 * the bounding sphere; use_matrices 0) to the view the tools take of
 * scene's bounds for an up axis, azimuth and elevation;
 * width, height, format and background are left as they are. azimuth:
 * any finite angle (0: the eye on the +z side for y or x up, on the -y
 * side for z up; 90 a quarter turn to the right); elevation in [-90, 90]
 * (the tools' default is 20). */
OIT_API oit_status oit_offscreen_default_view(const oit_scene *scene, oit_up_axis up,
                                              float azimuth_deg, float elevation_deg,
                                              oit_offscreen_view *view, oit_error *err);

/* Renders scene into pixels: width * height pixels of 4 components (format),
 * colour sRGB-encoded in both colour spaces (in OIT_RENDER_COLOUR_LINEAR the
 * linear result is encoded with the exact sRGB OETF before it is returned;
 * alpha is never converted),
 * row 0 at the TOP (image order, unlike GL), pixels_bytes the buffer's size
 * (at least width * height * 4 * component size, else OIT_ERR_ARGUMENT).
 * stats may be NULL (see oit_renderer_draw). Errors name the scene or the
 * field of view that is wrong. A method that draws images only
 * (oit_renderer_desc.method other than stream and dfb) renders through
 * oit_renderer_draw_image: RGBA8 and RGBA32F over an opaque background
 * (alpha 1), else OIT_ERR_UNSUPPORTED. */
OIT_API oit_status oit_offscreen_render(oit_offscreen *o, oit_scene *scene,
                                        const oit_offscreen_view *view, void *pixels,
                                        size_t pixels_bytes, oit_draw_stats *stats, oit_error *err);

/* The layers of pixel (x, y) of view (y = 0 the top row, as the rendered
 * image's): oit_renderer_pick (liboit.h) on view's camera and section
 * planes. Needs no GL; renders nothing. */
OIT_API oit_status oit_offscreen_pick(oit_offscreen *o, oit_scene *scene,
                                      const oit_offscreen_view *view, int x, int y,
                                      oit_pick_layer *layers, size_t capacity, size_t *count,
                                      oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
