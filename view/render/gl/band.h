/* Frames larger than what one GL storage binding holds, rendered as bands
 * of rows: each band is a complete frame of width x rows whose camera is
 * the sub-window those rows cover (oit_camera.window, at the full frame's
 * aspect), so every method renders a band unchanged and the streamer culls
 * parts per band. A method's per-pixel state (its largest per-pixel storage
 * buffer) must sit in one binding, GL_MAX_SHADER_STORAGE_BLOCK_SIZE, which
 * the spec lets be 128 MiB: 20 bytes a pixel at 3840x2160 do not fit.
 *
 * view/render/method.c bands every method's frames with these; liboit bands its
 * GPU-resident frames itself, blending each band as it is done. Pixel
 * centres and depth keys stay where the full frame has them up to the
 * float rounding of the sub-window (the tie rule's key grid absorbs it but
 * where a near tie straddles a grid line). */
#ifndef OIT_RENDER_BAND_H
#define OIT_RENDER_BAND_H

#include <stdint.h>

#include "oit/status.h"
#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The most rows a band of v may have (*rows = v->height: one band takes
 * the whole frame): pixel_bytes a pixel times v->width times the rows
 * within `limit` bytes (0: this driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE,
 * read with glGetInteger64v), and within GL_MAX_FRAMEBUFFER_HEIGHT and
 * GL_MAX_VIEWPORT_DIMS. pixel_bytes 0: no per-pixel storage limit. Fails
 * with OIT_ERR_ARGUMENT naming the limit when v is too wide to render at
 * all (GL_MAX_FRAMEBUFFER_WIDTH, GL_MAX_VIEWPORT_DIMS) or one row does not
 * fit. Needs a current GL context. */
oit_status oit_band_rows(const oit_view *v, uint64_t pixel_bytes, uint64_t limit, int *rows,
                         oit_error *err);

/* *band: the view of rows [y0, y1) of full (row 0 at the top, y1 > y0): the
 * same camera, its window the part of full's that these rows cover, width
 * full->width, height y1 - y0. */
void oit_view_band(const oit_view *full, int y0, int y1, oit_view *band);

/* The GL-convention projection matrix p (column-major, a caller's, as
 * liboit takes it) of a frame `height` rows high narrowed to its rows
 * [y0, y1) (row 0 at the top): x and depth as p gives them, y stretched so
 * that those rows fill the clip volume. */
void oit_band_projection(const float p[16], int height, int y0, int y1, float out[16]);

/* acc takes a band's figures: counts add up (fragments, overflow,
 * batches, second-pass pixels and packs, saturated fragments), the most
 * layers and the GPU peak take the larger; ms is left to the caller, who
 * times the whole frame. */
void oit_frame_stats_add(oit_frame_stats *acc, const oit_frame_stats *band);

#ifdef __cplusplus
}
#endif
#endif
