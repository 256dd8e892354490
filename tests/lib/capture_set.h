/* One setting of a capture changed between frames, the rest kept:
 * CAPTURE_SET(c, store_limit, 8 << 10) for the tests that drive a setting
 * on a capture they keep (oit_capture_apply, view/render/capture/capture.h);
 * and the tests' backends as the capture's two axes (capture.h's table):
 * {.fill = capture_fill(k), .cut = capture_cut(k)}. */
#ifndef OIT_TESTS_LIB_CAPTURE_SET_H
#define OIT_TESTS_LIB_CAPTURE_SET_H

#include "view/render/capture/capture.h"

#define CAPTURE_SET(c, field, value)                                    \
    do {                                                                \
        oit_capture_settings capture_set_ = oit_capture_get_settings(c); \
        capture_set_.field = (value);                                   \
        oit_capture_apply((c), &capture_set_);                          \
    } while (0)

static inline oit_render_capture capture_fill(oit_capture_kind k)
{
    return k == OIT_CAPTURE_STENCIL   ? OIT_RENDER_CAPTURE_STENCIL
           : k == OIT_CAPTURE_COMPUTE ? OIT_RENDER_CAPTURE_COMPUTE
           : k == OIT_CAPTURE_AUTO    ? OIT_RENDER_CAPTURE_AUTO
                                      : OIT_RENDER_CAPTURE_ARRAY;
}

static inline oit_render_pack capture_cut(oit_capture_kind k)
{
    return k == OIT_CAPTURE_COUNTED  ? OIT_RENDER_PACK_COUNTED
           : k == OIT_CAPTURE_FIRSTK ? OIT_RENDER_PACK_FIRSTK
                                     : OIT_RENDER_PACK_BUDGET;
}

#endif
