/* One setting of a capture changed between frames, the rest kept:
 * CAPTURE_SET(c, store_limit, 8 << 10) for the tests that drive a setting
 * on a capture they keep (oit_capture_apply, render/capture/capture.h). */
#ifndef OIT_TESTS_LIB_CAPTURE_SET_H
#define OIT_TESTS_LIB_CAPTURE_SET_H

#include "render/capture/capture.h"

#define CAPTURE_SET(c, field, value)                                    \
    do {                                                                \
        oit_capture_settings capture_set_ = oit_capture_get_settings(c); \
        capture_set_.field = (value);                                   \
        oit_capture_apply((c), &capture_set_);                          \
    } while (0)

#endif
