/* The capture's K-slot fill, chosen (capture_choice.h). */
#include "view/render/capture/capture_choice.h"

#include <stdio.h>
#include <string.h>

/* The next sample count to try after k: the largest power of two below
 * it (sample counts GL offers), 0 when none is left. */
static int next_try(int k)
{
    int p = 1;
    while (p * 2 < k)
        p *= 2;
    return p >= 2 ? p : 0;
}

/* AUTO keeps the caller's K and takes the array backend where stencil
 * routing is refused; STENCIL refuses with the reason: the caller asked for
 * that method, and a lower K would lose fragments (an inexact image). The
 * refusal is the driver's limit, not the caller's input: OIT_ERR_GL, as a
 * feature the driver lacks (the tools' runtime failure, exit 1). */
oit_status oit_capture_choose(oit_render_capture asked, const char *what, int K, int fewer_ok,
                              oit_capture_try try_stencil, void *ctx, oit_capture_choice *out,
                              oit_error *err)
{
    what = what ? what : "capture";
    memset(out, 0, sizeof *out);
    out->asked = asked;
    out->slots = OIT_RENDER_CAPTURE_ARRAY;
    if (asked != OIT_RENDER_CAPTURE_AUTO && asked != OIT_RENDER_CAPTURE_ARRAY &&
        asked != OIT_RENDER_CAPTURE_STENCIL)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not auto, stencil or array", what,
                             (int)asked);
    oit_status k = oit_capture_k_check(K, NULL, err);
    if (k != OIT_OK)
        return k;
    if (asked == OIT_RENDER_CAPTURE_ARRAY)
        return OIT_OK;
    for (int k = K; k >= 2; k = fewer_ok ? next_try(k) : 0) {
        oit_error why = {0};
        oit_status s = try_stencil(ctx, k, &why);
        if (s == OIT_OK) {
            out->slots = OIT_RENDER_CAPTURE_STENCIL;
            out->stencil_k = k;
            return OIT_OK;
        }
        if (s != OIT_ERR_UNSUPPORTED) {
            if (err)
                *err = why;
            return s;
        }
        if (k == K)
            snprintf(out->reason, sizeof out->reason, "%s", why.message);
    }
    if (asked == OIT_RENDER_CAPTURE_STENCIL)
        return oit_error_set(err, OIT_ERR_GL, "%s = stencil at K=%d%s: %s", what, K,
                             fewer_ok && K > 2 ? " (nor fewer samples)" : "", out->reason);
    return OIT_OK;
}

const char *oit_capture_asked_name(oit_render_capture asked)
{
    switch (asked) {
    case OIT_RENDER_CAPTURE_AUTO: return "auto";
    case OIT_RENDER_CAPTURE_ARRAY: return "array";
    case OIT_RENDER_CAPTURE_STENCIL: return "stencil";
    case OIT_RENDER_CAPTURE_COMPUTE: return "compute";
    }
    return NULL;
}

oit_status oit_capture_k_check(long long K, const char *what, oit_error *err)
{
    if (K >= OIT_CAPTURE_K_MIN && K <= OIT_CAPTURE_K_MAX)
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %lld is outside [%d, %d]",
                         what ? what : "capture: K", K, OIT_CAPTURE_K_MIN, OIT_CAPTURE_K_MAX);
}
