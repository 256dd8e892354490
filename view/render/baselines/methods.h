/* The baselines as method tables (view/render/method.h): the approximate ones
 * (unsorted, wboit, ppll4, guarded, f2b) and the exact ones the papers
 * compare against (pll, dp, ddp, b3d). Each table's name is the one the
 * tools take for a method; each is defined at the end of its baseline's
 * file. */
#ifndef OIT_RENDER_BASELINES_METHODS_H
#define OIT_RENDER_BASELINES_METHODS_H

#include "view/render/baselines/baseline_common.h"
#include "view/render/method.h"

#include <stdlib.h>

extern const oit_method oit_method_unsorted;
extern const oit_method oit_method_wboit;
extern const oit_method oit_method_pll;
extern const oit_method oit_method_dp;
extern const oit_method oit_method_ppll4;
extern const oit_method oit_method_b3d;
extern const oit_method oit_method_ddp;
extern const oit_method oit_method_guarded;
extern const oit_method oit_method_f2b;

/* Defines `const oit_method oit_method_NAME` from a baseline's typed
 * functions, so that each baseline file ends with its table in one line
 * and none repeats the object's life or the frame around its passes:
 *   oit_status INIT(T *self, oit_error *err)  self is zeroed memory;
 *       makes what the method keeps between frames
 *   void RELEASE(T *self)  deletes what INIT and the frames made (also
 *       after a failed INIT); the table frees self
 *   oit_status RENDER(T *self, const oit_gpu_mesh *const *meshes, int n,
 *                     const oit_view *v, oit_image *out,
 *                     oit_frame_stats *stats, oit_error *err)
 *       one frame; v is renderable here and has its shading defaults
 *       resolved (oit_baseline_begin); out is allocated by the call; fills
 *       stats' fragments, max_layers, gpu_bytes_peak and batches (the
 *       table adds the time; the rest stay 0)
 * OIT_BASELINE_METHOD takes them as T_init, T_release and T_render. LABEL
 * names the method in errors ("depth peeling"). SET is OIT_NO_THRESHOLD,
 * or OIT_THRESHOLD for a baseline with a T_set_threshold that takes
 * oit_method_options.threshold when one is given (INIT sets its default).
 * OIT_BASELINE_METHOD_FRAMED adds FRAME(impl, f), run before each RENDER
 * with the method's frame: what a baseline takes from it beyond the view
 * (the list stores: the storage limit and the request to split,
 * list_store.h); OIT_NO_FRAME takes nothing. Every baseline's frames are
 * banded for OIT_BASELINE_PIXEL_BYTES a pixel (view/render/gl/band.h). */
#define OIT_NO_THRESHOLD(T, impl, opt, err) OIT_OK
#define OIT_THRESHOLD(T, impl, opt, err)                                                    \
    ((opt) && (opt)->threshold ? T##_set_threshold(impl, *(opt)->threshold, err) : OIT_OK)
#define OIT_BASELINE_METHOD(NAME, T, LABEL, FLAGS, SET)                                     \
    OIT_BASELINE_METHOD_OF(NAME, T, LABEL, T##_init, T##_release, T##_render, FLAGS, SET)
#define OIT_NO_FRAME(impl, f) ((void)0)
#define OIT_BASELINE_METHOD_OF(NAME, T, LABEL, INIT, RELEASE, RENDER, FLAGS, SET)           \
    OIT_BASELINE_METHOD_FRAMED(NAME, T, LABEL, INIT, RELEASE, RENDER, OIT_NO_FRAME, FLAGS, SET)
#define OIT_BASELINE_METHOD_FRAMED(NAME, T, LABEL, INIT, RELEASE, RENDER, FRAME, FLAGS, SET) \
    static void NAME##_method_destroy(void *impl)                                           \
    {                                                                                       \
        if (impl)                                                                           \
            RELEASE((T *)impl);                                                             \
        free(impl);                                                                         \
    }                                                                                       \
    static oit_status NAME##_method_create(const oit_mesh *mesh,                           \
                                           const oit_method_options *opt, void **impl,     \
                                           oit_error *err)                                 \
    {                                                                                       \
        T *p = calloc(1, sizeof *p);                                                        \
        oit_status s = p ? INIT(p, err)                                                     \
                         : oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", LABEL);   \
        if (s == OIT_OK)                                                                    \
            s = SET(T, p, opt, err);                                                        \
        if (s != OIT_OK) {                                                                  \
            NAME##_method_destroy(p);                                                       \
            p = NULL;                                                                       \
        }                                                                                   \
        *impl = p;                                                                          \
        return s;                                                                           \
    }                                                                                       \
    static oit_status NAME##_method_render(void *impl, const oit_method_frame *f,          \
                                           oit_error *err)                                 \
    {                                                                                       \
        oit_baseline_frame fr;                                                              \
        oit_status s = oit_baseline_begin(LABEL, f->view, 1, &fr, err);                     \
        FRAME((T *)impl, f);                                                                \
        if (s == OIT_OK)                                                                    \
            s = RENDER((T *)impl, &f->gpu, 1, &fr.view, f->out, &fr.stats, err);            \
        return oit_baseline_end(&fr, f->stats, s);                                          \
    }                                                                                       \
    const oit_method oit_method_##NAME = {.name = #NAME,                                    \
                                          .flags = OIT_RENDER_METHOD_GL | OIT_RENDER_METHOD_CLIP | (FLAGS), \
                                          .create = NAME##_method_create,                   \
                                          .render = NAME##_method_render,                   \
                                          .destroy = NAME##_method_destroy,                 \
                                          .pixel_bytes = oit_baseline_pixel_bytes}

#endif
