/* Wide batches: u_W slots a pixel of the tile u_tile (fill.glsl), so that
 * a part with more than K layers fits the same slots buffer over fewer
 * pixels. */
uniform int u_W;
#define OIT_FILL_SLOTS u_W
