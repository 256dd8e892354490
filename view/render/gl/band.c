/* Bands of rows (band.h). */
#include "view/render/gl/band.h"

#include "view/render/gl/gl_util.h"

#include <string.h>

oit_status oit_band_rows(const oit_view *v, uint64_t pixel_bytes, uint64_t limit, int *rows,
                         oit_error *err)
{
    GLint fb_w = 0, fb_h = 0, dims[2] = {0, 0};
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &fb_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &fb_h);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    int most_w = fb_w < dims[0] ? fb_w : dims[0], most_h = fb_h < dims[1] ? fb_h : dims[1];
    *rows = 0;
    if (v->width <= 0 || v->height <= 0 || v->width > most_w)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "frame %dx%d: not renderable here (at most "
                             "%d pixels wide: GL_MAX_FRAMEBUFFER_WIDTH %d, "
                             "GL_MAX_VIEWPORT_DIMS %d)",
                             v->width, v->height, most_w, fb_w, dims[0]);
    uint64_t fit = (uint64_t)(most_h > 0 ? most_h : 1);
    if (pixel_bytes) {
        uint64_t driver = oit_gl_ssbo_max_bytes();
        uint64_t bind = limit && limit < driver ? limit : driver;
        uint64_t row = (uint64_t)v->width * pixel_bytes;
        if (row > bind)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "frame %dx%d: one row takes %llu bytes "
                                 "in one storage buffer, more than this driver binds (%llu)",
                                 v->width, v->height, (unsigned long long)row,
                                 (unsigned long long)bind);
        fit = bind / row < fit ? bind / row : fit;
    }
    /* Bands of one height (the last no shorter than the others but by
     * rounding): as few as fit, none a sliver. */
    uint64_t bands = ((uint64_t)v->height + fit - 1) / fit;
    *rows = (int)(((uint64_t)v->height + bands - 1) / bands);
    return OIT_OK;
}

void oit_view_band(const oit_view *full, int y0, int y1, oit_view *band)
{
    *band = *full;
    double w[4];
    oit_camera_window(&full->camera, (double)full->width / full->height, w);
    /* Row y's top edge, row 0 at the top, lies (t - b) * y / height below t. */
    double step = (w[3] - w[2]) / full->height;
    band->camera.window[0] = (float)w[0];
    band->camera.window[1] = (float)w[1];
    band->camera.window[2] = (float)(w[3] - step * y1);
    band->camera.window[3] = (float)(w[3] - step * y0);
    band->height = y1 - y0;
}

void oit_band_projection(const float p[16], int height, int y0, int y1, float out[16])
{
    memcpy(out, p, 16 * sizeof *out);
    /* y_band = y * H / rows + w * (H - 2 g0 - rows) / rows, g0 the band's
     * first GL row (bottom first): the band's rows map onto [-1, 1]. */
    double rows = y1 - y0, g0 = height - y1;
    double scale = height / rows, shift = (height - 2.0 * g0 - rows) / rows;
    for (int c = 0; c < 4; c++)
        out[c * 4 + 1] = (float)(scale * p[c * 4 + 1] + shift * p[c * 4 + 3]);
}

void oit_frame_stats_add(oit_frame_stats *acc, const oit_frame_stats *band)
{
    acc->fragments += band->fragments;
    acc->max_layers = band->max_layers > acc->max_layers ? band->max_layers : acc->max_layers;
    acc->overflow_pixels += band->overflow_pixels;
    acc->gpu_bytes_peak =
        band->gpu_bytes_peak > acc->gpu_bytes_peak ? band->gpu_bytes_peak : acc->gpu_bytes_peak;
    acc->gpu_mesh_bytes =
        band->gpu_mesh_bytes > acc->gpu_mesh_bytes ? band->gpu_mesh_bytes : acc->gpu_mesh_bytes;
    acc->batches += band->batches;
    acc->second_pass_pixels += band->second_pass_pixels;
    acc->second_pass_packs += band->second_pass_packs;
    acc->deep_pixels += band->deep_pixels;
    acc->predicted_batches += band->predicted_batches;
    acc->host_waits += band->host_waits;
    acc->redraws += band->redraws;
    acc->fragments_saturated += band->fragments_saturated;
    if (band->capture) {
        acc->capture = band->capture;
        acc->capture_k = band->capture_k;
    }
    if (band->capture_slots) {
        acc->capture_slots = band->capture_slots;
        acc->capture_slots_k = band->capture_slots_k;
    }
}
