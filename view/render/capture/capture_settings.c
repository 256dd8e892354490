/* The caller's settings of a capture (oit_capture_settings, capture.h),
 * each taken from the next frame or batch on, and what a frame leaves for
 * its caller to ask (its waits, whether it ended short). */
#include "view/render/capture/capture_backend.h"

oit_capture_settings oit_capture_get_settings(const oit_capture *c)
{
    return c->set;
}

void oit_capture_apply(oit_capture *c, const oit_capture_settings *settings)
{
    float was = c->set.epsilon;
    c->set = *settings;
    c->set.epsilon = settings->epsilon > 0.0f ? settings->epsilon : 0.0f;
    c->set.no_wait = settings->no_wait != 0;
    c->set.no_counts = settings->no_counts != 0;
    if (c->set.epsilon != was)
        oit_capture_apply_epsilon(c);
}

void oit_capture_set_first_k(oit_capture *c, int on)
{
    if (c->ops->first_k)
        c->ops->first_k(c, on);
}

void oit_capture_ready_counted(oit_capture *c)
{
    if (c->ops->ready_counted && !c->frame.in_frame)
        c->ops->ready_counted(c);
}

int oit_capture_short(const oit_capture *c)
{
    return c->ended_short;
}

uint64_t oit_capture_store_budget(const oit_capture *c)
{
    return c->set.store_budget ? c->set.store_budget : c->set.slot_budget;
}

oit_host_waits *oit_capture_host_waits(oit_capture *c)
{
    return &c->frame.waits;
}
