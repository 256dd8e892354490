/* oit_streamer_desc's one range check (streamer.h): every caller (oitstream,
 * oitstream-mpi, liboit) maps its spelling onto the fields and lets this
 * check them, so a range is written once and an error names the caller's
 * spelling. */
#include "stream/streamer.h"

#include <inttypes.h>
#include <stdio.h>

static const char *name_of(const char *given, const char *field)
{
    return given ? given : field;
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

oit_status oit_streamer_desc_check(const oit_streamer_desc *d, const oit_streamer_names *names,
                                   oit_error *err)
{
    static const oit_streamer_names none = {0};
    const oit_streamer_names *n = names ? names : &none;
    char off[96];
    snprintf(off, sizeof off, ", %s (no cache)", name_of(n->cache_off, "OIT_STREAM_CACHE_OFF"));
    oit_status s = check_bytes(d->upload_budget, OIT_STREAM_BUDGET_MIN,
                               name_of(n->upload_budget, "oit_streamer_desc.upload_budget"), "",
                               err);
    if (s == OIT_OK)
        s = check_bytes(d->slot_budget, OIT_STREAM_BUDGET_MIN,
                        name_of(n->slot_budget, "oit_streamer_desc.slot_budget"), "", err);
    if (s == OIT_OK)
        s = check_bytes(d->store_budget, OIT_STREAM_BUDGET_MIN,
                        name_of(n->store_budget, "oit_streamer_desc.store_budget"), "", err);
    if (s == OIT_OK && d->cache_budget != OIT_STREAM_CACHE_OFF)
        s = check_bytes(d->cache_budget, OIT_STREAM_BUDGET_MIN,
                        name_of(n->cache_budget, "oit_streamer_desc.cache_budget"), off, err);
    if (s == OIT_OK)
        s = check_bytes(d->gpu_budget, OIT_STREAM_GPU_BUDGET_MIN,
                        name_of(n->gpu_budget, "oit_streamer_desc.gpu_budget"), "", err);
    if (s != OIT_OK)
        return s;
    /* written so that NaN fails too */
    if (!(d->epsilon >= 0.0f && d->epsilon < 1.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %g: expected a transmittance in [0, 1) "
                             "(0: exact)", name_of(n->epsilon, "oit_streamer_desc.epsilon"),
                             (double)d->epsilon);
    if ((unsigned)d->pack > (unsigned)OIT_PACK_FIRSTK)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not an oit_pack_mode",
                             name_of(n->pack, "oit_streamer_desc.pack"), (int)d->pack);
    if ((unsigned)d->schedule > (unsigned)OIT_SCHEDULE_WAVE)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not an oit_pack_schedule",
                             name_of(n->schedule, "oit_streamer_desc.schedule"),
                             (int)d->schedule);
    return OIT_OK;
}
