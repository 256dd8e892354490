/* A pixel's index within the GL rect r (exclusive ends): the first-K
 * capture's slots and pass-2 table cover their rectangle, not the frame,
 * so that they scale with what a pack covers. */
uint oit_rect_index(ivec2 px, ivec4 r) {
    return uint((px.y - r.y) * (r.z - r.x) + (px.x - r.x));
}
