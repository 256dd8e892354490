/* A status line drawn into an image with a built-in 5x7 bitmap font, so the
 * viewer needs no font library and its figures land in screenshots too. */
#ifndef OIT_STREAM_TEXT_OVERLAY_H
#define OIT_STREAM_TEXT_OVERLAY_H

#include "render/view.h"

/* Height in pixels of one text line at scale s (glyph 7 rows + margins). */
int oit_text_line_height(int scale);

/* Darkens rows [0, oit_text_line_height(scale)) of img to a band and writes
 * text on it in white from the left, clipped at the right edge. Lower-case
 * letters draw as upper case; characters outside the font draw as '?'. */
void oit_text_status_line(oit_image *img, const char *text, int scale);

#endif
