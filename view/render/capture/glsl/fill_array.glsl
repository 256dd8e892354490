/* The array fill keeps K slots a pixel (fill.glsl). */
#define OIT_FILL_SLOTS u_K
