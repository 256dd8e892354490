/* oit_streamer_desc's one range check (streamer.h): its caller (liboit)
 * maps its settings onto the fields and lets this check them, so a range
 * is written once and an error names the caller's spelling. */
#include "view/stream/streamer.h"

#include <inttypes.h>
#include <stdio.h>

oit_streamer_names oit_streamer_names_resolve(const oit_streamer_names *names)
{
    oit_streamer_names n = names ? *names : (oit_streamer_names){0};
#define OWN(f) n.f = n.f ? n.f : "oit_streamer_desc." #f
    OWN(upload_budget);
    OWN(slot_budget);
    OWN(cache_budget);
    OWN(gpu_budget);
    OWN(epsilon);
    OWN(pack);
    OWN(schedule);
    OWN(store_budget);
    OWN(capture);
#undef OWN
    n.cache_off = n.cache_off ? n.cache_off : "OIT_STREAM_CACHE_OFF";
    return n;
}

/* 0 (the default) or a byte count in [lo, OIT_STREAM_BUDGET_MAX]. */
static oit_status check_bytes(uint64_t v, uint64_t lo, const char *name, const char *extra,
                              oit_error *err)
{
    if (v == 0 || (v >= lo && v <= OIT_STREAM_BUDGET_MAX))
        return OIT_OK;
    int mib = lo % (1u << 20) == 0;
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %" PRIu64 ": expected 0 (the default)%s or "
                         "%" PRIu64 "..%" PRIu64 " bytes (%" PRIu64 "%c..1T)", name, v, extra, lo,
                         (uint64_t)OIT_STREAM_BUDGET_MAX, lo >> (mib ? 20 : 10), mib ? 'M' : 'K');
}

oit_status oit_streamer_desc_check(const oit_streamer_desc *d, oit_error *err)
{
    const oit_streamer_names n = oit_streamer_names_resolve(d->names);
    char off[96];
    snprintf(off, sizeof off, ", %s (no cache)", n.cache_off);
    oit_status s = check_bytes(d->upload_budget, OIT_STREAM_BUDGET_MIN, n.upload_budget, "", err);
    if (s == OIT_OK)
        s = check_bytes(d->slot_budget, OIT_STREAM_BUDGET_MIN, n.slot_budget, "", err);
    if (s == OIT_OK)
        s = check_bytes(d->store_budget, OIT_STREAM_BUDGET_MIN, n.store_budget, "", err);
    if (s == OIT_OK && d->cache_budget != OIT_STREAM_CACHE_OFF)
        s = check_bytes(d->cache_budget, OIT_STREAM_BUDGET_MIN, n.cache_budget, off, err);
    if (s == OIT_OK)
        s = check_bytes(d->gpu_budget, OIT_STREAM_GPU_BUDGET_MIN, n.gpu_budget, "", err);
    if (s != OIT_OK)
        return s;
    /* written so that NaN fails too */
    if (!(d->epsilon >= 0.0f && d->epsilon < 1.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %g: expected a transmittance in [0, 1) "
                             "(0: exact)", n.epsilon, (double)d->epsilon);
    if ((unsigned)d->pack > (unsigned)OIT_RENDER_PACK_FIRSTK)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not an oit_render_pack", n.pack,
                             (int)d->pack);
    if ((unsigned)d->schedule > (unsigned)OIT_RENDER_SCHEDULE_WAVE)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not an oit_render_schedule",
                             n.schedule, (int)d->schedule);
    /* Asked for together, first-k would silently run as counted: its
     * first pass is a K-slot fill, which compute does not make. */
    if (d->capture == OIT_RENDER_CAPTURE_COMPUTE && d->pack == OIT_RENDER_PACK_FIRSTK)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = compute and %s = first-k: the "
                             "compute capture has no K-slot fill for first-k's first pass "
                             "(its packs would be counted's); take %s = counted or auto with "
                             "it, or another capture with first-k", n.capture, n.pack, n.pack);
    return OIT_OK;
}
