/* The baselines as method tables (render/method.h): the approximate ones
 * (unsorted, wboit, ppll4, guarded, f2b) and the exact ones the papers
 * compare against (pll, dp, ddp, b3d). Each table's name is the one the
 * tools take after --method; each is defined at the end of its baseline's
 * file. */
#ifndef OIT_RENDER_BASELINES_METHODS_H
#define OIT_RENDER_BASELINES_METHODS_H

#include "render/method.h"

extern const oit_method oit_method_unsorted;
extern const oit_method oit_method_wboit;
extern const oit_method oit_method_pll;
extern const oit_method oit_method_dp;
extern const oit_method oit_method_ppll4;
extern const oit_method oit_method_b3d;
extern const oit_method oit_method_ddp;
extern const oit_method oit_method_guarded;
extern const oit_method oit_method_f2b;

/* Defines `const oit_method oit_method_NAME` from a baseline's typed API
 * (static T_create(T **, oit_error *), T_destroy(T *), T_render(T *, const
 * oit_gpu_mesh *const *, int, view, out, stats, err)), so that each
 * baseline file ends with its table in one line instead of a hand-written
 * adapter. SET is OIT_NO_THRESHOLD, or OIT_THRESHOLD for a baseline with a
 * T_set_threshold that takes oit_method_options.epsilon when it is >= 0. */
#define OIT_NO_THRESHOLD(T, impl, opt, err) OIT_OK
#define OIT_THRESHOLD(T, impl, opt, err)                                                    \
    ((opt) && (opt)->epsilon >= 0.0f ? T##_set_threshold(impl, (opt)->epsilon, err) : OIT_OK)
#define OIT_BASELINE_METHOD(NAME, T, FLAGS, SET)                                            \
    static oit_status NAME##_method_create(const oit_mesh *mesh,                           \
                                           const oit_method_options *opt, void **impl,     \
                                           oit_error *err)                                 \
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
    static oit_status NAME##_method_render(void *impl, const oit_method_frame *f,          \
                                           oit_error *err)                                 \
    {                                                                                       \
        return T##_render(impl, &f->gpu, 1, f->view, f->out, f->stats, err);                \
    }                                                                                       \
    static void NAME##_method_destroy(void *impl) { T##_destroy(impl); }                    \
    const oit_method oit_method_##NAME = {.name = #NAME,                                    \
                                          .flags = OIT_METHOD_GL | (FLAGS),                 \
                                          .create = NAME##_method_create,                   \
                                          .render = NAME##_method_render,                   \
                                          .destroy = NAME##_method_destroy}

#endif
