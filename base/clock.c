#include "base/clock.h"

#include <time.h>

double oit_time_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double oit_time_s(void)
{
    return oit_time_ms() * 1e-3;
}
