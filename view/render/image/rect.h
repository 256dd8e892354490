/* Screen rectangles as int[4] {x0, y0, x1, y1} with exclusive ends, as the
 * packer and the capture pass them around. */
#ifndef OIT_RENDER_RECT_H
#define OIT_RENDER_RECT_H

/* 1 when a and b share a pixel (an empty rectangle shares none). */
static inline int oit_rect_overlaps(const int a[4], const int b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* acc becomes the bounding box of acc and r. */
static inline void oit_rect_grow(int acc[4], const int r[4])
{
    acc[0] = r[0] < acc[0] ? r[0] : acc[0];
    acc[1] = r[1] < acc[1] ? r[1] : acc[1];
    acc[2] = r[2] > acc[2] ? r[2] : acc[2];
    acc[3] = r[3] > acc[3] ? r[3] : acc[3];
}

#endif
