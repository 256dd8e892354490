/* Text drawn into an image with a built-in 5x7 bitmap font, so the viewer's
 * status line and oitbench's charts need no font library and their figures
 * land in screenshots and PNG files alike. Everything is clipped at the
 * image's edges; nothing here allocates or fails. */
#ifndef OIT_PLOT_TEXT_OVERLAY_H
#define OIT_PLOT_TEXT_OVERLAY_H

#include "view/render/image/view.h"

/* Height in pixels of one status line at scale s (glyph 7 rows + margins). */
int oit_text_line_height(int scale);

/* Pixels a string spans along its baseline at scale s (6 per character,
 * less the last column's gap), and across it (7 rows and a descender row).
 * Scale < 1 counts as 1. */
int oit_text_width(const char *text, int scale);
int oit_text_height(int scale);

/* Darkens rows [0, oit_text_line_height(scale)) of img to a band and writes
 * text on it in white from the left, clipped at the right edge. Lower-case
 * letters draw as upper case; characters outside the font draw as '?'. */
void oit_text_status_line(oit_image *img, const char *text, int scale);

/* The status line of named fields ("layers 26", "frame 32 ms"), joined by
 * two spaces and wrapped between fields onto as many lines as the image's
 * width needs (a field wider than the image is cut at its edge), on one
 * dark band from row 0, in the same upper-case look. Returns the band's
 * height in rows (0 for no fields). */
int oit_text_status_fields(oit_image *img, const char *const *fields, int n, int scale);

/* An opaque box of colour rgb over [x, x+w) x [y, y+h), clipped. */
void oit_text_box(oit_image *img, int x, int y, int w, int h, const float rgb[3]);

/* Writes text in colour rgb (each in [0,1]) with its glyphs' top-left corner
 * at (x, y), every font pixel a scale x scale block; only the glyphs' own
 * pixels are set (no background). Lower-case letters have their own shapes
 * here; characters outside the font draw as '?'. */
void oit_text_draw(oit_image *img, int x, int y, const char *text, const float rgb[3],
                   int scale);

/* The same turned a quarter turn counter-clockwise, reading upwards (a
 * vertical axis label): (x, y) is the bottom-left corner of the text, which
 * spans oit_text_height across (x rightwards) and oit_text_width up. */
void oit_text_draw_up(oit_image *img, int x, int y, const char *text, const float rgb[3],
                      int scale);

#endif
