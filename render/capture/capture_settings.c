/* The caller's settings of a capture (oit_capture_set_*, capture.h), each
 * taken from the next frame or batch on, and what a frame leaves for its
 * caller to ask (its waits, whether it ended short). */
#include "render/capture/capture_backend.h"

void oit_capture_set_first_k(oit_capture *c, int on)
{
    if (c->ops->first_k)
        c->ops->first_k(c, on);
}

void oit_capture_set_store_limit(oit_capture *c, uint64_t bytes)
{
    c->set.store_limit = bytes;
}

void oit_capture_set_no_wait(oit_capture *c, int on)
{
    c->set.no_wait = on != 0;
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

void oit_capture_set_slot_budget(oit_capture *c, uint64_t bytes)
{
    c->set.slot_budget = bytes;
}

void oit_capture_set_store_budget(oit_capture *c, uint64_t bytes)
{
    c->set.store_budget = bytes;
}

uint64_t oit_capture_store_budget(const oit_capture *c)
{
    return c->set.store_budget ? c->set.store_budget : c->set.slot_budget;
}

void oit_capture_set_keep_counts(oit_capture *c, int on)
{
    c->set.no_counts = !on;
}

void oit_capture_set_gpu_timer(oit_capture *c, struct oit_gpu_timer *t)
{
    c->set.timer = t;
}

oit_host_waits *oit_capture_host_waits(oit_capture *c)
{
    return &c->frame.waits;
}
