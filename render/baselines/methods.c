/* The baselines' method tables (methods.h). Every baseline has the same
 * typed API (oit_X_create, oit_X_destroy, oit_X_render over GPU meshes),
 * so one macro adapts each to render/method.h instead of a hand-written
 * wrapper per method; adding a baseline is one line here. */
#include "render/baselines/methods.h"

#include "render/baselines/b3d.h"
#include "render/baselines/depth_peel.h"
#include "render/baselines/dual_peel.h"
#include "render/baselines/f2b.h"
#include "render/baselines/guarded.h"
#include "render/baselines/ppll.h"
#include "render/baselines/ppll4.h"
#include "render/baselines/unsorted.h"
#include "render/baselines/wboit.h"

/* The thresholded baselines take opt->epsilon when it is >= 0. */
#define NO_THRESHOLD(T, impl, opt, err) OIT_OK
#define THRESHOLD(T, impl, opt, err)                                                        \
    (opt && opt->epsilon >= 0.0f ? T##_set_threshold(impl, opt->epsilon, err) : OIT_OK)

#define BASELINE(method, T, FLAGS, SET)                                                     \
    static oit_status method##_create(const oit_mesh *mesh, const oit_method_options *opt,  \
                                      void **impl, oit_error *err)                          \
    {                                                                                       \
        T *p = NULL;                                                                        \
        oit_status s = T##_create(&p, err);                                                 \
        if (s == OIT_OK && (s = SET(T, p, opt, err)) != OIT_OK) {                           \
            T##_destroy(p);                                                                 \
            p = NULL;                                                                       \
        }                                                                                   \
        *impl = p;                                                                          \
        return s;                                                                           \
    }                                                                                       \
    static oit_status method##_render(void *impl, const oit_method_frame *f, oit_error *err) \
    {                                                                                       \
        return T##_render(impl, &f->gpu, 1, f->view, f->out, f->stats, err);                \
    }                                                                                       \
    static void method##_destroy(void *impl) { T##_destroy(impl); }                         \
    const oit_method oit_method_##method = {.name = #method,                                \
                                            .flags = OIT_METHOD_GL | (FLAGS),               \
                                            .create = method##_create,                      \
                                            .render = method##_render,                      \
                                            .destroy = method##_destroy}

BASELINE(unsorted, oit_unsorted, 0, NO_THRESHOLD);
BASELINE(wboit, oit_wboit, 0, NO_THRESHOLD);
BASELINE(pll, oit_pll, 0, NO_THRESHOLD);
BASELINE(dp, oit_depth_peel, 0, NO_THRESHOLD);
BASELINE(ppll4, oit_ppll4, 0, NO_THRESHOLD);
BASELINE(b3d, oit_b3d, 0, NO_THRESHOLD);
BASELINE(ddp, oit_dual_peel, 0, NO_THRESHOLD);
BASELINE(guarded, oit_guarded, OIT_METHOD_EPSILON, THRESHOLD);
BASELINE(f2b, oit_f2b, OIT_METHOD_EPSILON, THRESHOLD);
