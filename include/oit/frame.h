/* What one draw sees (oit_frame: the caller's matrices or a look-at
 * camera, the viewport, the target, the opaque depth, the model matrix and
 * the section planes): a plain struct, included by oit/liboit.h, which
 * documents the calls that take it. */
#ifndef OIT_FRAME_H
#define OIT_FRAME_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_frame {
    /* Column-major 4x4, as glUniformMatrix4fv(..., GL_FALSE, m) takes.
     * view: a rigid world-to-eye transform (rotation and translation; no
     * scale: that belongs in model).
     * projection, classified from the matrix (m[i] = column i / 4, row
     * i % 4); m[1], m[2], m[3], m[4], m[6], m[7] must be 0, m[0], m[5] > 0:
     * - perspective: m[11] = -1, m[15] = 0, m[12] = m[13] = 0 (glFrustum,
     *   gluPerspective, glm::perspective / frustum / infinitePerspective).
     *   Off-centre (stereo, tiles) through m[8], m[9]; the aspect need not
     *   match the viewport's. Far plane finite (0 < near < far, from m[10],
     *   m[14]) or infinite: m[10] = -1 exactly, m[14] = -2 near.
     * - orthographic: m[11] = 0, m[15] = 1, m[8] = m[9] = 0 (glOrtho,
     *   glm::ortho): any window (m[0], m[5], m[12], m[13]), near < far, both
     *   finite, near may be <= 0.
     * Anything else (reversed or [0,1] depth, oblique, skewed) is
     * OIT_ERR_UNSUPPORTED, with the entries seen in the message. */
    float view[16];
    float projection[16];
    int viewport_x, viewport_y; /* lower-left corner in the target, pixels */
    int viewport_width, viewport_height;
    unsigned framebuffer;       /* GL framebuffer name; 0: the default one */
    /* The caller's opaque depth: the GL name of a single-sample
     * GL_TEXTURE_2D depth texture (a depth or depth-stencil format, level
     * 0, GL_DEPTH_STENCIL_TEXTURE_MODE left at GL_DEPTH_COMPONENT) of the
     * TARGET's size: texel (x, y) is the target's pixel (x, y), and it must
     * cover the viewport (else OIT_ERR_ARGUMENT). 0 (default): none.
     * Transparent fragments whose window depth is >= the texel under them
     * are dropped before they are stored or counted (streamed and in-core
     * scenes alike), so the result is the transparent scene composited
     * over the caller's opaque geometry as if that geometry were part of
     * it. Window depth is gl_FragCoord.z of `projection` applied to the
     * eye-space position (liboit then uses `projection` itself as its
     * projection), with the default glDepthRange(0, 1) and
     * glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE) assumed; a
     * transparent surface within rounding (about 1e-6 of the depth range,
     * the caller's own depth test alike) of an opaque one may go either
     * way. liboit only reads the texture, through a sampler object of its
     * own (nearest, no depth compare), so its filtering and compare mode do
     * not matter; it may be the depth attachment of `framebuffer`. A part
     * file's draw reads back the texture's largest depth per 16x16 tile at
     * its start (so waits for the caller's opaque pass) to skip parts
     * wholly behind it (oit_draw_stats.parts_skipped). */
    unsigned depth_texture;
    /* Model to world, column-major like view; all 16 zero: the identity.
     * Affine (m[3] = m[7] = m[11] = 0, m[15] = 1), finite, with an
     * invertible linear part: rotation, translation and uniform or
     * non-uniform scale (a mirror too). It is applied to the vertices on the
     * GPU before the tie rule, so the image is that of vertices transformed
     * beforehand (in float), and the streamer culls and orders parts
     * through it; anything else is OIT_ERR_UNSUPPORTED. */
    float model[16];
    /* Section planes, 0..OIT_FRAME_CLIP_MAX (0, default: none). Plane i,
     * clip[i] = (a, b, c, d) in world space (the space view maps to eye
     * space: the scene's coordinates, relative to oit_scene_info.origin,
     * after model), KEEPS the points where a x + b y + c z + d >= 0; a
     * fragment is drawn only when every plane keeps the point where its
     * pixel centre's ray meets its triangle (exact per pixel). A part
     * file's parts wholly cut away are neither read, uploaded nor drawn
     * (oit_draw_stats.parts_clipped). A count above OIT_FRAME_CLIP_MAX, a
     * number that is not finite or a zero normal (a, b, c) is
     * OIT_ERR_ARGUMENT. */
    uint32_t clip_count;
    float clip[6][4];
    /* NULL (default): the camera is view and projection. Else the camera
     * by its parameters, as the tools take it, and view and projection
     * are not read: no matrix stands between the caller's numbers and the
     * rasterizer's, so the image is bit for bit the one the tools render
     * of the same camera. */
    const struct oit_frame_camera *camera;
} oit_frame;

/* oit_frame.camera: a look-at camera. Perspective (ortho_height 0):
 * fovy_deg in (0, 180), 0 < znear < zfar, zfar INFINITY for an infinite far
 * plane. Orthographic (ortho_height > 0, the view volume's height):
 * znear < zfar, both finite, znear may be <= 0. window: an off-centre
 * window (left, right, bottom, top; at distance 1 for a perspective, in
 * eye units for an orthographic one); all 0: symmetric about the view
 * direction. up need not be orthogonal to the view direction, only not
 * parallel to it. Anything else is OIT_ERR_ARGUMENT naming the field. */
typedef struct oit_frame_camera {
    float eye[3], target[3], up[3];
    float fovy_deg, znear, zfar;
    float ortho_height;
    float window[4];
} oit_frame_camera;

#define OIT_FRAME_CLIP_MAX 6

#ifdef __cplusplus
}
#endif
#endif
